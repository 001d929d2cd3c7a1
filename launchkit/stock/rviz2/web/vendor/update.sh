#!/usr/bin/env bash
# Refresh the viewer's vendored browser libraries from the npm registry.
#
# Run by hand when upgrading (needs npm; users and CI never run it): it downloads the released
# tarball of each package with `npm pack`, checks it against the integrity the registry states,
# copies the files the viewer loads (flattened: `build/` and `examples/jsm/` are not kept as
# such) with the package's licence, and rewrites VENDORED.md with version, licence and hash.
set -euo pipefail
cd "$(dirname "$0")"

THREE_VERSION=0.187.0
# files of the `three` package the page imports, as  source-in-package:destination
THREE_FILES=(
  build/three.module.js:three/three.module.js
  build/three.core.js:three/three.core.js
  examples/jsm/controls/OrbitControls.js:three/addons/controls/OrbitControls.js
  examples/jsm/loaders/STLLoader.js:three/addons/loaders/STLLoader.js
  examples/jsm/loaders/OBJLoader.js:three/addons/loaders/OBJLoader.js
  examples/jsm/loaders/ColladaLoader.js:three/addons/loaders/ColladaLoader.js
  examples/jsm/loaders/collada/ColladaParser.js:three/addons/loaders/collada/ColladaParser.js
  examples/jsm/loaders/collada/ColladaComposer.js:three/addons/loaders/collada/ColladaComposer.js
  examples/jsm/loaders/TGALoader.js:three/addons/loaders/TGALoader.js
  LICENSE:three/LICENSE
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

tarball=$(cd "$work" && npm pack --silent "three@$THREE_VERSION" 2>/dev/null | tail -n 1)
expected=$(npm view "three@$THREE_VERSION" dist.integrity 2>/dev/null)
actual="sha512-$(openssl dgst -sha512 -binary "$work/$tarball" | base64 -w0)"
if [ "$expected" != "$actual" ]; then
  echo "integrity mismatch for $tarball: registry says $expected, got $actual" >&2
  exit 1
fi
licence=$(npm view "three@$THREE_VERSION" license 2>/dev/null)
tar -xzf "$work/$tarball" -C "$work"

rm -rf three
for entry in "${THREE_FILES[@]}"; do
  source=${entry%%:*}
  destination=${entry#*:}
  mkdir -p "$(dirname "$destination")"
  cp "$work/package/$source" "$destination"
done

{
  echo "# Vendored browser libraries"
  echo
  echo "Released files from the npm registry, unchanged, fetched by \`update.sh\` (run it to upgrade;"
  echo "users never need npm). The page loads them through the import map in \`../index.html\`."
  echo
  echo "| package | version | licence | tarball integrity (npm) |"
  echo "|---|---|---|---|"
  echo "| three | $THREE_VERSION | $licence | \`$expected\` |"
  echo
  echo "Files (package path -> here):"
  echo
  for entry in "${THREE_FILES[@]}"; do
    echo "- \`${entry%%:*}\` -> \`${entry#*:}\`"
  done
} > VENDORED.md
echo "vendored three@$THREE_VERSION ($licence)"
