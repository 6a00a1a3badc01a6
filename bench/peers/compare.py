#!/usr/bin/env python3
"""Peer comparison: the knotted hagfish state stepped by MuJoCo and by hagfish.

1. `cargo xtask knotted --export` writes the 100-body model and the knotted state
   (data/scenarios/form.ron at t = 23.13 s) as JSON.
2. This script builds the same chain in MuJoCo (MJCF generated from the JSON): masses,
   principal inertias, X-revolute and YZ-universal joints (two hinges, Y then Z), joint
   stiffness with the rest angles as spring references, damping, limits, one capsule per body
   with its radius, no gravity; the head (root joint, held at rest by hagfish's head rows) is
   welded to the wall. Capsule pairs less than 9 bodies apart are excluded from contact, as
   hagfish ignores self contacts with an index gap <= 8.
3. It checks that the MuJoCo body centres of the exported q equal hagfish's (joint order and
   frames match), then times passive steps (no controller, no drag) from the knotted state at
   h = 1e-3 and 1e-2: median wall time per step over repeated runs, contacts, stability.
4. It runs `cargo xtask knotted` for hagfish's numbers on the same state in the same run
   (`--backend sparse`, the default; `dense` or `both` for the dense reduced backend).

Usage (from the workspace root):  python3 bench/peers/compare.py [--steps N] [--repeat R]
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import mujoco
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
INDEX_GAP = 8


def xtask(*args):
    """Runs `cargo xtask ...` in the workspace and returns its stdout."""
    command = ["cargo", "xtask", *args]
    result = subprocess.run(command, cwd=ROOT, check=True, capture_output=True, text=True)
    return result.stdout


def quaternion(matrix):
    """(w, x, y, z) of a rotation matrix given as a list of column vectors."""
    m = np.array(matrix).T  # rows
    w = math.sqrt(max(0.0, 1.0 + m[0, 0] + m[1, 1] + m[2, 2])) / 2.0
    x = math.copysign(math.sqrt(max(0.0, 1.0 + m[0, 0] - m[1, 1] - m[2, 2])) / 2.0, m[2, 1] - m[1, 2])
    y = math.copysign(math.sqrt(max(0.0, 1.0 - m[0, 0] + m[1, 1] - m[2, 2])) / 2.0, m[0, 2] - m[2, 0])
    z = math.copysign(math.sqrt(max(0.0, 1.0 - m[0, 0] - m[1, 1] + m[2, 2])) / 2.0, m[1, 0] - m[0, 1])
    return [w, x, y, z]


def multiply(a, b):
    """Quaternion product a*b."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return [
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    ]


def axis_angle(axis, angle):
    s = math.sin(angle / 2.0)
    return [math.cos(angle / 2.0), axis[0] * s, axis[1] * s, axis[2] * s]


def joint_axes(kind):
    """Hinge axes of a hagfish joint kind, in order."""
    if kind == "universal_yz":
        return [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    if kind == "fixed":
        return []
    if kind == "translation":
        raise ValueError("a translation joint has no hinge axes; MJCF export covers hinges only")
    return [kind["revolute"]]


def mjcf(model, time_step):
    """MJCF of the exported hagfish model; the root joint welded at its rest angles."""
    fmt = lambda v: " ".join(repr(float(x)) for x in v)
    bodies, joints, dofs = model["bodies"], model["joints"], model["dofs"]
    lines = []
    for i, (body, joint) in enumerate(zip(bodies, joints)):
        quat = quaternion(joint["rotation"])
        axes = joint_axes(joint["kind"])
        start = joint["dof_start"]
        if joint["parent"] is None:
            for k, axis in enumerate(axes):  # welded: bake the rest rotation into the frame
                quat = multiply(quat, axis_angle(axis, dofs[start + k]["rest"]))
        lines.append(f'<body name="b{i}" pos="{fmt(joint["offset"])}" quat="{fmt(quat)}">')
        if joint["parent"] is not None:
            for k, axis in enumerate(axes):
                d = dofs[start + k]
                limited = d["lower"] is not None and d["upper"] is not None
                limit = f' range="{d["lower"]!r} {d["upper"]!r}"' if limited else ""
                lines.append(
                    f'<joint name="j{start + k}" type="hinge" axis="{fmt(axis)}" '
                    f'stiffness="{d["stiffness"]!r}" springref="{d["rest"]!r}" '
                    f'damping="{d["damping"]!r}" limited="{str(limited).lower()}"{limit}/>'
                )
        offset = body["offset"]
        lines.append(
            f'<inertial pos="{fmt(offset)}" mass="{body["mass"]!r}" '
            f'diaginertia="{fmt(body["principal_inertia"])}"/>'
        )
        half = body["length"] / 2.0
        start_point = [offset[0] - half, offset[1], offset[2]]
        end_point = [offset[0] + half, offset[1], offset[2]]
        lines.append(
            f'<geom type="capsule" fromto="{fmt(start_point + end_point)}" size="{body["radius"]!r}"/>'
        )
    lines.extend("</body>" for _ in bodies)
    excludes = [
        f'<exclude body1="b{i}" body2="b{j}"/>'
        for i in range(len(bodies))
        for j in range(i + 1, min(len(bodies), i + INDEX_GAP + 1))
    ]
    return f"""<mujoco model="hagfish-es103">
<compiler angle="radian" autolimits="true"/>
<option timestep="{time_step!r}" gravity="{fmt(model["gravity"])}" integrator="implicitfast"/>
<worldbody>
{chr(10).join(lines)}
</worldbody>
<contact>
{chr(10).join(excludes)}
</contact>
</mujoco>"""


def state_indices(model):
    """Hagfish DOF indices of the MuJoCo qpos entries (root joint excluded)."""
    indices = []
    for joint in model["joints"]:
        if joint["parent"] is None:
            continue
        indices.extend(range(joint["dof_start"], joint["dof_start"] + len(joint_axes(joint["kind"]))))
    return indices


def set_state(mj_model, data, exported, indices):
    mujoco.mj_resetData(mj_model, data)
    data.qpos[:] = [exported["q"][i] for i in indices]
    data.qvel[:] = [exported["qdot"][i] for i in indices]
    mujoco.mj_forward(mj_model, data)


def time_mujoco(exported, time_step, steps, repeat):
    mj_model = mujoco.MjModel.from_xml_string(mjcf(exported, time_step))
    data = mujoco.MjData(mj_model)
    indices = state_indices(exported)
    set_state(mj_model, data, exported, indices)
    centres = np.array(exported["centres"])
    centre_error = float(np.max(np.linalg.norm(data.xipos[1:] - centres, axis=1)))
    initial_contacts = int(data.ncon)
    deepest = float(min([data.contact[k].dist for k in range(data.ncon)], default=0.0))
    per_step, contacts, unstable = [], [], 0
    max_qvel, displacement = 0.0, 0.0
    for _ in range(repeat):
        set_state(mj_model, data, exported, indices)
        for _ in range(steps):
            start = time.perf_counter()
            mujoco.mj_step(mj_model, data)
            per_step.append(time.perf_counter() - start)
            contacts.append(data.ncon)
        finite = np.all(np.isfinite(data.qvel))
        warnings = sum(int(w.number) for w in data.warning)
        if not finite or warnings > 0:
            unstable += 1
        max_qvel = max(max_qvel, float(np.max(np.abs(data.qvel))) if finite else math.inf)
        moved = np.max(np.linalg.norm(data.xipos[1:] - centres, axis=1))
        displacement = max(displacement, float(moved))
    median = statistics.median(per_step)
    return {
        "simulator": f"mujoco {mujoco.__version__}",
        "time_step": time_step,
        "steps": steps,
        "repeat": repeat,
        "median_us_per_step": round(1e6 * median, 2),
        "min_us_per_step": round(1e6 * min(per_step), 2),
        "steps_per_second": round(1.0 / median),
        "median_contacts": statistics.median(contacts),
        "max_contacts": max(contacts),
        "initial_contacts": initial_contacts,
        "initial_deepest_penetration_cm": round(-deepest, 4),
        "unstable_runs": unstable,
        "max_abs_qvel": max_qvel,
        "max_centre_displacement_cm": round(displacement, 4),
        "centre_error_cm": centre_error,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=100, help="steps per timed run")
    parser.add_argument("--repeat", type=int, default=20, help="timed runs per time step")
    parser.add_argument(
        "--backend",
        choices=["dense", "sparse", "both"],
        default="sparse",
        help="hagfish dynamics backend (sparse: the default of every scenario)",
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "knotted.json")
        xtask("knotted", "--export", path, "--steps", "0")
        with open(path) as f:
            exported = json.load(f)
    print(f"state: {exported['source']}, {exported['self_contacts']} hagfish self contacts")
    results = []
    for h in (1e-3, 1e-2):
        results.append(time_mujoco(exported, h, args.steps, args.repeat))
        backends = ["dense", "sparse"] if args.backend == "both" else [args.backend]
        for backend in backends:
            hagfish = xtask(
                "knotted", "--steps", str(args.steps), "--repeat", str(args.repeat),
                "--time-step", str(h), "--backend", backend,
            )
            results.append(json.loads(hagfish))
    for r in results:
        print(json.dumps(r))
    print()
    print(f"{'simulator':<14} {'h (s)':>7} {'median us/step':>15} {'steps/s':>9} {'contacts':>9} {'stable':>7}")
    for r in results:
        stable = (r.get("unstable_runs", 0) + r.get("failed_runs", 0)) == 0
        print(
            f"{r['simulator']:<14} {r['time_step']:>7} {r['median_us_per_step']:>15} "
            f"{r['steps_per_second']:>9} {r['median_contacts']:>9} {str(stable):>7}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
