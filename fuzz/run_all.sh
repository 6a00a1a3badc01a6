#!/bin/sh
# Runs every fuzz target for MINUTES minutes (default 10), two at a time, with the limits
# docs/outputs.md states: a finding is a crash, an input that runs over 5 s, or an
# allocation over 1 GB. Seeds: the shipped scenario, body and knot plan files, and
# fuzz/seeds/ (--set values, a centreline). Findings go to fuzz/artifacts/TARGET/.
# Usage (from the workspace root): fuzz/run_all.sh [MINUTES] [WORK_DIR]
set -eu
minutes=${1:-10}
work=${2:-target/fuzz-corpus}
mkdir -p "$work/seeds/plan"
printf '\000(scenario: "../scenarios/thesis.ron", grid: [("time_step_s", ["0.01", "0.005"])])' \
    > "$work/seeds/plan/grid"
printf '\001{"scenario":"/x.ron","parameters":["h"],"runs":[{"id":"0","overrides":["h=1"]}]}' \
    > "$work/seeds/plan/plan_json"
for knot in data/knots/*.ron; do
    { printf '\002'; cat "$knot"; } > "$work/seeds/plan/$(basename "$knot")"
done
run() {
    target=$1
    shift
    mkdir -p "$work/$target"
    if cargo +nightly fuzz run -O "$target" "$work/$target" "$@" -- \
        -max_total_time=$((minutes * 60)) -timeout=5 -malloc_limit_mb=1024 \
        -rss_limit_mb=2048 -max_len=16384 -print_final_stats=1 > "$work/$target.log" 2>&1
    then
        echo "$target: no finding in $minutes min ($(grep -m1 -o 'stat::number_of_executed_units: [0-9]*' "$work/$target.log"))"
    else
        echo "$target: FINDING, see $work/$target.log and fuzz/artifacts/$target"
    fi
}
run scenario data/scenarios tests/data & run body data/hagfish data/rods & wait
run set fuzz/seeds/set & run plan "$work/seeds/plan" & wait
run centreline fuzz/seeds/centreline
