#!/usr/bin/env bash
# The headless-browser tests of the page of `rover drive` (drive.mjs) and
# of `rover view` (view.mjs), and the Foxglove protocol test of `rover
# drive` (foxglove.mjs: a client, no browser).
# Needs Node.js, and Chromium (Debian's `chromium`; .ci/setup-browser
# installs it) for the page tests; where either is missing the tests that
# need it are skipped with a message saying what to install, and it exits 0.
set -euo pipefail
cd "${0%/*}"
if ! command -v node > /dev/null; then
  echo "SKIPPED: the browser and Foxglove tests of rover drive need Node.js 18 or newer"
  exit 0
fi
[ -d node_modules/playwright-core ] && [ -d node_modules/@foxglove/ws-protocol ] || npm ci --no-audit --no-fund
target=${CARGO_TARGET_DIR:-../../target}
cargo build --release --locked --bin rover
node foxglove.mjs "$target/release/rover"
browser=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
if [ -z "$browser" ]; then
  echo "SKIPPED: the browser test of rover drive needs Chromium (apt-get install chromium, or .ci/setup-browser; or set CHROMIUM=/path/to/chrome)"
  exit 0
fi
node drive.mjs "$target/release/rover" "$browser"
node view.mjs "$target/release/rover" "$browser"
