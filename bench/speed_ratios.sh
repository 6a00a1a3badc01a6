#!/usr/bin/env bash
# Issue #40's speed ratios, measured side by side: each benchmark run ROUNDS times on a build
# of BASE_REV and on this tree, alternated (base, this, base, this, …), and the ratio of the
# medians (this / base). This machine's speed moves by tens of per cent between hours, so only
# ratios taken in one run like this are comparable (docs/performance.md).
#
#   bench/speed_ratios.sh BASE_REV [ROUNDS]     (ROUNDS defaults to 5)
#
# The benchmarks:
# - knotted: the knotted 100-body step, `xtask knotted --steps 100 --repeat 20` (the median µs
#   per step it prints), each build from the knotted state its own run reaches (a change of
#   rounding moves that state: the contacts it prints may differ);
# - knotted_1000: the 1000-body knotted rope, `cargo bench --bench step -- knotted_1000` (the
#   criterion median);
# - free_chain: ES103 at 10 000 bodies held in water for 2 s, `hagfish run` (the summary's
#   mean µs per step).
# BASE_REV is built once in a git worktree under ${SPEED_RATIOS_DIR:-/tmp/hagfish-speed-ratios}
# (kept for the next call); this tree is built with `cargo build --release`.
set -euo pipefail
base_rev="${1:?usage: bench/speed_ratios.sh BASE_REV [ROUNDS]}"
rounds="${2:-5}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cache="${SPEED_RATIOS_DIR:-/tmp/hagfish-speed-ratios}"
base="$cache/$(git -C "$root" rev-parse --short "$base_rev")"
if [ ! -d "$base" ]; then
    git -C "$root" worktree add --detach "$base" "$base_rev" >/dev/null
fi
this_target="${CARGO_TARGET_DIR:-$root/target}"
build() { (cd "$1" && CARGO_TARGET_DIR="$2" cargo build --release --quiet -p xtask --bin xtask \
    && CARGO_TARGET_DIR="$2" cargo build --release --quiet --bin hagfish); }
echo "building $base_rev in $base and this tree …" >&2
build "$base" "$base/target"
build "$root" "$this_target"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
sed 's/^    body_count: 100,/    body_count: 10000,/' "$root/data/hagfish/es103.ron" > "$work/es103_10000.ron"
cat > "$work/free_chain.ron" <<SCENARIO
Scenario(
    name: "free_chain",
    body: "es103_10000.ron",
    time_step_s: 0.01,
    duration_s: 2.0,
    record_every_s: 1.0,
    backend: SparseMaximal,
    drag: Some((linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 0.5)),
    phases: [Hold(10.0)],
)
SCENARIO

# One measurement (µs) of benchmark $1 on the tree $2 with target directory $3.
measure() {
    case "$1" in
        knotted)
            (cd "$2" && "$3/release/xtask" knotted --steps 100 --repeat 20 2>/dev/null) \
                | sed -n 's/.*"median_us_per_step": *\([0-9.]*\).*/\1/p' ;;
        knotted_1000)
            (cd "$2" && CARGO_TARGET_DIR="$3" cargo bench --quiet --bench step -- --noplot \
                'knotted_1000/SparseMaximal' 2>/dev/null) \
                | sed -n 's/.*time: *\[[^ ]* [^ ]* \([0-9.]*\) \([µm]s\).*/\1 \2/p' | head -1 \
                | awk '{print ($2 == "ms") ? $1 * 1000 : $1}' ;;
        free_chain)
            rm -rf "$work/out"
            "$3/release/hagfish" run "$work/free_chain.ron" --out "$work/out" --quiet 2>&1 \
                | sed -n 's/.*(total \([0-9.]*\)).*/\1/p' ;;
    esac
}
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }

echo "| benchmark | $base_rev (µs) | this tree (µs) | ratio of medians |"
echo "|---|---|---|---|"
for benchmark in knotted knotted_1000 free_chain; do
    : > "$work/base"
    : > "$work/this"
    for _ in $(seq "$rounds"); do
        for side in base this; do
            if [ "$side" = base ]; then tree="$base" target="$base/target"; else tree="$root" target="$this_target"; fi
            value="$(measure "$benchmark" "$tree" "$target")"
            if [ -z "$value" ]; then
                echo "$benchmark printed no measurement on $tree" >&2
                exit 1
            fi
            echo "$value" >> "$work/$side"
        done
    done
    b=$(median < "$work/base")
    t=$(median < "$work/this")
    echo "| $benchmark | $(tr '\n' ' ' < "$work/base")| $(tr '\n' ' ' < "$work/this")| $(echo "scale=3; $t / $b" | bc) |"
done
echo
echo "\`bench/speed_ratios.sh $base_rev $rounds\`, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD || echo " with changes")"
