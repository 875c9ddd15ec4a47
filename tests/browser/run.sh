#!/usr/bin/env bash
# The headless-browser tests of the page of `rover drive` (drive.mjs) and
# of `rover view` (view.mjs).
# Needs Chromium (Debian's `chromium`; .ci/setup-browser installs it) and
# Node.js; where either is missing it is skipped with a message saying
# what to install, and exits 0.
set -euo pipefail
cd "${0%/*}"
browser=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
if [ -z "$browser" ]; then
  echo "SKIPPED: the browser test of rover drive needs Chromium (apt-get install chromium, or .ci/setup-browser; or set CHROMIUM=/path/to/chrome)"
  exit 0
fi
if ! command -v node > /dev/null; then
  echo "SKIPPED: the browser test of rover drive needs Node.js 18 or newer"
  exit 0
fi
[ -d node_modules/playwright-core ] || npm ci --no-audit --no-fund
target=${CARGO_TARGET_DIR:-../../target}
cargo build --release --locked --bin rover
node drive.mjs "$target/release/rover" "$browser"
node view.mjs "$target/release/rover" "$browser"
