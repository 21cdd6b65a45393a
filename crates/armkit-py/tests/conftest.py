"""Shared fixtures: where the reference data is, and loading it.

The reference files are the repository's copies in tests/data (as the Rust
tests use them); a file not copied there is read from ../shared/reference
beside the repository.
"""

import json
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
DATA = REPO / "tests" / "data"
SHARED = REPO.parent / "shared" / "reference"


def data_file(name: str) -> Path:
    """tests/data/NAME, else ../shared/reference/NAME; skips when neither exists."""
    for folder in (DATA, SHARED):
        if (folder / name).is_file():
            return folder / name
    pytest.skip(f"reference file {name} is in neither {DATA} nor {SHARED}")


def reference(name: str) -> dict:
    """A reference file with its samples as arrays: q (N, dof), pose (N, 4, 4), jacobian (N, 6, dof)."""
    with open(data_file(name)) as f:
        ref = json.load(f)
    samples = ref["samples"]
    ref["Q"] = np.array([s["q"] for s in samples])
    if "pose" in samples[0]:
        ref["poses"] = np.array([s["pose"] for s in samples])
    if "jacobian" in samples[0]:
        ref["jacobians"] = np.array([s["jacobian"] for s in samples])
    return ref


@pytest.fixture(scope="session")
def ur5():
    import armkit

    return armkit.Robot.builtin("ur5")
