#!/usr/bin/env bash
# Builds and runs tests/consumers/one_ping.cpp in a CMake project that uses sss as a user would.
#   consumer_cmake.sh install      <sss source dir> [cmake]: cmake --install sss into a temporary
#                                  prefix, then find_package(sss) with CMAKE_PREFIX_PATH there.
#   consumer_cmake.sh subdirectory <sss source dir> [cmake]: add_subdirectory(<sss source dir>).
# Honours CXX (the compiler). Everything happens in a temporary directory, removed on exit.
set -euo pipefail

mode=${1:?usage: consumer_cmake.sh install|subdirectory <sss source dir> [cmake]}
src=$(cd "${2:?missing sss source dir}" && pwd)
cmake=${3:-cmake}

work=$(mktemp -d "${TMPDIR:-/tmp}/sss-consumer-cmake.XXXXXX")
trap 'rm -rf "$work"' EXIT

generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
compiler=()
if [[ -n "${CXX:-}" ]]; then compiler=(-DCMAKE_CXX_COMPILER="$CXX"); fi

mkdir -p "$work/consumer"
cp "$src/tests/consumers/cmake/CMakeLists.txt" "$src/tests/consumers/one_ping.cpp" "$work/consumer/"

case "$mode" in
install)
    "$cmake" -S "$src" -B "$work/sss-build" "${generator[@]}" "${compiler[@]}" \
        -DCMAKE_BUILD_TYPE=Release -DSSS_BUILD_TESTS=OFF -DSSS_BUILD_BENCH=OFF -DSSS_BUILD_EXAMPLES=OFF -DSSS_BUILD_TOOLS=OFF
    "$cmake" --build "$work/sss-build"
    "$cmake" --install "$work/sss-build" --prefix "$work/prefix"
    # sss.pc names the headers where they were installed, whatever the prefix configured.
    if command -v pkg-config >/dev/null 2>&1; then
        cflags=$(PKG_CONFIG_PATH="$work/prefix/share/pkgconfig" pkg-config --cflags sss) || exit 1
        include=${cflags#*-I}
        include=${include%% *}
        if [ ! -f "$include/sss/sss.hpp" ]; then
            echo "consumer_cmake.sh: pkg-config --cflags sss gives '$cflags', not the installed headers" >&2
            exit 1
        fi
        # A pkg-config user sees sss's headers with -I, not as system headers: they stay free of the warnings strict
        # users turn on.
        # shellcheck disable=SC2046
        "${CXX:-c++}" -std=c++20 -fsyntax-only -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Wdouble-promotion -Werror \
            $(PKG_CONFIG_PATH="$work/prefix/share/pkgconfig" pkg-config --cflags sss) "$work/consumer/one_ping.cpp"
        # Where pkg-config knows no glm.pc (a GLM installed from its sources), sss.pc requires none: configured so,
        # it still answers.
        mkdir -p "$work/no-pc"
        PKG_CONFIG_LIBDIR="$work/no-pc" "$cmake" -S "$src" -B "$work/sss-no-glm-pc" "${generator[@]}" "${compiler[@]}" \
            -DSSS_BUILD_TESTS=OFF -DSSS_BUILD_BENCH=OFF -DSSS_BUILD_EXAMPLES=OFF -DSSS_BUILD_TOOLS=OFF -DSSS_INSTALL=ON >/dev/null
        if ! PKG_CONFIG_LIBDIR="$work/no-pc" PKG_CONFIG_PATH="$work/sss-no-glm-pc" pkg-config --cflags sss >/dev/null; then
            echo "consumer_cmake.sh: sss.pc configured without a glm.pc requires one:" >&2
            cat "$work/sss-no-glm-pc/sss.pc" >&2
            exit 1
        fi
    fi
    "$cmake" -S "$work/consumer" -B "$work/consumer-build" "${generator[@]}" "${compiler[@]}" \
        -DCMAKE_BUILD_TYPE=Release -DSSS_CONSUMER_MODE=install -DCMAKE_PREFIX_PATH="$work/prefix" \
        -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
    ;;
subdirectory)
    "$cmake" -S "$work/consumer" -B "$work/consumer-build" "${generator[@]}" "${compiler[@]}" \
        -DCMAKE_BUILD_TYPE=Release -DSSS_CONSUMER_MODE=subdirectory -DSSS_SOURCE_DIR="$src"
    ;;
*)
    echo "consumer_cmake.sh: unknown mode '$mode' (install or subdirectory)" >&2
    exit 2
    ;;
esac

"$cmake" --build "$work/consumer-build"
"$work/consumer-build/one_ping"
echo "consumer ($mode): one_ping ran and returned 0"
