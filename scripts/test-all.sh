#!/usr/bin/env bash
# The README's test command: the Rust suite, then the Python package's suite.
#
#   1. cargo test --workspace --release
#   2. the armkit wheel built by pip (pip fetches maturin, the build backend,
#      from PyPI) into a fresh virtual environment with numpy, pytest and
#      mypy (its stubtest checks the type stubs),
#      then pytest on crates/armkit-py/tests.
#
# Needs Rust and Python >= 3.9 with pip and venv. PYTHON picks the
# interpreter (default python3); ARMKIT_PY_VENV the environment's folder
# (default target/py-venv, made afresh each run).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== Rust: cargo test --workspace --release"
cargo test --workspace --release

PYTHON="${PYTHON:-python3}"
VENV="${ARMKIT_PY_VENV:-target/py-venv}"
WHEELS=target/py-wheels
echo "== Python: wheel, then pytest (venv $VENV)"
rm -rf "$VENV" "$WHEELS"
"$PYTHON" -m venv "$VENV"
"$VENV/bin/python" -m pip install -q --disable-pip-version-check numpy pytest mypy
"$VENV/bin/python" -m pip wheel -q --disable-pip-version-check --no-deps -w "$WHEELS" crates/armkit-py
"$VENV/bin/python" -m pip install -q --disable-pip-version-check "$WHEELS"/armkit-*.whl
# From outside the source tree, so that the installed wheel is what is tested.
(cd "$VENV" && bin/python -m pytest -q -p no:cacheprovider "$OLDPWD/crates/armkit-py/tests")
