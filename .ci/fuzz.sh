#!/usr/bin/env bash
# libFuzzer runs of the tests/fuzz targets (clang, ASan + UBSan): first every seed and every kept crashing
# input once, then both targets fuzz at the same time for SECONDS each. Fails on any finding; the input that
# triggered it is left in BUILD/fuzz-work/TARGET/artifacts/ (keep it in tests/fuzz/regressions/TARGET/).
# Usage: .ci/fuzz.sh [SECONDS]          (default 60; see tests/fuzz/README.md for long runs)
# Env:   SONARSIM_FUZZ_BUILD_DIR=build-fuzz  SONARSIM_JOBS=$(nproc)
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-60}"
dir="${SONARSIM_FUZZ_BUILD_DIR:-build-fuzz}"
jobs="${SONARSIM_JOBS:-$(nproc)}"
targets=(scene mesh aris)

CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSONARSIM_FUZZ=ON \
    -DSONARSIM_BUILD_VIEWER=OFF >/dev/null
cmake --build "$dir" -j "$jobs" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:${UBSAN_OPTIONS:-}"
pids=()
for t in "${targets[@]}"; do
    work="$dir/fuzz-work/$t"
    mkdir -p "$work/corpus" "$work/artifacts"
    "$dir/tests/fuzz/fuzz_$t" -runs=0 "tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t" >"$work/replay.log" 2>&1 ||
        { tail -n 40 "$work/replay.log"; echo "fuzz: $t: a seed or a kept regression fails"; exit 1; }
    dict=()
    [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
    # The working corpus grows across runs in the build directory; the seeds stay as committed.
    "$dir/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        "${dict[@]}" -artifact_prefix="$work/artifacts/" "$work/corpus" "tests/fuzz/corpus/$t" \
        >"$work/fuzz.log" 2>&1 &
    pids+=($!)
done
status=0
for i in "${!targets[@]}"; do
    t=${targets[$i]}
    if wait "${pids[$i]}"; then
        echo "fuzz: $t: $(grep -m1 -o 'stat::number_of_executed_units: [0-9]*' "$dir/fuzz-work/$t/fuzz.log" |
            grep -o '[0-9]*') inputs in ${seconds} s, no findings"
    else
        grep -A 30 -m1 "ERROR\|==ERROR\|runtime error\|deadly signal\|timeout" "$dir/fuzz-work/$t/fuzz.log" || true
        echo "fuzz: $t: FINDING, input in $dir/fuzz-work/$t/artifacts/"
        status=1
    fi
done
exit $status
