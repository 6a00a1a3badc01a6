#!/bin/sh
# Runs every fuzz target for MINUTES minutes (default 10), two at a time, with the limits
# docs/outputs.md states: a finding is a crash, an input that runs over 5 s, or an
# allocation over 1 GB. Seeds: the shipped scenario, body and knot plan files, and
# fuzz/seeds/ (--set values, a centreline). Findings go to fuzz/artifacts/TARGET/.
# Usage (from the workspace root): fuzz/run_all.sh [MINUTES] [WORK_DIR] [TARGET…]
# (every target when none is named).
set -eu
minutes=${1:-10}
work=${2:-target/fuzz-corpus}
shift $(( $# < 2 ? $# : 2 ))
targets=${*:-scenario body set plan centreline}
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
seeds() {
    case $1 in
        scenario) echo data/scenarios tests/data ;;
        body) echo data/hagfish data/rods ;;
        plan) echo "$work/seeds/plan" ;;
        *) echo "fuzz/seeds/$1" ;;
    esac
}
# Two at a time.
set -- $targets
while [ $# -gt 0 ]; do
    first=$1
    shift
    if [ $# -gt 0 ]; then
        second=$1
        shift
        run "$first" $(seeds "$first") & run "$second" $(seeds "$second") & wait
    else
        run "$first" $(seeds "$first")
    fi
done
