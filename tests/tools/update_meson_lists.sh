#!/usr/bin/env bash
# Rewrites the Meson source lists from the files present, so that Meson builds what CMake globs:
#   tests/<dir>/meson.build  : <dir>_tests = files(...)     from tests/<dir>/test_*.cpp (dirs: tests/areas.txt)
#   bench/meson.build        : bench_sources = files(...)   from bench/bench_*.cpp
#   examples/meson.build     : example_sources = files(...) from examples/*.cpp
# Only the lines between "<var> = files(" and the closing ")" change. Run it after adding or removing
# a test, benchmark or example:   bash tests/tools/update_meson_lists.sh [sss source dir]
set -euo pipefail

src=$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/../..}" && pwd)

# rewrite <meson.build> <variable> <file names...>
rewrite() {
    local file=$1 var=$2
    shift 2
    if ! grep -q "^$var = files($" "$file"; then
        echo "update_meson_lists: $file has no line '$var = files('" >&2
        return 1
    fi
    local entries=""
    local name
    for name in "$@"; do
        entries+="    '$name',"$'\n'
    done
    local tmp
    tmp=$(mktemp "$file.XXXXXX")
    ENTRIES="$entries" awk -v var="$var" '
        $0 == var " = files(" { print; printf "%s", ENVIRON["ENTRIES"]; skipping = 1; next }
        skipping && /^\)/     { skipping = 0 }
        !skipping             { print }
    ' "$file" >"$tmp"
    if cmp -s "$tmp" "$file"; then
        rm -f "$tmp"
    else
        chmod --reference="$file" "$tmp" 2>/dev/null || true
        mv "$tmp" "$file"
        echo "updated ${file#"$src"/}"
    fi
}

# names <dir> <pattern>: the matching file names in <dir>, sorted.
names() {
    (cd "$1" && shopt -s nullglob && for f in $2; do echo "$f"; done) | LC_ALL=C sort
}

# The test directories: the first field of tests/areas.txt up to any '/', in order, once each.
dirs=$(sed 's/#.*//' "$src/tests/areas.txt" | awk 'NF { split($1, p, "/"); if (!seen[p[1]]++) print p[1] }')
for dir in $dirs; do
    mapfile -t files < <(names "$src/tests/$dir" 'test_*.cpp')
    rewrite "$src/tests/$dir/meson.build" "${dir}_tests" "${files[@]}"
done
mapfile -t files < <(names "$src/bench" 'bench_*.cpp')
rewrite "$src/bench/meson.build" bench_sources "${files[@]}"
mapfile -t files < <(names "$src/examples" '*.cpp')
rewrite "$src/examples/meson.build" example_sources "${files[@]}"
