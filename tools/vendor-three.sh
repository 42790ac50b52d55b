#!/bin/sh
# Vendors the pinned three.js release into crates/platener-web/assets/vendor/three, unedited, with
# its licence: only the files the page imports. Run it again after changing VERSION (and INTEGRITY,
# from `npm view three@VERSION dist.integrity`). Needs node's npm and the npm registry.
set -eu
VERSION=0.187.0
INTEGRITY=sha512-Qiu7R+Cmh8CstZsY1uJOSWnVlfo7ZtNLV7mF8Jltk3LB3AtDu9cRZlcnRKkAk8Y4z6KKw35z7Y7Urd7jWY8etA==
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DEST="$ROOT/crates/platener-web/assets/vendor/three"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
npm pack --silent "three@$VERSION" >/dev/null
TARBALL="three-$VERSION.tgz"
ACTUAL="sha512-$(openssl dgst -sha512 -binary "$TARBALL" | base64 -w0)"
if [ "$ACTUAL" != "$INTEGRITY" ]; then
  echo "vendor-three: $TARBALL is not the release pinned here ($INTEGRITY)" >&2
  exit 1
fi
tar xzf "$TARBALL"
rm -rf "$DEST"
mkdir -p "$DEST/build" "$DEST/examples/jsm/controls" "$DEST/examples/jsm/loaders" "$DEST/examples/jsm/utils"
cp package/LICENSE "$DEST/LICENSE"
cp package/build/three.module.js package/build/three.core.js "$DEST/build/"
cp package/examples/jsm/controls/OrbitControls.js "$DEST/examples/jsm/controls/"
cp package/examples/jsm/loaders/GLTFLoader.js "$DEST/examples/jsm/loaders/"
cp package/examples/jsm/utils/BufferGeometryUtils.js package/examples/jsm/utils/SkeletonUtils.js "$DEST/examples/jsm/utils/"
printf 'three.js %s from the npm registry (%s), unedited; licence in LICENSE.\n' "$VERSION" "$ACTUAL" > "$DEST/VERSION"
echo "vendored three.js $VERSION into $DEST"
