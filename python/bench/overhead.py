"""What Python adds to a render: `python python/bench/overhead.py [GRAPH] [WxH]`.

Measured side by side in one run, on one adapter (printed), as a markdown table for
docs/benchmarks.md:

- cold: a new process that imports hatchery, loads the graph and renders it (the GPU opened
  included), against the command line's own in-process time for the same graph and size (the
  "rendered … in X s" it prints: load, GPU, pass, PNG written), each the median of 5 processes;
- warm: re-renders after one parameter change (camera azimuth), Python's wall time of `render`
  against the time the same call spent in Rust (the pass and the read-back), median of 15;
- cached: a re-render with nothing changed.
"""

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import hatchery

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
graph = sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO, "graphs", "hidden_structures.ron")
w, h = (int(v) for v in (sys.argv[2] if len(sys.argv) > 2 else "320x240").split("x"))
cli = os.environ.get("HATCHERY_BIN", os.path.join(REPO, "target", "release", "hatchery"))
runs = 5


def cli_in_process() -> float:
    out = subprocess.run(
        [cli, "render", graph, "--size", f"{w}x{h}", "-o", os.path.join(tempfile.gettempdir(), "hatchery-bench.png")],
        check=True, capture_output=True, text=True,
    ).stdout
    return float(re.search(r" in ([0-9.]+) s on ", out).group(1))


COLD = f"""
import time; t = time.perf_counter()
import hatchery
g = hatchery.Graph.load({graph!r}); g.render(size=({w}, {h}))
print(time.perf_counter() - t)
"""


def python_cold() -> float:
    out = subprocess.run([sys.executable, "-c", COLD], check=True, capture_output=True, text=True).stdout
    return float(out.strip().splitlines()[-1])


cli_times = [cli_in_process() for _ in range(runs)]
cold_times = [python_cold() for _ in range(runs)]

g = hatchery.Graph.load(graph)
camera = next(n for n in g.nodes if g.kind(n) == "Camera")
g.render(size=(w, h))
wall, rust = [], []
for i in range(15):
    g.set(camera, "azimuth", 20.0 + 3.0 * i)
    t = time.perf_counter()
    g.render(size=(w, h))
    wall.append(time.perf_counter() - t)
    rust.append(g._g.last_seconds())
ran = len(g.last_ran)
cached, cached_rust = [], []
for _ in range(15):
    t = time.perf_counter()
    g.render(size=(w, h))
    cached.append(time.perf_counter() - t)
    cached_rust.append(g._g.last_seconds())

med = statistics.median
ms = lambda s: f"{s * 1000:.1f} ms"  # noqa: E731
print(f"graph: {os.path.relpath(graph, REPO)} at {w}×{h}; adapter: {hatchery.adapter()}")
print()
print("| what | Python | in Rust / the CLI | ratio |")
print("|---|---|---|---|")
print(f"| cold: import, load, GPU, render (vs CLI in-process) | {ms(med(cold_times))} | {ms(med(cli_times))} | {med(cold_times) / med(cli_times):.2f} |")
print(f"| re-render after one parameter change ({ran} of {len(g.nodes)} nodes ran) | {ms(med(wall))} | {ms(med(rust))} | {med(wall) / med(rust):.3f} |")
print(f"| re-render, nothing changed | {ms(med(cached))} | {ms(med(cached_rust))} | {med(cached) / med(cached_rust):.3f} |")
print()
print(f"Python's own share of a warm re-render: {ms(med(wall) - med(rust))} (median).")
