"""The capstan threshold of a rope of rigid links whose contact spheres sit at the links'
midpoints (docs/physics.md, "Friction"), from its statics alone: a linear program.

K links of length ℓ = 2ρ tan(α/2) touch a cylinder (radius R, ρ = R + r) at their midpoints,
each turned by α from the last, on free joints. The first link is pulled back along its
direction by 1 dyn, the last link on along its own by T_B. Unknowns: the joint forces, each
contact's normal force N ≥ 0 and friction f (|f| ≤ μN, acting at the contact point, r inside
the link's centre); each link balances its forces and its moment about its centre. The
largest T_B that balances is where the rope slips. `cargo test --release -p hagfish-sim
--test integration capstan` has the rope with its spheres at the joints instead, which slips
at e^{μθ}.

    python bench/capstan_midpoint_statics.py
"""

import math

import numpy as np
from scipy.optimize import linprog


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def threshold(links, alpha, cylinder, rope, mu):
    """The largest far-end tension the rope holds against 1 dyn (θ = (links − 1)·α)."""
    reach = cylinder + rope
    length = 2.0 * reach * math.tan(alpha / 2.0)
    heading = [np.array([math.cos(i * alpha), math.sin(i * alpha)]) for i in range(links)]
    normal = [np.array([math.sin(i * alpha), -math.cos(i * alpha)]) for i in range(links)]
    centre = [reach * n for n in normal]
    joints = 2 * (links - 1)  # the joint forces G_1 … G_{K−1}, two components each
    n_at, f_at, far = joints, joints + links, joints + 2 * links
    unknowns = far + 1
    equalities, rhs = [], []
    for i in range(links):
        rows = [np.zeros(unknowns) for _ in range(3)]  # x, y, moment
        values = np.zeros(3)
        left = centre[i] - 0.5 * length * heading[i]
        right = centre[i] + 0.5 * length * heading[i]
        if i == 0:
            pull = -heading[0]
            values -= [pull[0], pull[1], cross(left - centre[i], pull)]
        for k, unit in enumerate((np.array([1.0, 0.0]), np.array([0.0, 1.0]))):
            if i > 0:  # the joint force G_i acts on link i's left end reversed
                column = 2 * (i - 1) + k
                rows[0][column] -= unit[0]
                rows[1][column] -= unit[1]
                rows[2][column] -= cross(left - centre[i], unit)
            if i < links - 1:
                column = 2 * i + k
                rows[0][column] += unit[0]
                rows[1][column] += unit[1]
                rows[2][column] += cross(right - centre[i], unit)
        if i == links - 1:
            rows[0][far] += heading[i][0]
            rows[1][far] += heading[i][1]
            rows[2][far] += cross(right - centre[i], heading[i])
        rows[0][n_at + i] += normal[i][0]
        rows[1][n_at + i] += normal[i][1]
        rows[0][f_at + i] += heading[i][0]
        rows[1][f_at + i] += heading[i][1]
        rows[2][f_at + i] += cross(-rope * normal[i], heading[i])
        equalities += rows
        rhs += list(values)
    inequalities = []
    for i in range(links):
        for sign in (1.0, -1.0):
            row = np.zeros(unknowns)
            row[f_at + i], row[n_at + i] = sign, -mu
            inequalities.append(row)
    bounds = [(None, None)] * joints + [(0, None)] * links + [(None, None)] * links + [(0, None)]
    cost = np.zeros(unknowns)
    cost[far] = -1.0
    result = linprog(cost, A_ub=np.array(inequalities), b_ub=np.zeros(len(inequalities)),
                     A_eq=np.array(equalities), b_eq=rhs, bounds=bounds, method="highs")
    return result.x[far] if result.status == 0 else float("nan")


def main():
    mu, cylinder = 0.2, 2.0
    print("links  alpha   rope_cm  holds     e^mu*theta")
    for rope in (0.2, 0.0):
        for links, alpha in ((19, math.pi / 18), (37, math.pi / 36), (73, math.pi / 72)):
            theta = (links - 1) * alpha
            holds = threshold(links, alpha, cylinder, rope, mu)
            print(f"{links:5d}  {alpha:.4f}  {rope:7.3f}  {holds:.6f}  {math.exp(mu * theta):.6f}")


if __name__ == "__main__":
    main()
