#!/usr/bin/env python3
"""Sums up the libFuzzer logs fuzz/run.sh leaves in fuzz/logs/: per run and per target the
time fuzzed, executions, and how the run ended. Run from the repository root:
python3 fuzz/stats.py
"""

import glob
import os
import re
from collections import defaultdict

runs = defaultdict(list)
for path in sorted(glob.glob("fuzz/logs/*.log")):
    target = os.path.basename(path).rsplit("-", 1)[0]
    text = open(path, errors="replace").read()
    stat = dict(re.findall(r"^stat::(\w+):\s+(\d+)", text, re.M))
    execs = int(stat.get("number_of_executed_units", 0))
    rate = int(stat.get("average_exec_per_sec", 0))
    if "SUMMARY: libFuzzer: out-of-memory" in text:
        end = "out-of-memory"
    elif "ERROR: libFuzzer: timeout" in text:
        end = "timeout"
    elif "ERROR: libFuzzer: deadly signal" in text or "ERROR: AddressSanitizer" in text:
        end = "crash"
    elif re.search(r"^#\d+\s+DONE", text, re.M):
        end = "done"
    else:
        end = "unfinished"
    # libFuzzer says how long a run that ran out its time took; for one that stopped at a
    # crash, executions / average rate is as close as its log gets.
    took = re.findall(r"^Done \d+ runs in (\d+) second", text, re.M)
    seconds = int(took[-1]) if took else (execs / rate if rate else 0)
    done = re.findall(r"^#\d+\s+DONE.*?corp: (\d+)/(\S+)", text, re.M)
    corpus = f"{done[-1][0]} files/{done[-1][1]}" if done else "-"
    runs[target].append((os.path.basename(path), seconds, execs, rate, end, corpus))

print(f"{'run':45} {'~seconds':>9} {'executions':>11} {'exec/s':>7}  end  corpus")
for target in sorted(runs):
    for name, seconds, execs, rate, end, corpus in runs[target]:
        print(f"{name:45} {seconds:9.0f} {execs:11d} {rate:7d}  {end}  {corpus}")
print()
print(f"{'target':12} {'runs':>4} {'~minutes':>9} {'executions':>11}")
for target in sorted(runs):
    r = runs[target]
    print(f"{target:12} {len(r):4d} {sum(x[1] for x in r) / 60:9.1f} {sum(x[2] for x in r):11d}")
