#!/usr/bin/env bash
# Writes the README's first C++ example (the first ```cpp block) to <output>, so that the build compiles it and
# CTest / meson test run it (foundation/readme_example): the front page's code cannot drift from the API.
#   readme_example.sh <README.md> <output.cpp>
set -euo pipefail
readme=${1:?usage: readme_example.sh <README.md> <output.cpp>}
out=${2:?usage: readme_example.sh <README.md> <output.cpp>}
tmp=$(mktemp "$out.XXXXXX")
awk '/^```cpp[ \t]*$/ { inside = 1; next } inside && /^```/ { exit } inside { print }' "$readme" >"$tmp"
if [[ ! -s "$tmp" ]]; then
    rm -f "$tmp"
    echo "readme_example: $readme has no \`\`\`cpp block" >&2
    exit 1
fi
mv "$tmp" "$out"
