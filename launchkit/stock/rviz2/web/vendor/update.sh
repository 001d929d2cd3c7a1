#!/usr/bin/env bash
# Refresh the viewer's vendored browser libraries from the npm registry.
#
# Run by hand when upgrading (needs npm; users and CI never run it): it downloads the released
# tarball of each package with `npm pack`, checks it against the integrity the registry states,
# copies the files the viewer loads (flattened: `build/`, `dist/` and `examples/jsm/` are not kept
# as such) with the package's licence, and rewrites VENDORED.md with versions, licences and hashes.
set -euo pipefail
cd "$(dirname "$0")"

# every package as  name@version, and its files as  package@version|source-in-package:destination
PACKAGES=(three@0.187.0 @dagrejs/dagre@3.1.3 uplot@1.6.32)
FILES=(
  "three@0.187.0|build/three.module.js:three/three.module.js"
  "three@0.187.0|build/three.core.js:three/three.core.js"
  "three@0.187.0|examples/jsm/controls/OrbitControls.js:three/addons/controls/OrbitControls.js"
  "three@0.187.0|examples/jsm/loaders/STLLoader.js:three/addons/loaders/STLLoader.js"
  "three@0.187.0|examples/jsm/loaders/OBJLoader.js:three/addons/loaders/OBJLoader.js"
  "three@0.187.0|examples/jsm/loaders/ColladaLoader.js:three/addons/loaders/ColladaLoader.js"
  "three@0.187.0|examples/jsm/loaders/collada/ColladaParser.js:three/addons/loaders/collada/ColladaParser.js"
  "three@0.187.0|examples/jsm/loaders/collada/ColladaComposer.js:three/addons/loaders/collada/ColladaComposer.js"
  "three@0.187.0|examples/jsm/loaders/TGALoader.js:three/addons/loaders/TGALoader.js"
  "three@0.187.0|LICENSE:three/LICENSE"
  # the node graph's and the TF tree's layout (graphlib is bundled inside this file)
  "@dagrejs/dagre@3.1.3|dist/dagre.esm.js:dagre/dagre.esm.js"
  "@dagrejs/dagre@3.1.3|LICENSE:dagre/LICENSE"
  # the plot panel's chart
  "uplot@1.6.32|dist/uPlot.esm.js:uplot/uPlot.esm.js"
  "uplot@1.6.32|dist/uPlot.min.css:uplot/uPlot.min.css"
  "uplot@1.6.32|LICENSE:uplot/LICENSE"
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rows=()
for package in "${PACKAGES[@]}"; do
  unpacked="$work/$(echo "$package" | tr '/@' '__')"
  mkdir -p "$unpacked"
  tarball=$(cd "$work" && npm pack --silent "$package" 2>/dev/null | tail -n 1)
  expected=$(npm view "$package" dist.integrity 2>/dev/null)
  actual="sha512-$(openssl dgst -sha512 -binary "$work/$tarball" | base64 -w0)"
  if [ "$expected" != "$actual" ]; then
    echo "integrity mismatch for $tarball: registry says $expected, got $actual" >&2
    exit 1
  fi
  licence=$(npm view "$package" license 2>/dev/null)
  tar -xzf "$work/$tarball" -C "$unpacked"
  rows+=("| ${package%@*} | ${package##*@} | $licence | \`$expected\` |")
done

rm -rf three dagre uplot
for entry in "${FILES[@]}"; do
  package=${entry%%|*}
  pair=${entry#*|}
  source=${pair%%:*}
  destination=${pair#*:}
  mkdir -p "$(dirname "$destination")"
  cp "$work/$(echo "$package" | tr '/@' '__')/package/$source" "$destination"
done

{
  echo "# Vendored browser libraries"
  echo
  echo "Released files from the npm registry, unchanged, fetched by \`update.sh\` (run it to upgrade;"
  echo "users never need npm). The page loads them through the import map in \`../index.html\`."
  echo
  echo "| package | version | licence | tarball integrity (npm) |"
  echo "|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "Files (package path -> here):"
  echo
  for entry in "${FILES[@]}"; do
    pair=${entry#*|}
    echo "- \`${entry%%|*}\` \`${pair%%:*}\` -> \`${pair#*:}\`"
  done
} > VENDORED.md
echo "vendored ${PACKAGES[*]}"
