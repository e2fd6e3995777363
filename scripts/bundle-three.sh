#!/usr/bin/env bash
# Bundles the part of three.js the viewer uses (and its OrbitControls) into one minified script,
# crates/biscara-view/assets/three.min.js, which `biscara view` inlines into every page. The bundle
# is committed, so building biscara needs no network; run this only to change three's version.
# It installs the pinned npm packages into a temporary folder, bundles with the pinned esbuild and
# writes the versions and the bundle's SHA-256 into assets/three.VERSIONS (and three's licence
# beside the bundle).
set -euo pipefail
THREE_VERSION=0.187.0
ESBUILD_VERSION=0.28.2
here="$(cd "$(dirname "$0")/.." && pwd)"
assets="$here/crates/biscara-view/assets"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
npm init -y >/dev/null
npm install --no-audit --no-fund --save-exact "three@$THREE_VERSION" "esbuild@$ESBUILD_VERSION" >/dev/null
cat > entry.js <<'JS'
export {
  Scene, PerspectiveCamera, OrthographicCamera, WebGLRenderer, Color, Vector3, Quaternion, Euler,
  Group, Mesh, BoxGeometry, CylinderGeometry, SphereGeometry, ConeGeometry, PlaneGeometry,
  BufferGeometry, BufferAttribute, Float32BufferAttribute, LineSegments, Line, Points,
  MeshStandardMaterial, MeshBasicMaterial, LineBasicMaterial, PointsMaterial, AmbientLight,
  DirectionalLight, HemisphereLight, GridHelper, AxesHelper, EdgesGeometry, DoubleSide,
  MathUtils, Box3, Plane,
} from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
JS
npx --no-install esbuild entry.js --bundle --minify --format=iife --global-name=THREE \
  --legal-comments=none --target=es2020 --outfile=three.min.js
cp three.min.js "$assets/three.min.js"
cp node_modules/three/LICENSE "$assets/three-LICENSE.txt"
sum="$(sha256sum "$assets/three.min.js" | cut -d' ' -f1)"
cat > "$assets/three.VERSIONS" <<TXT
three $(node -p "require('./node_modules/three/package.json').version")
esbuild $(node -p "require('./node_modules/esbuild/package.json').version")
node $(node --version)
sha256 three.min.js $sum
TXT
echo "wrote $assets/three.min.js ($(wc -c < "$assets/three.min.js") bytes, sha256 $sum)"
