#!/usr/bin/env python3
"""Peer check: the frictionless loose trefoil's braid force, hagfish against MuJoCo's rods.

Audoly, Clauvelin & Neukirch (2007) give the loose trefoil's braid a total normal force
N = sigma B eps^3 / h^2 (sigma = 0.492) at leading order in eps = sqrt(h/R). hagfish's braid
presses harder at finite eps (N h^2/(sigma B eps^3) = 1 + 3.3 eps, docs/validation.md). This
script asks whether another simulator's rods do the same, on the same rod, pull and knot:
1. `cargo xtask braid --radius H --force F --export FILE` settles the knot in hagfish (400
   bodies, 120 s at the pull) and writes the rod, N, the loop radius and the settled centreline.
2. MuJoCo (4.0's 1D flex: discrete elastic rods, Bergou et al. 2008) gets the same rod: bending
   stiffness E I = B and torsion G J = C for a circular section of radius h, the same mass, edges
   kept at their length by the flex's edge equality, frictionless capsule self contact
   (condim 1) of radius h; the first edge clamped at the head, the tail pulled along +X by F
   (ramped over 1 s), posed on hagfish's centreline (resampled at equal arc length; the rest
   shape straight) and settled with a linear drag on the vertices. Edges are at least 2.5 h
   long, so that no two non-adjacent capsules touch on a straight rod.
3. It prints N and N h^2/(sigma B eps^3) for both, with eps = (2 F h^2 / B)^(1/4) of the law and
   with eps = sqrt(h / R) of the loop radius R each settled at, N averaged
   over MuJoCo's last second (its spread beside it), and both loop radii where the tangent is
   perpendicular to the pull against sqrt(B / 2F), which the first integral gives a
   frictionless knot exactly: that column is each simulator's own error on a known answer.
Usage (from the workspace root):  python3 bench/peers/audoly_braid.py [--cases H:F,...]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import mujoco
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SIGMA = 0.492
# Linear drag per length of rod on the vertices (dyn s/cm^2): settles the knot's slow modes.
DRAG_PER_LENGTH = 3.0
# Rayleigh damping of the rod's elasticity (s).
ELASTIC_DAMPING_S = 0.01


def hagfish_braid(radius, force):
    """Runs `cargo xtask braid` and returns its export."""
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "braid.json")
        command = ["cargo", "xtask", "braid", "--radius", str(radius), "--force", str(force),
                   "--export", path]
        subprocess.run(command, cwd=ROOT, check=True, capture_output=True, text=True)
        with open(path) as f:
            return json.load(f)


def mjcf(rod, edges, time_step):
    """MJCF of the rod as a straight 1D flex of `edges` edges, its first edge clamped."""
    h, length = rod["radius_cm"], rod["length_cm"]
    second_moment = math.pi * h**4 / 4
    young = rod["bending_stiffness_dyn_cm2"] / second_moment
    shear = rod["twist_stiffness_dyn_cm2"] / (2 * second_moment)
    mass = rod["density_g_per_cm3"] * math.pi * h * h * length
    spacing = length / edges
    points = " ".join(f"{i * spacing!r} 0 0" for i in range(edges + 1))
    elements = " ".join(f"{i} {i + 1}" for i in range(edges))
    return f"""<mujoco model="loose-trefoil">
<option timestep="{time_step!r}" gravity="0 0 0" integrator="discrete" solver="Newton"
        iterations="100" tolerance="1e-12"/>
<size memory="200M"/>
<worldbody>
<flexcomp name="rod" type="direct" dim="1" radius="{h!r}" mass="{mass!r}" point="{points}"
          element="{elements}">
  <pin id="0 1"/>
  <edge equality="true"/>
  <elasticity young="{young!r}" shear="{shear!r}" damping="{ELASTIC_DAMPING_S}"/>
  <contact condim="1" selfcollide="auto" solref="{2 * time_step!r} 1" solimp="0.99 0.999 0.0001"/>
</flexcomp>
</worldbody>
</mujoco>"""


def resampled(centreline, edges):
    """`edges` + 1 points at equal arc length along the polyline `centreline`."""
    points = np.array(centreline)
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    at = np.linspace(0.0, arc[-1], edges + 1)
    return np.stack([np.interp(at, arc, points[:, k]) for k in range(3)], axis=1)


def loop_radii(points):
    """Radius of the circle through three consecutive points wherever the tangent's x changes
    sign (the loop's points perpendicular to the pull along +X)."""
    radii = []
    tangents = np.diff(points, axis=0)
    for i in range(1, len(tangents)):
        if tangents[i - 1][0] * tangents[i][0] < 0:
            a, b, c = points[i - 1], points[i], points[i + 1]
            area = 0.5 * np.linalg.norm(np.cross(b - a, c - a))
            sides = np.linalg.norm(b - a) * np.linalg.norm(c - b) * np.linalg.norm(a - c)
            radii.append(sides / (4 * area))
    return radii


def settle_in_mujoco(export, edges, time_step, seconds):
    """Settles the exported knot in MuJoCo; returns its measures."""
    rod = export["rod"]
    model = mujoco.MjModel.from_xml_string(mjcf(rod, edges, time_step))
    data = mujoco.MjData(model)
    spacing = rod["length_cm"] / edges
    start = resampled(export["centreline_cm"], edges)
    # Points 0 and 1 are pinned; point i ≥ 2 is body rod_i, three slide joints from (i ℓ, 0, 0).
    vertex = [model.body(f"rod_{i}").id for i in range(2, edges + 1)]
    for i, body in enumerate(vertex, start=2):
        address = model.jnt_qposadr[model.body_jntadr[body]]
        data.qpos[address:address + 3] = start[i] - np.array([i * spacing, 0.0, 0.0])
    mujoco.mj_forward(model, data)
    slides = np.array([model.jnt_dofadr[j] for j in range(model.njnt)
                       if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_SLIDE])
    drag = DRAG_PER_LENGTH * spacing
    tail = vertex[-1]
    steps = int(round(seconds / time_step))
    window = int(round(1.0 / time_step))
    forces, contacts, deepest = [], [], 0.0
    wrench = np.zeros(6)
    for step in range(steps):
        data.xfrc_applied[tail, 0] = min(1.0, data.time) * export["tension_dyn"]
        data.qfrc_applied[slides] = -drag * data.qvel[slides]
        mujoco.mj_step(model, data)
        if step >= steps - window:
            total = 0.0
            for c in range(data.ncon):
                mujoco.mj_contactForce(model, data, c, wrench)
                total += wrench[0]
                deepest = min(deepest, data.contact[c].dist)
            forces.append(total)
            contacts.append(data.ncon)
    warnings = sum(int(w.number) for w in data.warning)
    points = np.vstack([start[:2], data.xpos[vertex]])
    forces = np.array(forces)
    return {
        "edges": edges,
        "edge_cm": spacing,
        "normal_force_dyn": float(forces.mean()),
        "spread": float((forces.max() - forces.min()) / forces.mean()),
        "contacts": float(np.mean(contacts)),
        "deepest_penetration_over_h": -deepest / rod["radius_cm"],
        "loop_radii_cm": loop_radii(points),
        "stable": bool(np.all(np.isfinite(data.qvel))) and warnings == 0,
    }


def number(normal_force, export, epsilon):
    """N h^2/(sigma B eps^3)."""
    rod = export["rod"]
    h, b = rod["radius_cm"], rod["bending_stiffness_dyn_cm2"]
    return normal_force * h * h / (SIGMA * b * epsilon**3)


def numbers(normal_force, export, loop_radius):
    """The normal-force number with eps = (2 F h^2 / B)^(1/4) (the law's, from the pull) and
    with eps = sqrt(h / R) of the loop radius R the simulator settled at (as the controls of
    `cargo xtask audoly --control` count it), as a table cell."""
    by_pull = number(normal_force, export, export["epsilon"])
    by_loop = number(normal_force, export, math.sqrt(export["rod"]["radius_cm"] / loop_radius))
    return f"{by_pull:.3f} / {by_loop:.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default="0.02:10,0.08:10,0.18:10",
                        help="rod radius (cm) : pull (dyn), comma separated")
    parser.add_argument("--seconds", type=float, default=90.0, help="MuJoCo's settling time (s)")
    parser.add_argument("--time-step", type=float, default=5e-4, help="MuJoCo's time step (s)")
    args = parser.parse_args()
    print("| h (cm) | F (dyn) | ε | simulator | edge (cm) | N (dyn) | N h²/(σBε³), ε from F / from R | N / hagfish's | "
          "loop radius / √(B/2F) | N's spread over 1 s | deepest penetration (% h) | contacts | stable |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in args.cases.split(","):
        radius, force = (float(x) for x in case.split(":"))
        export = hagfish_braid(radius, force)
        law = export["law_loop_radius_cm"]
        head = f"| {radius} | {force} | {export['epsilon']:.4f}"
        rod = export["rod"]
        print(f"{head} | hagfish ({rod['bodies']} bodies) | {rod['length_cm'] / rod['bodies']:.3f} | "
              f"{export['normal_force_dyn']:.2f} | "
              f"{numbers(export['normal_force_dyn'], export, export['loop_radius_cm'])} | 1 | "
              f"{export['loop_radius_cm'] / law:.4f} | — | — | {export['self_contacts']} | True |")
        shortest = max(2.5 * radius, 0.2)
        for edge in (shortest, 4.0 * shortest / 3.0):
            edges = int(rod["length_cm"] / edge)
            peer = settle_in_mujoco(export, edges, args.time_step, args.seconds)
            n = peer["normal_force_dyn"]
            radii = " / ".join(f"{r / law:.4f}" for r in peer["loop_radii_cm"]) or "—"
            print(f"{head} | MuJoCo {mujoco.__version__} | {peer['edge_cm']:.3f} | {n:.2f} | "
                  f"{numbers(n, export, np.mean(peer['loop_radii_cm']))} | "
                  f"{n / export['normal_force_dyn']:.3f} | {radii} | "
                  f"{100 * peer['spread']:.2f} % | {100 * peer['deepest_penetration_over_h']:.3f} | "
                  f"{peer['contacts']:.1f} | {peer['stable']} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
