#!/usr/bin/env bash
# Wall time of a 16-run sweep of the thesis scenario (4 water drags × 4 tail pulls) made
# serially and with `--jobs 2`, REPEAT times each (default 3), and the ratio of the medians
# (docs/performance.md). Needs the release build: cargo build --release.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
hagfish="${HAGFISH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/hagfish}"
repeat="${REPEAT:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat > "$work/grid.ron" <<GRID
Sweep(
    scenario: "$root/data/scenarios/thesis.ron",
    grid: [
        ("drag.quadratic_g_per_cm3", ["0.4", "0.5", "0.6", "0.7"]),
        ("Thigmotaxis.parameters.tail_pull_dyn", ["0", "10", "20", "30"]),
    ],
)
GRID
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
for jobs in 1 2; do
    for _ in $(seq "$repeat"); do
        rm -rf "$work/sweep"
        "$hagfish" sweep plan "$work/grid.ron" --out "$work/sweep" >/dev/null
        start=$(date +%s.%N)
        "$hagfish" sweep run "$work/sweep" --jobs "$jobs" >/dev/null 2>&1
        end=$(date +%s.%N)
        echo "$end - $start" | bc
    done > "$work/jobs$jobs"
    echo "--jobs $jobs: $(tr '\n' ' ' < "$work/jobs$jobs")s"
done
one=$(median < "$work/jobs1"); two=$(median < "$work/jobs2")
echo "median serial $one s, --jobs 2 $two s, ratio $(echo "scale=3; $two / $one" | bc)"
