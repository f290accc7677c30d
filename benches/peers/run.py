"""Runs hatchery, VTK and pygfx on the shared MRI with hatchery's camera, interleaved round by
round, and prints the median frame times and ratios. See benches/peers/README.md.

    python run.py HATCHERY_BIN [ROUNDS] [FRAMES] [SIZE]
"""

import re
import statistics
import subprocess
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
root = here.parent.parent
hatchery = sys.argv[1]
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
frames = sys.argv[3] if len(sys.argv) > 3 else "5"
size = sys.argv[4] if len(sys.argv) > 4 else "512x512"
graph = root / "graphs" / "tf1d_phong_brain.ron"
volume = root.parent / "shared" / "data" / "volumes" / "mni152_t1.nii.gz"
camera = Path("/tmp") / "hatchery_peers_camera.json"
tf = re.search(r'"points": "([^"]*)"', graph.read_text()).group(1)

subprocess.run(
    [hatchery, "render", str(graph), "--size", size, "--dump", f"camera.camera={camera}",
     "-o", "/tmp/hatchery_peers_dvr.png"],
    check=True, capture_output=True)


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=root).stdout
    return out


times = {k: [] for k in ["hatchery_mip", "hatchery_dvr", "vtk_mip", "vtk_dvr", "pygfx_mip"]}
py = sys.executable
for r in range(rounds):
    out = run([hatchery, "bench", str(graph), str(graph), "--set", "1:ray.mode=mip",
               "--set", "1:ray.step=1", "--scenario", "orbit:camera", "--size", size,
               "--frames", frames])
    row = re.search(rf"^\| {size} \| ([\d.]+) \([^)]*\) \| ([\d.]+) ", out, re.M)
    times["hatchery_mip"].append(float(row.group(1)))
    times["hatchery_dvr"].append(float(row.group(2)))
    adapter = re.search(r"^adapter: (.*)$", out, re.M).group(1)
    for mode, step in [("mip", "1.0"), ("dvr", "0.5")]:
        out = run([py, str(here / "vtk_bench.py"), str(volume), str(camera), mode, frames, step, tf])
        times[f"vtk_{mode}"].append(float(re.search(r"vtk_\w+_ms ([\d.]+)", out).group(1)))
    out = run([py, str(here / "pygfx_bench.py"), str(volume), str(camera), frames])
    times["pygfx_mip"].append(float(re.search(r"pygfx_mip_ms ([\d.]+)", out).group(1)))
    print(f"round {r + 1}/{rounds}: " + ", ".join(f"{k} {v[-1]:.1f}" for k, v in times.items()),
          flush=True)

med = {k: statistics.median(v) for k, v in times.items()}
print(f"\nhatchery adapter: {adapter}")
print(f"MRI 197x233x189 u8, {size}, hatchery's camera (graphs/tf1d_phong_brain.ron), orbiting; "
      f"medians of {rounds} rounds x {frames} frames, ms/frame")
print("| mode | hatchery | VTK | pygfx | VTK / hatchery | pygfx / hatchery |")
print("|---|---|---|---|---|---|")
print(f"| MIP, 1-voxel steps | {med['hatchery_mip']:.1f} | {med['vtk_mip']:.1f} | "
      f"{med['pygfx_mip']:.1f} | {med['vtk_mip'] / med['hatchery_mip']:.2f} | "
      f"{med['pygfx_mip'] / med['hatchery_mip']:.2f} |")
print(f"| shaded DVR, 0.5-voxel steps | {med['hatchery_dvr']:.1f} | {med['vtk_dvr']:.1f} | n/a | "
      f"{med['vtk_dvr'] / med['hatchery_dvr']:.2f} | n/a |")
