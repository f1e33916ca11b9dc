#!/usr/bin/env bash
# ThreadSanitizer: builds the core, the viewer's non-GL part (ui_core) and the test executables with
# SONARSIM_TSAN=ON and runs them: the render worker (cancellation, previews, supersession), the session, the
# simulator's shared frames and everything else in test_ui and test_core, and the mesh cache tests when
# they exist. Any report fails the run.
# TBB and Embree come uninstrumented from Debian. Every test executable of this build runs TBB algorithms on
# the calling thread (tests/tsan_serial_tbb.cpp): TSan cannot see libtbb's fork/join synchronisation and would
# report every parallel loop. Our own threads are all checked; races between iterations of one parallel loop
# are not (the ASan suite runs those with full parallelism, but ASan does not look for races).
# Suppressions (.ci/tsan.supp) are for TBB's and Embree's internals only, never for our code.
# Usage: .ci/tsan.sh [Catch2 test spec...]      (default: every test of each executable)
# Env:   SONARSIM_TSAN_DIR=build-tsan  SONARSIM_JOBS=$(nproc)
set -euo pipefail
cd "$(dirname "$0")/.."

dir="${SONARSIM_TSAN_DIR:-build-tsan}"
jobs="${SONARSIM_JOBS:-$(nproc)}"
start=$(date +%s)
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSONARSIM_TSAN=ON -DSONARSIM_BUILD_VIEWER=OFF \
      -DSONARSIM_GL_TESTS=OFF >/dev/null
# The executables that exercise threads; test_mesh_cache only once the geometry layer has it.
tests=(tests/ui/test_ui tests/core/test_core)
targets=(test_ui test_core)
if cmake --build "$dir" --target help | grep -q '^test_mesh_cache:'; then
    tests+=(tests/core/test_mesh_cache)
    targets+=(test_mesh_cache)
fi
cmake --build "$dir" -j "$jobs" --target "${targets[@]}"
echo "tsan: built in $(($(date +%s) - start)) s"

export TSAN_OPTIONS="halt_on_error=1:abort_on_error=1:second_deadlock_stack=1:suppressions=$PWD/.ci/tsan.supp:print_suppressions=0:${TSAN_OPTIONS:-}"
for t in "${tests[@]}"; do
    exe="$dir/$t"
    [ -x "$exe" ] || exe=$(find "$dir" -name "$(basename "$t")" -type f -executable | head -n 1)
    t0=$(date +%s)
    "$exe" "$@" >"$dir/$(basename "$t").tsan.log" 2>&1 || {
        grep -A 40 -m 1 "WARNING: ThreadSanitizer\|FAILED\|ERROR" "$dir/$(basename "$t").tsan.log" || tail -n 40 "$dir/$(basename "$t").tsan.log"
        echo "tsan: $(basename "$t") FAILED (log: $dir/$(basename "$t").tsan.log)"
        exit 1
    }
    echo "tsan: $(basename "$t"): $(tail -n 2 "$dir/$(basename "$t").tsan.log" | head -n 1) ($(($(date +%s) - t0)) s)"
done
echo "tsan: ThreadSanitizer suite passed in $(($(date +%s) - start)) s"
