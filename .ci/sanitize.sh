#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer: builds everything but the viewer's GL part with
# SONARSIM_SANITIZE=ON (the viewer's non-GL library ui_core and its tests test_ui included: render worker,
# session, snapshots, display meshes) and runs the whole ctest suite under it. Any sanitizer report fails the
# test that triggered it.
# Usage: .ci/sanitize.sh [ctest args...]
# Env:   SONARSIM_ASAN_DIR=build-asan  SONARSIM_JOBS=$(nproc)
set -euo pipefail
cd "$(dirname "$0")/.."

dir="${SONARSIM_ASAN_DIR:-build-asan}"
jobs="${SONARSIM_JOBS:-$(nproc)}"
start=$(date +%s)
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSONARSIM_SANITIZE=ON \
      -DSONARSIM_BUILD_VIEWER=OFF >/dev/null
cmake --build "$dir" -j "$jobs"

# Embree and TBB are system libraries built without sanitizers; their worker threads' caches are not
# leaks of ours (lsan.supp). halt_on_error turns every report into a failed test.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"
ctest --test-dir "$dir" --output-on-failure -j "$jobs" "$@"
echo "sanitize: ASan+UBSan suite passed in $(($(date +%s) - start)) s"
