#!/usr/bin/env python3
"""Pinocchio's joint placements (oMi after forwardKinematics) along the UR5
and Panda URDF chains, for armkit's all-frames forward kinematics
(`kinematics::link_frames`, `armkit fk --all-frames`, Python `robot.fk_all`).

Chains (every joint off the chain locked at 0 with buildReducedModel, as
armkit's URDF loader does): urdf/ur5.urdf base_link -> tool0 and
urdf/panda.urdf panda_link0 -> panda_link8. Per chain: q = 0 and 20
configurations uniform within the joint limits (seed 20261204); per
configuration, each joint's name and its placement oMi (4x4, row-major,
metres, in the root link's frame), the frame of the child link the joint
moves.

Usage: python make_reference_frames.py   (Pinocchio 4.1.0, pip install pin==4.1.0)
Writes reference_frames.json beside this script.
"""
from __future__ import annotations

import json
from importlib.metadata import version
from pathlib import Path

import numpy as np
import pinocchio as pin

from make_reference_dynamics_published import chain_joints

HERE = Path(__file__).resolve().parent
SEED = 20261204
CHAINS = [
    ("ur5", "urdf/ur5.urdf", "base_link", "tool0"),
    ("panda", "urdf/panda.urdf", "panda_link0", "panda_link8"),
]


def main() -> None:
    rng = np.random.default_rng(SEED)
    out = {
        "made_by": f"Pinocchio {version('pin')} (buildModelFromUrdf, buildReducedModel, forwardKinematics, data.oMi), make_reference_frames.py, seed {SEED}",
        "conventions": "placement: 4x4 row-major homogeneous transform of the joint frame (the child link's frame) in the chain's root link frame, metres",
        "chains": [],
    }
    for name, urdf, base, tip in CHAINS:
        path = HERE / urdf
        joints = chain_joints(path, base, tip)
        keep = {j[0] for j in joints}
        full = pin.buildModelFromUrdf(str(path))
        lock = [full.getJointId(n) for n in full.names[1:] if n not in keep]
        model = pin.buildReducedModel(full, lock, pin.neutral(full)) if lock else full
        assert list(model.names[1:]) == [j[0] for j in joints], (name, list(model.names[1:]))
        data = model.createData()
        lower = np.array([j[1] for j in joints])
        upper = np.array([j[2] for j in joints])
        configurations = [np.zeros(len(joints))] + [rng.uniform(lower, upper) for _ in range(20)]
        samples = []
        for q in configurations:
            pin.forwardKinematics(model, data, q)
            samples.append({
                "q": q.tolist(),
                "placements": [data.oMi[i].homogeneous.reshape(-1).tolist() for i in range(1, model.njoints)],
            })
        out["chains"].append({
            "robot": name, "urdf": urdf, "base": base, "tip": tip,
            "joint_names": [j[0] for j in joints], "samples": samples,
        })
    (HERE / "reference_frames.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
