#!/usr/bin/env bash
# Fails when a source file that CMake picks up by globbing is not named in the matching Meson list:
#   tests/<area>/test_*.cpp  in tests/<area>/meson.build (and <area> in the area list of tests/meson.build)
#   bench/bench_*.cpp        in bench/meson.build
#   examples/*.cpp           in examples/meson.build
# so that the two builds compile and run the same things.
#   check_meson_lists.sh <sss source dir>
set -euo pipefail

src=$(cd "${1:?usage: check_meson_lists.sh <sss source dir>}" && pwd)
missing=0
checked=0

# listed <meson.build> <file name>: the file name appears quoted outside comments. (grep reads all of its input:
# with -q it would stop at the first match, and sed, still writing, would fail the pipeline under pipefail.)
listed() {
    [[ -f "$1" ]] && sed 's/#.*//' "$1" | grep -E "['\"]$2['\"]" >/dev/null
}

complain() {
    echo "$1" >&2
    missing=$((missing + 1))
}

shopt -s nullglob
for file in "$src"/tests/*/test_*.cpp; do
    area=$(basename "$(dirname "$file")")
    name=$(basename "$file")
    checked=$((checked + 1))
    if ! listed "$src/tests/$area/meson.build" "$name"; then
        complain "tests/$area/$name: not listed in tests/$area/meson.build"
    elif ! listed "$src/tests/meson.build" "$area"; then
        complain "tests/$area/$name: area '$area' is not in the area list of tests/meson.build"
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
