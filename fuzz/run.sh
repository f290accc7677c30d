#!/bin/sh
# Runs one fuzz target the way docs/fuzzing.md reports it, from the repository root:
#   fuzz/run.sh TARGET [SECONDS]     (default 600 s)
# One job, one worker, niced; libFuzzer's log ends up in fuzz/logs/TARGET-<time>.log, crashes
# in fuzz/artifacts/TARGET/.
set -eu
t=$1
secs=${2:-600}
dict=""
if [ -f "fuzz/dicts/$t.dict" ]; then dict="-dict=fuzz/dicts/$t.dict"; fi
mkdir -p fuzz/logs "fuzz/artifacts/$t"
log="fuzz/logs/$t-$(date -u +%Y%m%dT%H%M%SZ).log"
# Stable toolchain: cargo-fuzz needs nightly flags (-Zsanitizer), RUSTC_BOOTSTRAP allows them.
# One rayon thread: the volume readers use rayon, and the machine is shared.
# In the foreground with its own log (not -jobs=1, whose fuzz-0.log in the working folder two
# runs at once would share).
RUSTC_BOOTSTRAP=1 RAYON_NUM_THREADS=1 nice -n 10 cargo fuzz run "$t" "fuzz/corpus/$t" -- \
    -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 $dict > "$log" 2>&1 || true
grep -E '^#[0-9]+|stat::|ERROR|SUMMARY|Test unit written' "$log" | tail -12
