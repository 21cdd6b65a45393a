#!/usr/bin/env bash
# The README's test command: the Rust suite, then the Python package's suite.
#
#   1. cargo test --workspace --release (four test binaries and the merged
#      doctests). The browser tests (`demo_browser`, `view_browser`) open the
#      demo's reports and `armkit view`'s pages in headless Chromium when it
#      is installed (scripts/install-browser.sh) and skip that half with a
#      message when it is not; ARMKIT_REQUIRE_BROWSER=1 makes a missing
#      Chromium a failure (.ci/run sets it once Chromium is installed).
#   2. the armkit wheel built by pip (pip fetches maturin, the build backend,
#      from PyPI; the wheel reuses the Rust build of step 1) into a fresh
#      virtual environment with numpy, pytest, mypy (its stubtest checks
#      the type stubs) and the package's optional dask and zarr extras (the
#      reachability map's Dask and Zarr tests), then pytest on
#      crates/armkit-py/tests.
#
# Each stage prints a line when it starts and its time when it ends; where the
# output is not a terminal (CI, a pipe), a line every 30 s says the stage is
# still running, since cargo then hides its progress bar.
#
# Needs Rust and Python >= 3.9 with pip and venv. PYTHON picks the
# interpreter (default python3); ARMKIT_PY_VENV the environment's folder
# (default target/py-venv, made afresh each run).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage.sh

# example-robot-data's UR5 and Panda with their meshes, for the view's
# browser test, where the peers' environment (../shared/peers/setup.sh) is
# installed; that test is skipped otherwise.
if [ -z "${ARMKIT_EXAMPLE_ROBOT_DATA:-}" ]; then
  for share in ../shared/peers/.venv/lib/python3*/site-packages/cmeel.prefix/share; do
    if [ -d "$share/example-robot-data" ]; then export ARMKIT_EXAMPLE_ROBOT_DATA="$PWD/$share"; fi
  done
fi

stage "Rust: cargo test --workspace --release" \
    cargo test --workspace --release

PYTHON="${PYTHON:-python3}"
VENV="${ARMKIT_PY_VENV:-target/py-venv}"
WHEELS=target/py-wheels
PIP=(-m pip --disable-pip-version-check)
rm -rf "$VENV" "$WHEELS"
stage "Python: a virtual environment with numpy, pytest, mypy, dask and zarr ($VENV)" \
    bash -c "'$PYTHON' -m venv '$VENV' && '$VENV/bin/python' ${PIP[*]} install -q numpy pytest mypy 'dask[distributed]' zarr"
# Verbose, so that maturin's cargo build shows as it goes.
stage "Python: the armkit wheel (pip wheel: maturin, then cargo build --release)" \
    "$VENV/bin/python" "${PIP[@]}" wheel -v --no-deps -w "$WHEELS" crates/armkit-py
stage "Python: install the wheel" \
    bash -c "'$VENV/bin/python' ${PIP[*]} install -q '$WHEELS'/armkit-*.whl"
# From outside the source tree, so that the installed wheel is what is tested.
stage "Python: pytest" \
    bash -c "cd '$VENV' && bin/python -m pytest -q -p no:cacheprovider '$PWD/crates/armkit-py/tests'"
stage_summary
