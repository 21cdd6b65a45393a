#!/usr/bin/env bash
# The browser half of the end-to-end tests (crates/armkit-cli/tests/it/
# demo_browser.rs: the demo's reports; view_browser.rs: `armkit view` on a URDF
# with meshes, its link transforms read back from the page against armkit's
# FK), which the README's test command skips with a message when Chromium is
# missing: installs Debian's chromium when it is missing (as root,
# or with sudo), then runs that test with ARMKIT_REQUIRE_BROWSER=1 so that a
# missing browser fails it. Where Chromium cannot be installed, says so and
# exits 0 (the rest of the test ran in the README's command). Called by
# .ci/run after the README's test command.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  { $SUDO apt-get update -q >/dev/null \
    && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q chromium >/dev/null; } \
    || true
fi
if ! command -v chromium >/dev/null 2>&1; then
  echo "chromium could not be installed: the browser half of the demo test was not run"
  exit 0
fi
# The same selection as the README's test command (--workspace --release), so
# that cargo reuses its build instead of building the dependencies again with
# another feature set; the filter runs only the browser tests.
# example-robot-data's UR5 and Panda with their meshes, where the peers'
# environment (../shared/peers/setup.sh) is installed; skipped otherwise.
if [ -z "${ARMKIT_EXAMPLE_ROBOT_DATA:-}" ]; then
  for share in ../shared/peers/.venv/lib/python3*/site-packages/cmeel.prefix/share; do
    if [ -d "$share/example-robot-data" ]; then export ARMKIT_EXAMPLE_ROBOT_DATA="$PWD/$share"; fi
  done
fi
# Both modules (demo_browser, view_browser) end in `browser`.
ARMKIT_REQUIRE_BROWSER=1 cargo test --workspace --release --test it -- browser
