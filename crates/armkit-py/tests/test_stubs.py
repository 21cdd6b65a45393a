"""The type stubs match the extension: every class, function, parameter and
default (mypy's stubtest; PEP 800 disjoint bases are not marked). Skipped
only where mypy is not installed (scripts/test-all.sh installs it)."""

import subprocess
import sys

import pytest


def test_stubs_match_the_runtime():
    pytest.importorskip("mypy")
    result = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "armkit", "--ignore-disjoint-bases"],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_package_ships_the_stubs_and_py_typed():
    import armkit
    from pathlib import Path

    folder = Path(armkit.__file__).parent
    for name in ("py.typed", "_armkit.pyi", "dynamics.pyi", "redundancy.pyi", "singularity.pyi", "study.pyi"):
        assert (folder / name).is_file(), name
