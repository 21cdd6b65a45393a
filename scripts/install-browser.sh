#!/usr/bin/env bash
# Installs Debian's chromium when it is missing (as root, or with sudo), for
# the browser half of the end-to-end tests (crates/armkit-cli/tests/it/
# demo_browser.rs: the demo's reports; view_browser.rs: `armkit view` on a
# URDF with meshes, its link transforms read back from the page against
# armkit's FK). The README's test command runs those tests when Chromium is
# there and skips their browser half with a message when it is not.
# Where Chromium cannot be installed, says so and exits 0. Called by .ci/run
# before the README's test command.
set -euo pipefail

if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  { $SUDO apt-get update -q >/dev/null \
    && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q chromium >/dev/null; } \
    || true
fi
if command -v chromium >/dev/null 2>&1; then
  echo "chromium: $(command -v chromium)"
else
  echo "chromium could not be installed: the browser tests will skip their browser half"
fi
