#!/usr/bin/env python3
"""Batch throughput, measured side by side in one run (docs/batch.md):

- items per minute of `hatchery batch` with 1 process, and with 2 processes (--shard 0/2 and
  1/2 started together), for a 24-frame orbit of graphs/hidden_structures.ron at 320×240;
- the per-item overhead of one process per item (`hatchery render --set camera.azimuth=…`
  for each, what a job array without batching does) against an item inside one session.

Usage: scripts/bench-batch.py [FRAMES] [WxH]   (the binary: target/release/hatchery)
"""

import json
import os
import subprocess
import sys
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.environ.get("HATCHERY_BIN", os.path.join(root, "target", "release", "hatchery"))
frames = int(sys.argv[1]) if len(sys.argv) > 1 else 24
size = sys.argv[2] if len(sys.argv) > 2 else "320x240"
w, h = size.split("x")
graph = os.path.join(root, "graphs", "hidden_structures.ron")
tmp = tempfile.mkdtemp(prefix="hatchery-bench-batch-")
job = os.path.join(tmp, "job.ron")
with open(job, "w") as f:
    f.write(f'(graph: "{graph}", size: ({w}, {h}), '
            f'camera: Some(Orbit(node: "camera", frames: {frames})), output: "f_{{frame:03}}.png")')


def timed(commands):
    start = time.perf_counter()
    procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for c in commands]
    for p in procs:
        assert p.wait() == 0, "a batch process failed"
    return time.perf_counter() - start


one = timed([[exe, "batch", job, "--out", os.path.join(tmp, "one")]])
two = timed([[exe, "batch", job, "--out", os.path.join(tmp, "two"), "--shard", f"{k}/2"] for k in (0, 1)])
with open(os.path.join(tmp, "one", "manifest-0-of-1.json")) as f:
    manifest = json.load(f)
in_session = [e["seconds"] for e in manifest["items"]]
adapter = manifest["adapter"]
# One process per item, for the first 8 items.
per_process = []
for e in manifest["items"][:8]:
    start = time.perf_counter()
    subprocess.run([exe, "render", graph, "--size", size, "-o", os.path.join(tmp, "p.png"),
                    "--set", f"camera.azimuth={e['params']['camera.azimuth']}"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    per_process.append(time.perf_counter() - start)

mean = lambda xs: sum(xs) / len(xs)  # noqa: E731
print(f"{frames} items ({os.path.relpath(graph, root)} orbit at {size}) on {adapter}, {os.cpu_count()} cores")
print()
print("| run | wall | items per minute | ratio |")
print("|---|---|---|---|")
print(f"| 1 process | {one:.2f} s | {frames / one * 60:.0f} | 1.00 |")
print(f"| 2 processes (--shard 0/2, 1/2) | {two:.2f} s | {frames / two * 60:.0f} | {one / two:.2f} |")
print()
print("| per item | seconds |")
print("|---|---|")
print(f"| inside one session (manifest, mean; first item {in_session[0]:.3f} s) | {mean(in_session[1:]):.3f} |")
print(f"| one `hatchery render` process per item (mean of 8) | {mean(per_process):.3f} |")
print(f"| overhead of a process per item | {mean(per_process) - mean(in_session[1:]):.3f} ({mean(per_process) / mean(in_session[1:]):.1f}×) |")
