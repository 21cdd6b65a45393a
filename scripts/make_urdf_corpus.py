#!/usr/bin/env python3
"""Build the URDF corpus test data: copy the URDF files of
example-robot-data into tests/data/urdf_corpus/ and write Pinocchio reference
forward kinematics and Jacobians for every root-to-leaf chain with two or more
moving joints into tests/data/urdf_corpus/reference.json.

Run with the peers' virtual environment (../shared/peers/setup.sh makes it:
pin 4.1.0, example-robot-data 6.0.0 from PyPI):

    PEERS_VENV/bin/python scripts/make_urdf_corpus.py

Mimic joints: the model is built with `mimic=False` (every joint independent)
and the script expands the mimic joints itself: the chain's configuration is
its independent joints (a mimic joint resolved to its first independent
leader, ordered by first appearance along the chain, as armkit does), the
full configuration sets q_m = multiplier * q_leader + offset, and the
Jacobian is J = J0 M (a mimic joint's column times its multiplier added to
its leader's). Pinocchio computes FK and J0; the expansion is the script's.

Chains that break the URDF specification (a revolute or prismatic joint
without <limit>) or that hold a joint armkit does not put on a chain
(floating, planar) are recorded with the rule, and the test expects armkit
to refuse them with that rule in the message.
"""
import json
import math
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin

SAMPLES = 3
SEED = 20
ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "tests" / "data" / "urdf_corpus"
MOVING = ("revolute", "continuous", "prismatic")


def source_dir():
    """The `robots` folder example-robot-data installs (under cmeel.prefix)."""
    import importlib.metadata as md
    for p in md.files("example-robot-data"):
        text = str(p)
        if text.endswith(".urdf") and "/robots/" in text:
            full = Path(p.locate()).resolve()
            return Path(str(full)[: str(full).index("/robots/") + len("/robots")])
    raise SystemExit("example-robot-data has no URDF files")


def parse(path):
    root = ET.parse(path).getroot()
    joints = {}
    for j in root.findall("joint"):
        mimic = j.find("mimic")
        joints[j.get("name")] = {
            "type": j.get("type"),
            "parent": j.find("parent").get("link"),
            "child": j.find("child").get("link"),
            "has_limit": j.find("limit") is not None,
            "limit": j.find("limit"),
            "mimic": None if mimic is None else (
                mimic.get("joint"),
                float(mimic.get("multiplier", "1")),
                float(mimic.get("offset", "0")),
            ),
        }
    links = [l.get("name") for l in root.findall("link")]
    inertias = {}
    for l in root.findall("link"):
        i = l.find("inertial/inertia")
        m = l.find("inertial/mass")
        if i is not None and m is not None and float(m.get("value", "0")) != 0.0:
            v = {k: float(i.get(k, "0")) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
            inertias[l.get("name")] = np.array([
                [v["ixx"], v["ixy"], v["ixz"]],
                [v["ixy"], v["iyy"], v["iyz"]],
                [v["ixz"], v["iyz"], v["izz"]],
            ])
    return links, joints, inertias


def non_physical_link(joints, inertias, first_moving):
    """A link armkit reads mass properties of (everything below the chain's
    first moving joint, except behind floating joints) whose inertia is not
    positive semi-definite (armkit's check: smallest eigenvalue below
    -1e-12 max(1, max |I_ij|)), or None."""
    pending = [joints[first_moving]["child"]]
    while pending:
        link = pending.pop()
        tensor = inertias.get(link)
        if tensor is not None:
            scale = max(1.0, np.abs(tensor).max())
            if np.linalg.eigvalsh(tensor).min() < -1e-12 * scale:
                return link
        for n, j in joints.items():
            if j["parent"] == link and j["type"] != "floating":
                pending.append(j["child"])
    return None


def chains(links, joints):
    parent_joint = {j["child"]: n for n, j in joints.items()}
    children = {l: [] for l in links}
    for n, j in joints.items():
        children[j["parent"]].append(n)
    out = []
    for leaf in links:
        if children[leaf]:
            continue
        path, link = [], leaf
        while link in parent_joint:
            path.append(parent_joint[link])
            link = joints[parent_joint[link]]["parent"]
        path.reverse()
        moving = [n for n in path if joints[n]["type"] in MOVING]
        if len(moving) >= 2:
            out.append((link, leaf, path))
    return out


def resolve(joints, name):
    """(independent leader, multiplier, offset), or a string saying why not."""
    m, o = 1.0, 0.0
    seen = [name]
    while joints[name]["mimic"] is not None:
        leader, mm, oo = joints[name]["mimic"]
        if leader not in joints:
            return "the file has no joint named `%s`" % leader
        if joints[leader]["type"] not in MOVING:
            return "a mimic joint must follow a revolute, continuous or prismatic joint"
        o += m * oo
        m *= mm
        name = leader
        if name in seen:
            return "the mimic joints form a cycle"
        seen.append(name)
    return name, m, o


def bounds(joints, name):
    j = joints[name]
    lim = j["limit"]
    if j["type"] == "continuous" or lim is None:
        return -math.pi, math.pi
    lo, hi = float(lim.get("lower", "0")), float(lim.get("upper", "0"))
    return (lo, hi) if lo < hi else (lo - 0.5, lo + 0.5)


def set_joint(model, q, name, value):
    jid = model.getJointId(name)
    jm = model.joints[jid]
    if jm.nq == 2:  # continuous: (cos, sin)
        q[jm.idx_q], q[jm.idx_q + 1] = math.cos(value), math.sin(value)
    else:
        q[jm.idx_q] = value


def main():
    src = source_dir()
    OUT.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(SEED)
    files = []
    for path in sorted(src.rglob("*.urdf")):
        rel = path.relative_to(src)
        dest = OUT / str(rel).replace("/", "__")
        shutil.copyfile(path, dest)
        entry = {"file": dest.name, "source": str(rel), "chains": []}
        try:
            links, joints, inertias = parse(path)
            model = pin.buildModelFromUrdf(str(path))
        except (ValueError, RuntimeError, ET.ParseError) as e:
            entry["pinocchio_error"] = str(e).replace(str(src), "")
            files.append(entry)
            continue
        data = model.createData()
        for base, tip, path_joints in chains(links, joints):
            chain = {"base": base, "tip": tip}
            moving = [n for n in path_joints if joints[n]["type"] in MOVING]
            bad = [n for n in path_joints if joints[n]["type"] in ("floating", "planar", "spherical")]
            nolimit = [n for n in moving if joints[n]["type"] != "continuous" and not joints[n]["has_limit"]]
            if bad:
                chain["refused"] = "only revolute, continuous, prismatic and fixed joints can be on the chain"
                chain["joint"] = bad[0]
            elif nolimit:
                chain["refused"] = "the URDF specification requires <limit>"
                chain["joint"] = nolimit[0]
            elif non_physical_link(joints, inertias, moving[0]) is not None:
                chain["refused"] = "inertia must be positive semi-definite"
                chain["joint"] = non_physical_link(joints, inertias, moving[0])
            if "refused" in chain:
                entry["chains"].append(chain)
                continue
            drives = [resolve(joints, n) for n in moving]
            why = [(n, d) for n, d in zip(moving, drives) if isinstance(d, str)]
            if why:
                chain["joint"], chain["refused"] = why[0]
                entry["chains"].append(chain)
                continue
            independent = []
            for leader, _, _ in drives:
                if leader not in independent:
                    independent.append(leader)
            chain["joint_names"] = independent
            chain["mimic"] = [n for n, d in zip(moving, drives) if joints[n]["mimic"] is not None]
            frame = model.getFrameId(tip)
            samples = []
            for _ in range(SAMPLES):
                qi = [rng.uniform(*bounds(joints, n)) for n in independent]
                q = pin.neutral(model)
                for n, (leader, m, o) in zip(moving, drives):
                    set_joint(model, q, n, m * qi[independent.index(leader)] + o)
                pin.computeJointJacobians(model, data, q)
                pin.updateFramePlacements(model, data)
                pose = data.oMf[frame].homogeneous
                j0 = pin.getFrameJacobian(model, data, frame, pin.LOCAL_WORLD_ALIGNED)
                jac = np.zeros((6, len(independent)))
                for n, (leader, m, _) in zip(moving, drives):
                    jac[:, independent.index(leader)] += m * j0[:, model.joints[model.getJointId(n)].idx_v]
                samples.append({"q": qi, "pose": pose.tolist(), "jacobian": jac.tolist()})
            chain["samples"] = samples
            entry["chains"].append(chain)
        files.append(entry)
    reference = {
        "made_by": f"Pinocchio {pin.__version__}, example-robot-data 6.0.0, scripts/make_urdf_corpus.py (seed {SEED}, {SAMPLES} samples per chain; mimic joints expanded by the script)",
        "files": files,
    }
    with open(OUT / "reference.json", "w") as f:
        json.dump(reference, f, separators=(",", ":"))
    n = sum(len(e["chains"]) for e in files)
    r = sum(1 for e in files for c in e["chains"] if "refused" in c)
    print(f"{len(files)} files, {n} chains, {r} expected refusals")


if __name__ == "__main__":
    main()
