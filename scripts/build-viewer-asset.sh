#!/usr/bin/env bash
# Builds the vendored three.js bundle that armkit's reports load:
# crates/armkit-view/assets/three.bundle.js (three.js's core classes that
# assets/viewer.js uses, and OrbitControls, as the global THREE in one classic
# script: reports open from file://, where browsers refuse ES-module imports)
# and assets/three.LICENSE (three.js is MIT). Run by a developer when the
# viewer needs another three.js class or a newer three.js (versions pinned in
# scripts/viewer/package.json and its lock file); the user's build never runs
# npm: both files are committed.
set -euo pipefail
cd "$(dirname "$0")/viewer"
npm ci --no-audit --no-fund
version=$(node -p "JSON.parse(require('fs').readFileSync('node_modules/three/package.json')).version")
assets=../../crates/armkit-view/assets
{
  echo "/* three.js ${version} (https://threejs.org), MIT licence: see three.LICENSE."
  echo "   Built by scripts/build-viewer-asset.sh from scripts/viewer/entry.js; do not edit. */"
  node_modules/.bin/esbuild entry.js --bundle --minify --format=iife \
    --legal-comments=none --target=es2018 --log-level=warning
} > "$assets/three.bundle.js"
cp node_modules/three/LICENSE "$assets/three.LICENSE"
echo "wrote $assets/three.bundle.js ($(wc -c < "$assets/three.bundle.js") bytes, three $version)"
