#!/usr/bin/env bash
# Builds and runs tests/consumers/one_ping.cpp in a Meson project that has sss as a subproject:
# the sss source tree (without build directories) is copied into <consumer>/subprojects/sss.
#   consumer_meson.sh <sss source dir> [meson]
# Honours CXX (the compiler). Everything happens in a temporary directory, removed on exit.
set -euo pipefail

src=$(cd "${1:?usage: consumer_meson.sh <sss source dir> [meson]}" && pwd)
meson=${2:-meson}

work=$(mktemp -d "${TMPDIR:-/tmp}/sss-consumer-meson.XXXXXX")
trap 'rm -rf "$work"' EXIT

mkdir -p "$work/consumer/subprojects/sss"
cp "$src/tests/consumers/meson/meson.build" "$src/tests/consumers/one_ping.cpp" "$work/consumer/"
# Copy the tree as a user vendoring it would, leaving out VCS data and build directories.
tar -C "$src" --exclude=./.git --exclude='./build*' --exclude=./subprojects -cf - . \
    | tar -C "$work/consumer/subprojects/sss" -xf -

# Run from a neutral directory so no enclosing build's environment leaks in.
cd "$work"
"$meson" setup "$work/build" "$work/consumer" --force-fallback-for=sss
"$meson" compile -C "$work/build"
"$work/build/one_ping"
echo "consumer (meson subproject): one_ping ran and returned 0"
