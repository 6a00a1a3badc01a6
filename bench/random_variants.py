#!/usr/bin/env python3
"""Random hagfish within the family's ranges, every parameter changed at once, run through
the trefoil scenario and judged by the slide's acceptance checks (issue #14).

`tests/integration/tie_family.rs` changes one parameter at a time. Users will change several: this
script draws COUNT bodies with, independently and uniformly (log-uniformly for stiffness, damping
and drag), length 35–50 cm (mass ∝ length), circumferences ×0.85–1.15, stiffness ×0.1–10, damping
×1–10, 50–300 bodies, h = 0.005–0.02 s and water drag ×0.5–2, and runs `thesis.ron` on each.
A variant passes when the run completes, the knot (the trefoil, or `--knot`) holds on ≥ 99 % of
the frames after tying, its core's head-ward end is ≥ 0.35 L from the head when tied, the core's midpoint
travels ≥ 0.25 L over the slide, its head-ward end comes within 0.05 L of the head, self
penetration stays below 2 % of the local radius and no joint passes its limit by 0.5°; a
failing variant's line names the checks it fails. Travel and nearest end are measured over the
phase named `slide`, so `--scenario` takes scenarios that tie and slide (`thesis.ron`,
`figure_eight.ron` with `--knot 4_1`); on one without a slide those two checks fail.

Usage (from anywhere in the workspace):
    python3 bench/random_variants.py [--seed S] [--count N] [--jobs J] [--scenario FILE]
                                     [--knot K] [--set PATH=VALUE ...]
It builds `hagfish` with `cargo build --release` first and runs the binary cargo's target
directory holds (so never a stale one); set HAGFISH_BIN to run another binary instead. The
draws depend only on the seed. Run directories are made in a temporary directory and removed
as they are read.
"""

import argparse
import csv
import json
import math
import os
import random
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ES103 = os.path.join(ROOT, "data", "hagfish", "es103.ron")
CIRCUMFERENCES = [5.6, 5.5, 5.6, 4.3]
BODY_COUNTS = [50, 60, 75, 100, 120, 150, 200, 250, 300]


def log_uniform(rng, low, high):
    return 10 ** rng.uniform(math.log10(low), math.log10(high))


def draw(rng):
    """One variant: the body's edits and the scenario's time step and drag."""
    return {
        "length_cm": rng.uniform(35.0, 50.0),
        "circumference": rng.uniform(0.85, 1.15),
        "stiffness": log_uniform(rng, 0.1, 10.0),
        "damping": log_uniform(rng, 1.0, 10.0),
        "bodies": rng.choice(BODY_COUNTS),
        "time_step_s": rng.uniform(0.005, 0.02),
        "drag": log_uniform(rng, 0.5, 2.0),
    }


def body_text(v):
    """ES103's biometrics file with the variant's edits."""
    with open(ES103) as f:
        text = f.read()
    circumferences = ", ".join(f"{c * v['circumference']:.3f}" for c in CIRCUMFERENCES)
    edits = [
        ("length_cm: 42.4", f"length_cm: {v['length_cm']:.2f}"),
        ("mass_g: 80.0", f"mass_g: {80.0 * v['length_cm'] / 42.4:.3f}"),
        ("circumferences_cm: [5.6, 5.5, 5.6, 4.3]", f"circumferences_cm: [{circumferences}]"),
        ("bending_stiffness_dyn_cm_per_rad: 1.0",
         f"bending_stiffness_dyn_cm_per_rad: {v['stiffness']:.4f}"),
        ("twist_stiffness_dyn_cm_per_rad: 5.0",
         f"twist_stiffness_dyn_cm_per_rad: {5.0 * v['stiffness']:.4f}"),
        ("damping_dyn_cm_s_per_rad: 0.1", f"damping_dyn_cm_s_per_rad: {0.1 * v['damping']:.4f}"),
        (" body_count: 100", f" body_count: {v['bodies']}"),
    ]
    for old, new in edits:
        if old not in text:
            raise SystemExit(f"{ES103} no longer contains `{old}`")
        text = text.replace(old, new)
    return text


def number(row, column):
    try:
        return float(row[column])
    except ValueError:
        return math.nan


def judge(out, knot):
    """The checks of one run directory whose scenario ties `knot` (its name in metrics.csv,
    e.g. 3_1), as (passed, description)."""
    with open(os.path.join(out, "manifest.json")) as f:
        manifest = json.load(f)
    with open(os.path.join(out, "metrics.csv")) as f:
        rows = list(csv.DictReader(f))
    tied = next((i for i, r in enumerate(rows) if r["phase"] != "tie"), None)
    if tied is None:
        return False, f"{manifest['status']}, not tied"
    after = rows[tied:]
    held = sum(r["knot"] == knot for r in after) / len(after)
    slide = [r for r in rows if r["phase"] == "slide"]
    # During the slide, as `hagfish_bench_support::KnotRun` measures it for `cargo xtask family`.
    mids = [m for m in (number(r, "knot_core_mid_L") for r in slide) if not math.isnan(m)]
    travel = number(slide[0], "knot_core_mid_L") - min(mids) if slide and mids else math.nan
    nearest = min((number(r, "knot_core_start_L") for r in slide), default=math.nan)
    start = number(rows[tied], "knot_core_start_L")
    penetration = max(number(r, "max_self_penetration_rel") for r in rows)
    excess = max(number(r, "max_limit_excess_deg") for r in rows)
    checks = {
        "completed": manifest["status"] == "completed",
        "held": held >= 0.99,
        "tied at": start >= 0.35,
        "travel": travel >= 0.25,
        "nearest": nearest <= 0.05,
        "penetration": penetration < 0.02,
        "limit excess": excess < 0.5,
    }
    failed = [name for name, passed in checks.items() if not passed]
    text = (f"{manifest['status']}, held {held:.3f}, tied at {start:.3f} L, travel {travel:.3f} L,"
            f" nearest {nearest:.3f} L, penetration {100 * penetration:.4f} %,"
            f" limit excess {excess:.2f}°")
    if failed:
        text += f" (failed: {', '.join(failed)})"
    return not failed, text


def run(hagfish, scenario, knot, sets, work, index, v):
    body = os.path.join(work, f"body_{index}.ron")
    with open(body, "w") as f:
        f.write(body_text(v))
    out = os.path.join(work, f"run_{index}")
    subprocess.run(
        [hagfish, "run", scenario, "--body", body, "--out", out, "--quiet",
         "--set", f"time_step_s={v['time_step_s']:.5f}",
         "--set", f"drag.quadratic_g_per_cm3={0.5 * v['drag']:.4f}",
         *[arg for s in sets for arg in ("--set", s)]],
        capture_output=True, check=False,
    )
    passed, text = judge(out, knot)
    subprocess.run(["rm", "-rf", out, body], check=False)
    return passed, text


def hagfish_binary():
    """HAGFISH_BIN if set; else builds `hagfish` in release and returns the binary in cargo's
    target directory (as `cargo metadata` reports it, CARGO_TARGET_DIR included)."""
    if "HAGFISH_BIN" in os.environ:
        return os.environ["HAGFISH_BIN"]
    subprocess.run(["cargo", "build", "--release", "--bin", "hagfish"], cwd=ROOT, check=True)
    metadata = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"],
                              cwd=ROOT, check=True, capture_output=True, text=True)
    return os.path.join(json.loads(metadata.stdout)["target_directory"], "release", "hagfish")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--count", type=int, default=10)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--scenario", default=os.path.join(ROOT, "data", "scenarios", "thesis.ron"))
    parser.add_argument("--knot", default="3_1",
                        help="the knot the scenario ties, as metrics.csv names it (default 3_1)")
    parser.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                        help="a scenario override for every run, as `hagfish run --set`")
    args = parser.parse_args()
    hagfish = hagfish_binary()
    if not os.access(hagfish, os.X_OK):
        raise SystemExit(f"no hagfish binary at {hagfish} (HAGFISH_BIN)")
    rng = random.Random(args.seed)
    variants = [draw(rng) for _ in range(args.count)]
    with tempfile.TemporaryDirectory() as work, ThreadPoolExecutor(args.jobs) as pool:
        results = pool.map(lambda iv: run(hagfish, args.scenario, args.knot, args.set, work, *iv),
                           enumerate(variants))
        passes = 0
        for v, (passed, text) in zip(variants, results):
            passes += passed
            print(f"L {v['length_cm']:.1f} cm, circumferences ×{v['circumference']:.2f},"
                  f" stiffness ×{v['stiffness']:.2f}, damping ×{v['damping']:.1f},"
                  f" {v['bodies']} bodies, h {v['time_step_s']:.4f} s, drag ×{v['drag']:.2f}:"
                  f" {text} → {'pass' if passed else 'FAIL'}")
    print(f"{passes} of {args.count} pass (seed {args.seed})")


if __name__ == "__main__":
    main()
