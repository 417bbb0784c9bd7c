#!/usr/bin/env bash
# Fails when a source file that CMake picks up by globbing is not named in the matching Meson list:
#   tests/<dir>/test_*.cpp   in tests/<dir>/meson.build (and <dir> in the table tests/areas.txt)
#   bench/bench_*.cpp        in bench/meson.build
#   examples/*.cpp           in examples/meson.build
# so that the two builds compile and run the same things.
#   check_meson_lists.sh <sss source dir>
set -euo pipefail

src=$(cd "${1:?usage: check_meson_lists.sh <sss source dir>}" && pwd)
missing=0
checked=0

# listed <meson.build> <file name>: the file name appears quoted outside comments. (grep reads all of its input:
# with `grep -q` it could stop early and sed's SIGPIPE would fail the pipe under pipefail.)
listed() {
    [[ -f "$1" ]] && sed 's/#.*//' "$1" | grep -E "['\"]$2['\"]" >/dev/null
}

complain() {
    echo "$1" >&2
    missing=$((missing + 1))
}

shopt -s nullglob
# The test directories named in tests/areas.txt (first field up to any '/').
dirs=$(sed 's/#.*//' "$src/tests/areas.txt" | awk 'NF { split($1, p, "/"); print p[1] }' | sort -u)
for file in "$src"/tests/*/test_*.cpp; do
    dir=$(basename "$(dirname "$file")")
    name=$(basename "$file")
    checked=$((checked + 1))
    if ! listed "$src/tests/$dir/meson.build" "$name"; then
        complain "tests/$dir/$name: not listed in tests/$dir/meson.build"
    elif ! grep -qx "$dir" <<<"$dirs"; then
        complain "tests/$dir/$name: directory '$dir' has no line in tests/areas.txt"
    fi
done
for file in "$src"/bench/bench_*.cpp; do
    checked=$((checked + 1))
    listed "$src/bench/meson.build" "$(basename "$file")" ||
        complain "bench/$(basename "$file"): not listed in bench/meson.build"
done
for file in "$src"/examples/*.cpp; do
    checked=$((checked + 1))
    listed "$src/examples/meson.build" "$(basename "$file")" ||
        complain "examples/$(basename "$file"): not listed in examples/meson.build"
done

if ((missing > 0)); then
    echo "$missing of $checked source files are missing from the Meson lists: run" \
         "bash tests/tools/update_meson_lists.sh" >&2
    exit 1
fi
echo "all $checked test, benchmark and example sources are named in the Meson build"
