#!/usr/bin/env bash
# Rebuild three.min.js (committed) from three.js on npm: only the classes
# three-entry.js names, tree-shaken and minified by esbuild. Run it after
# the page starts using another three.js class, or to move to a new
# release (change the versions in package.json).
set -euo pipefail
cd "$(dirname "$0")"
npm install --no-audit --no-fund --no-save
npx esbuild three-entry.js --bundle --minify --format=esm --legal-comments=none \
  --outfile=three.min.js
version=$(node -p "JSON.parse(require('fs').readFileSync('node_modules/three/package.json')).version")
{ echo "three.js $version (https://threejs.org), bundled into three.min.js by build.sh:"; echo; cat node_modules/three/LICENSE; } > THREE_LICENSE
sed -i "1i // three.js $version, MIT licence (THREE_LICENSE); built by build.sh from three-entry.js." three.min.js
