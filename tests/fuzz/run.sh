#!/usr/bin/env bash
# Builds and runs sss's fuzz targets (libFuzzer + AddressSanitizer + UndefinedBehaviorSanitizer, through clang)
# and reports, per target, the executions and the findings. Optionally runs the long random-scene sweep.
#
#   bash tests/fuzz/run.sh [--runs N] [--time S] [--build DIR] [--jobs J] [--sweep SCENES] [target ...]
#
#   --runs N        executions per target (default 1000000)
#   --time S        at most S seconds per target (default 1800); whichever of --runs and --time comes first
#   --build DIR     where binaries, working corpora and findings go (default build-fuzz in the repository root)
#   --jobs J        build and run up to J targets at once (default 1)
#   --sweep SCENES  also build tests/robustness/test_scene_sweep.cpp and run it over SCENES random scenes
#   --no-fuzz       skip the fuzz targets (with --sweep: the sweep only)
#   target          fuzz_<target>.cpp in tests/fuzz/ (default: all of them)
#
# A target is one file tests/fuzz/fuzz_<target>.cpp (see fuzz_support.hpp); its seed corpus is the committed
# directory tests/fuzz/corpus/<target>/ (read only: inputs libFuzzer finds go to DIR/corpus/<target>/).
# A finding (crash, sanitizer report, leak, exception not derived from sss::error, allocation over 512 MiB,
# an input taking over 10 s) leaves its input in DIR/findings/<target>/; reproduce it with
#   DIR/fuzz_<target> DIR/findings/<target>/<file>
# and turn it into a regression test (tests/robustness/ or tests/io/).
# Exit status: 0 when nothing was found, 1 otherwise. Needs clang++ and libclang-rt (Debian: clang
# libclang-rt-14-dev) and GLM.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
runs=1000000
max_time=1800
build="$root/build-fuzz"
sweep=0
jobs=1
fuzz=1
targets=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --runs) runs="$2"; shift 2 ;;
        --time) max_time="$2"; shift 2 ;;
        --build) build="$2"; shift 2 ;;
        --jobs) jobs="$2"; shift 2 ;;
        --sweep) sweep="$2"; shift 2 ;;
        --no-fuzz) fuzz=0; shift ;;
        -h|--help) sed -n '2,22p' "${BASH_SOURCE[0]}"; exit 0 ;;
        -*) echo "run.sh: unknown option $1" >&2; exit 2 ;;
        *) targets+=("$1"); shift ;;
    esac
done
if [[ ${#targets[@]} -eq 0 ]]; then
    for f in "$root"/tests/fuzz/fuzz_*.cpp; do
        t="$(basename "$f" .cpp)"
        targets+=("${t#fuzz_}")
    done
fi

cxx="${CXX_FUZZ:-clang++}"
flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
       -I "$root/include" -I "$root/tests" -I "$root/tools")
mkdir -p "$build"
export TMPDIR="$build/tmp"
mkdir -p "$TMPDIR"
# Leaks are findings; UBSan stops at the first report (with -fno-sanitize-recover it aborts anyway).
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

status=0
report=()
if [[ $fuzz -eq 1 ]]; then
    # Build every target that is missing or older than its sources, up to $jobs at once.
    pids=()
    for t in "${targets[@]}"; do
        src="$root/tests/fuzz/fuzz_$t.cpp"
        [[ -f "$src" ]] || { echo "run.sh: no target $src" >&2; exit 2; }
        exe="$build/fuzz_$t"
        if [[ ! -x "$exe" || "$src" -nt "$exe" || -n "$(find "$root/include" "$root/tests/fuzz" "$root/tools" -newer "$exe" -name '*.hpp' -print -quit)" ]]; then
            echo "== building fuzz_$t"
            "$cxx" "${flags[@]}" "$src" -o "$exe.new" && mv "$exe.new" "$exe" &
            pids+=($!)
            if [[ ${#pids[@]} -ge $jobs ]]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
        fi
    done
    for p in "${pids[@]}"; do wait "$p"; done
    # fuzz_one <target>: runs it; its report line goes to $build/.report_<target>, its status is the finding's.
    fuzz_one() {
        local t="$1" exe="$build/fuzz_$1" work="$build/corpus/$1" findings="$build/findings/$1"
        local log="$build/fuzz_$1.log" stamp="$build/.start_$1" rc=0 execs secs found
        mkdir -p "$work" "$findings"
        local seeds=()
        [[ -d "$root/tests/fuzz/corpus/$t" ]] && seeds=("$root/tests/fuzz/corpus/$t")
        : >"$stamp" # findings of earlier runs stay in $findings but are not counted again
        echo "== fuzz_$t: up to $runs runs or $max_time s"
        "$exe" -runs="$runs" -max_total_time="$max_time" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
            -malloc_limit_mb=512 -print_final_stats=1 -artifact_prefix="$findings/" "$work" "${seeds[@]}" \
            >"$log" 2>&1 || rc=$?
        execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)"
        secs="$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' | tail -1 || true)"
        found="$(find "$findings" -type f -newer "$stamp" | wc -l)"
        printf '%-16s %12s executions %6s s %4s findings\n' "$t" "${execs:-?}" "${secs:-?}" "$found" >"$build/.report_$t"
        if [[ $rc -ne 0 || $found -ne 0 ]]; then
            echo "!! fuzz_$t: finding (exit $rc); log $log, inputs in $findings"
            grep -m 5 -E 'ERROR|runtime error|sss fuzz finding|SUMMARY' "$log" || true
            return 1
        fi
    }
    # Up to $jobs targets at once (each libFuzzer process uses one core).
    running=()
    for t in "${targets[@]}"; do
        fuzz_one "$t" &
        running+=($!)
        if [[ ${#running[@]} -ge $jobs ]]; then
            wait "${running[0]}" || status=1
            running=("${running[@]:1}")
        fi
    done
    for p in "${running[@]}"; do wait "$p" || status=1; done
    for t in "${targets[@]}"; do report+=("$(cat "$build/.report_$t" 2>/dev/null || echo "$t: no report")"); done
fi

if [[ $sweep -gt 0 ]]; then
    exe="$build/sweep"
    echo "== building the random-scene sweep"
    "$cxx" -std=c++20 -O2 -I "$root/include" -I "$root/tests" -DSSS_SOURCE_DIR="\"$root\"" \
        "$root/tests/doctest_main.cpp" "$root/tests/robustness/test_scene_sweep.cpp" -pthread -o "$exe"
    echo "== sweep of $sweep scenes"
    start=$(date +%s)
    if SSS_SWEEP_SCENES="$sweep" "$exe"; then
        report+=("$(printf '%-16s %12s scenes     %6s s    0 findings' sweep "$sweep" "$(( $(date +%s) - start ))")")
    else
        status=1
        report+=("$(printf '%-16s %12s scenes     %6s s  FAILED' sweep "$sweep" "$(( $(date +%s) - start ))")")
    fi
fi

echo
echo "== summary"
for line in "${report[@]}"; do echo "$line"; done
exit $status
