#!/usr/bin/env python3
"""Pinocchio's inverse dynamics and mass matrix on chains of published URDFs
whose mass properties are unusual, for armkit's dynamics tests.

Chains (base -> tip; every joint off the chain locked at 0 with
buildReducedModel, as armkit's URDF loader does):
  al5d       urdf/al5d.urdf (rtb-data 2.0.0, Lynxmotion AL5D), base -> link4:
             point masses on the joint axes, so M(q) is singular (the last
             row and column vanish) at every configuration;
  human_leg  urdf_corpus/human_description__robots__human.urdf
             (example-robot-data 6.0.0), middle_pelvis -> right_foot:
             massless links between the hip and ankle joints, M positive
             definite;
  bolt_leg   urdf_corpus/bolt_description__robots__bolt.urdf
             (example-robot-data 6.0.0), base_link -> FL_FOOT: the foot has
             zero mass and a non-zero inertia tensor, fixed to the lower leg.

Per chain: q = 0 and 5 configurations uniform within the joint limits
(seed 20261204), v in [-1, 1], a in [-2, 2]:
  tau = rnea(q, v, a), mass_matrix = crba(q) (symmetrized),
  gravity = computeGeneralizedGravity(q), and M's smallest and largest
  eigenvalues (numpy.linalg.eigvalsh) for information.
Gravity (0, 0, -9.81) m/s^2 in the root link's frame (the base of each chain).

Usage: python make_reference_dynamics_published.py
Writes reference_dynamics_<chain>.json beside this script.
"""
from __future__ import annotations

import hashlib
import json
import xml.etree.ElementTree as ET
from importlib.metadata import version
from pathlib import Path

import numpy as np
import pinocchio as pin

HERE = Path(__file__).resolve().parent
SEED = 20261204
CHAINS = [
    ("al5d", "urdf/al5d.urdf", "base", "link4"),
    ("human_leg", "urdf_corpus/human_description__robots__human.urdf", "middle_pelvis", "right_foot"),
    ("bolt_leg", "urdf_corpus/bolt_description__robots__bolt.urdf", "base_link", "FL_FOOT"),
]


def chain_joints(path: Path, base: str, tip: str) -> list[tuple[str, float, float]]:
    """The moving joints from base to tip, with their limits, base first."""
    by_child = {}
    for joint in ET.parse(path).getroot().iter("joint"):
        by_child[joint.find("child").get("link")] = joint
    joints, link = [], tip
    while link != base:
        joint = by_child[link]
        if joint.get("type") != "fixed":
            limit = joint.find("limit")
            joints.append((joint.get("name"), float(limit.get("lower")), float(limit.get("upper"))))
        link = joint.find("parent").get("link")
    return joints[::-1]


def main() -> None:
    rng = np.random.default_rng(SEED)
    for name, urdf, base, tip in CHAINS:
        path = HERE / urdf
        joints = chain_joints(path, base, tip)
        keep = {j[0] for j in joints}
        full = pin.buildModelFromUrdf(str(path))
        lock = [full.getJointId(n) for n in full.names[1:] if n not in keep]
        model = pin.buildReducedModel(full, lock, pin.neutral(full)) if lock else full
        assert list(model.names[1:]) == [j[0] for j in joints], (name, list(model.names[1:]))
        assert model.nq == model.nv == len(joints)
        model.gravity.linear = np.array([0.0, 0.0, -9.81])
        data = model.createData()
        n = len(joints)
        lower = np.array([j[1] for j in joints])
        upper = np.array([j[2] for j in joints])
        configurations = [np.zeros(n)] + [rng.uniform(lower, upper) for _ in range(5)]
        samples = []
        for q in configurations:
            v = rng.uniform(-1, 1, n)
            a = rng.uniform(-2, 2, n)
            tau = pin.rnea(model, data, q, v, a).copy()
            m = pin.crba(model, data, q).copy()
            m = np.triu(m) + np.triu(m, 1).T
            g = pin.computeGeneralizedGravity(model, data, q).copy()
            eigenvalues = np.linalg.eigvalsh(m)
            samples.append({
                "q": q.tolist(), "v": v.tolist(), "a": a.tolist(), "tau": tau.tolist(),
                "mass_matrix": m.tolist(), "gravity": g.tolist(),
                "mass_matrix_eigenvalues": [float(eigenvalues[0]), float(eigenvalues[-1])],
            })
        out = {
            "chain": name, "source": f"Pinocchio {pin.__version__}", "urdf": urdf,
            "urdf_sha256": hashlib.sha256(path.read_bytes()).hexdigest(), "base": base, "tip": tip,
            "joint_names": [j[0] for j in joints], "gravity": [0.0, 0.0, -9.81],
            "versions": {p: version(p) for p in ["pin", "example-robot-data", "rtb-data", "numpy"]},
            "conventions": {"q, v, a": "rad, rad/s, rad/s^2, joint_names order",
                            "tau, gravity": "N m", "mass_matrix": "n x n, row-major, kg m^2",
                            "mass_matrix_eigenvalues": "smallest and largest eigenvalue of mass_matrix"},
            "samples": samples,
        }
        (HERE / f"reference_dynamics_{name}.json").write_text(json.dumps(out, indent=1) + "\n")
        smallest = min(s["mass_matrix_eigenvalues"][0] / s["mass_matrix_eigenvalues"][1] for s in samples)
        print(f"{name}: {n} joints, {len(samples)} samples, smallest eigenvalue ratio {smallest:.1e}")


if __name__ == "__main__":
    main()
