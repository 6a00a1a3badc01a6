"""Tight open knot templates for the follow-the-leader tie (docs/knot-plans.md, "Templates").

A template is the curve the tail's tip runs along while the body follows it. This script
makes one from a knot's alternating 4-plat (a 2-bridge knot: 3_1 = σ₂³, 4_1 = σ₂²σ₁⁻¹σ₂,
X, cut open on its
straight strand, then pulls it tight by SONO (Pieranski's shrink-on-no-overlaps: the two ends
are pulled apart a little, then overlaps, stretched links and bends sharper than the tube
allows are removed, over and over). Lengths are in units of the tube's diameter D, so a
template is used at any body's size.

    python bench/knot_templates.py            # writes data/knots/templates/{3_1,4_1,6_2}.txt
    python bench/knot_templates.py --check    # prints each template's length, clearance, bend

Each written template is checked for its knot type by the project's analysis in
`cargo test --release -p hagfish-control --test integration templates`.
"""

import argparse
import pathlib

import numpy as np
from scipy.spatial import cKDTree

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parent / "data" / "knots" / "templates"

# The plats, by the generators' columns (±i: σᵢ^±1 on strands 1–4).
PLATS = {"3_1": [2, 2, 2], "4_1": [2, 2, -1, 2], "6_2": [2, 2, 2, -1, 2, 2]}

BEAD = 0.1  # spacing of the template's vertices (D)
CLEARANCE = 1.0  # the least distance between strands that do not neighbour along the curve (D)
MIN_BEND_RADIUS = 0.7  # the sharpest bend of a template (D): the chain's bending limits
LEG = 1.5  # straight length kept before the knot's first turn (D)
# Length kept after the knot's last turn (D): the tail beyond the knot. 1.5 D holds the
# figure-eight; 6_2's is 3 D, a margin against its tail slipping back once the tie's servos
# let go (with the soft skin of miller_institute.ron, 1.5 D also held it on ES103).
EXIT_LEGS = {"3_1": 1.5, "4_1": 1.5, "6_2": 3.0}


def four_plat_cut_open(word, height=0.5, depth=3.0):
    """The 4-plat of `word` with caps (1, 2) and (3, 4) at both ends, cut on strand 4 (as in
    crates/knots/tests/integration/plat_path.rs), its two ends leaving apart at right angles."""
    columns = len(word)
    right = columns + 1.0
    middle = right / 2.0

    def y(level):
        return 4.0 - level

    path = [(middle + depth, y(4.0) - depth, 0.0), (middle + 0.5, y(4.0), 0.0), (right, y(4.0), 0.0)]
    path += [(right + 0.5, y(3.5), 0.0), (right, y(3.0), 0.0)]
    level, leftward = 3, True
    while True:
        order = range(columns - 1, -1, -1) if leftward else range(columns)
        for column in order:
            generator = word[column]
            upper = abs(generator)
            if level not in (upper, upper + 1):
                continue
            nxt = upper + 1 if level == upper else upper
            x = column + 1.0
            step = -0.5 if leftward else 0.5
            low, high = (nxt, level) if leftward else (level, nxt)
            over = (generator > 0) == (high > low)
            z = height if over else -height
            mid = 0.5 * (y(level) + y(nxt))
            path += [(x - step, y(level), 0.0), (x, mid, z), (x + step, y(nxt), 0.0)]
            level = nxt
        partner = [0, 2, 1, 4, 3][level]
        edge, outside = (0.0, -0.5) if leftward else (right, right + 0.5)
        mid = 0.5 * (y(level) + y(partner))
        path += [(edge, y(level), 0.0), (outside, mid, 0.0), (edge, y(partner), 0.0)]
        if partner == 4:
            path += [(middle - 0.5, y(4.0), 0.0), (middle - depth, y(4.0) - depth, 0.0)]
            return np.array(path)
        level, leftward = partner, not leftward


def resample(points, spacing):
    """The polyline `points` with its vertices `spacing` apart along it."""
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    at = np.arange(0.0, arc[-1], spacing)
    return np.stack([np.interp(at, arc, points[:, k]) for k in range(3)], axis=1)


def smooth(points, rounds):
    """`rounds` passes of neighbour averaging (the ends fixed): rounds the plat's corners."""
    p = points.copy()
    for _ in range(rounds):
        p[1:-1] = 0.25 * p[:-2] + 0.5 * p[1:-1] + 0.25 * p[2:]
    return p


def remove_overlaps(p, skip):
    """Pushes apart every pair of vertices more than `skip` apart along the curve and closer
    than CLEARANCE, each by half the overlap (one Jacobi pass, averaged per vertex); returns
    the curve and the largest overlap found."""
    pairs = cKDTree(p).query_pairs(CLEARANCE, output_type="ndarray")
    pairs = pairs[np.abs(pairs[:, 0] - pairs[:, 1]) > skip]
    if len(pairs) == 0:
        return p, 0.0
    i, j = pairs[:, 0], pairs[:, 1]
    d = p[i] - p[j]
    r = np.linalg.norm(d, axis=1, keepdims=True)
    push = 0.5 * (CLEARANCE - r) * d / np.maximum(r, 1e-9)
    move = np.zeros_like(p)
    counts = np.zeros(len(p))
    np.add.at(move, i, push)
    np.add.at(move, j, -push)
    np.add.at(counts, i, 1.0)
    np.add.at(counts, j, 1.0)
    return p + move / np.maximum(counts, 1.0)[:, None], float((CLEARANCE - r).max())


def limit_bends(p):
    """Straightens every vertex whose turn is sharper than MIN_BEND_RADIUS allows (half-way
    toward its neighbours' midpoint)."""
    a, b, c = p[:-2], p[1:-1], p[2:]
    u, v = b - a, c - b
    cos = (u * v).sum(axis=1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
    sharp = cos < np.cos(BEAD / MIN_BEND_RADIUS)
    p[1:-1][sharp] += 0.5 * (0.5 * (a + c) - b)[sharp]
    return p


def pull_tight(points, iterations, shrink=0.2):
    """SONO with both ends held: every vertex moves `shrink` of the way toward its
    neighbours' midpoint (the curve shortens), then overlaps and bends sharper than the tube
    allows are removed; the curve is resampled every 10 iterations. Returns the tightened
    curve and the largest overlap left."""
    p = points.copy()
    skip = int(np.ceil(np.pi * CLEARANCE / 2 / BEAD))
    worst = 0.0
    for iteration in range(iterations):
        p[1:-1] += shrink * (0.5 * (p[:-2] + p[2:]) - p[1:-1])
        for _ in range(3):
            p = limit_bends(p)
            p, worst = remove_overlaps(p, skip)
        if iteration % 10 == 9:
            p = np.vstack([resample(p, BEAD), p[-1:]])
    return p, worst


def trimmed(p, exit_leg):
    """`p` with its legs cut to LEG before the first and `exit_leg` after the last vertex that
    comes within 1.2 D of another part of the curve (the knot's ends)."""
    skip = int(np.ceil(np.pi * CLEARANCE / 2 / BEAD))
    tree = cKDTree(p)
    near = np.array([any(abs(j - k) > skip for j in tree.query_ball_point(q, 1.2 * CLEARANCE))
                     for k, q in enumerate(p)])
    first, last = np.argmax(near), len(p) - 1 - np.argmax(near[::-1])
    return p[max(first - round(LEG / BEAD), 0):min(last + round(exit_leg / BEAD), len(p) - 1) + 1]


def template(name, iterations):
    """The tight open template of knot `name` (D units)."""
    plat = four_plat_cut_open(PLATS[name]) * 1.6
    curve = smooth(resample(plat, BEAD), 40)
    tight, worst = pull_tight(curve, iterations)
    return trimmed(tight, EXIT_LEGS[name]), worst


def describe(p):
    """Length, the least clearance between non-neighbours, and the sharpest bend radius (D)."""
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    skip = int(np.ceil(np.pi * CLEARANCE / 2 / BEAD))
    r = np.linalg.norm(p[:, None] - p[None, :], axis=2)
    index = np.arange(len(p))
    far = np.abs(index[:, None] - index[None, :]) > skip
    u, v = p[1:-1] - p[:-2], p[2:] - p[1:-1]
    cos = np.clip((u * v).sum(1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1)), -1, 1)
    bend = BEAD / np.maximum(np.arccos(cos), 1e-12)
    return steps.sum(), r[far].min(), bend.min()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=20000)
    parser.add_argument("--check", action="store_true", help="print, do not write")
    parser.add_argument("knots", nargs="*", default=list(PLATS))
    args = parser.parse_args()
    for name in args.knots:
        curve, worst = template(name, args.iterations)
        length, clearance, bend = describe(curve)
        print(f"{name}: {len(curve)} vertices, length {length:.2f} D, least clearance "
              f"{clearance:.3f} D, sharpest bend radius {bend:.2f} D (overlap left {worst:.3f} D)")
        if not args.check:
            OUT.mkdir(parents=True, exist_ok=True)
            header = (f"# {name}: tight open template (bench/knot_templates.py, "
                      f"{args.iterations} iterations), units of the tube diameter D\n")
            np.savetxt(OUT / f"{name}.txt", curve, fmt="%.5f", header=header.strip(), comments="")


if __name__ == "__main__":
    main()
