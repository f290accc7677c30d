#!/usr/bin/env bash
# Wall time of `hatchery render` for every preset in graphs/ (process start, reading the data,
# compiling the pipelines, rendering, writing the PNG), the presets taken in turn, each
# `--rounds` times (default 3) with the rounds interleaved; prints a Markdown table of the
# median and the slowest round per preset, with the adapter, and flags any preset over the
# limit (default 10 s; issue 32's goal at 1024×768 on a 2-core CPU driver). A benchmark, not a
# test: nothing fails on time, the script exits 0 unless a render fails.
#
#   scripts/bench-presets.sh [--size WxH] [--rounds N] [--limit S] BIN
#
# Run it from the repository root (the presets read ../shared/data by relative path); the
# pictures go to a temporary folder and are removed afterwards.
set -euo pipefail
size=1024x768
rounds=3
limit=10
while [ $# -ge 2 ]; do
    case "$1" in
        --size) size=$2; shift 2 ;;
        --rounds) rounds=$2; shift 2 ;;
        --limit) limit=$2; shift 2 ;;
        *) break ;;
    esac
done
[ $# -eq 1 ] || { echo "usage: $0 [--size WxH] [--rounds N] [--limit S] BIN" >&2; exit 2; }
bin=$(realpath "$1")
[ -x "$bin" ] || { echo "bench-presets: $1 is not an executable" >&2; exit 2; }
[ -d graphs ] || { echo "bench-presets: run from the repository root (no graphs/ here)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
presets=(graphs/*.ron)
adapter=""
for round in $(seq "$rounds"); do
    echo "round $round of $rounds: ${#presets[@]} presets at $size" >&2
    for graph in "${presets[@]}"; do
        name=$(basename "$graph" .ron)
        start=$(date +%s.%N)
        if ! "$bin" render "$graph" --size "$size" -o "$work/$name.png" >"$work/$name.log" 2>&1; then
            echo "bench-presets: $graph failed to render:" >&2
            cat "$work/$name.log" >&2
            exit 1
        fi
        end=$(date +%s.%N)
        echo "$name $(echo "$end - $start" | bc)" >>"$work/times"
        [ -n "$adapter" ] || adapter=$(grep -o ' on .*' "$work/$name.log" | tail -1 | sed 's/^ on //')
    done
done

echo "presets: \`hatchery render\` wall seconds at $size, $(date -u +%Y-%m-%d), $(nproc) cores,"
echo "adapter: $adapter"
echo "(median and slowest of $rounds interleaved rounds)"
echo
echo "| preset | median s | slowest s |"
echo "|---|---|---|"
over=0
for graph in "${presets[@]}"; do
    name=$(basename "$graph" .ron)
    mapfile -t t < <(awk -v n="$name" '$1 == n { print $2 }' "$work/times" | sort -g)
    median=${t[$(( ${#t[@]} / 2 ))]}
    slowest=${t[$(( ${#t[@]} - 1 ))]}
    flag=""
    if [ "$(echo "$median > $limit" | bc)" = 1 ]; then
        flag=" **over ${limit} s**"
        over=$((over + 1))
    fi
    printf '| %s | %.2f%s | %.2f |\n' "$name" "$median" "$flag" "$slowest"
done
echo
echo "$over of ${#presets[@]} presets over $limit s (median)"
