#!/usr/bin/env bash
# The benchmark suite in one command: builds Release if needed, runs every scene (each in its own process),
# writes bench/results/RESULTS.md, results.csv and results.json, and prints progress and the summary table.
# Usage: bench/run.sh [--quick] [--scenes a,b,...] [--no-view] [any other sonarsim_bench option]
#   --quick   smoke run (~1-2 min): small scenes, fewer settings and repeats, lighter reference; writes to
#             BUILD/bench/quick-results unless --out is given
# Env: SONARSIM_BUILD_DIR (default build)
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
cd "$repo"
build_dir="${SONARSIM_BUILD_DIR:-build}"

if [ -f "$build_dir/build.ninja" ] && grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$build_dir/CMakeCache.txt"; then
  cmake --build "$build_dir" -j 2 --target sonarsim sonarsim_bench
else
  # Not built yet (or not Release): install what is missing, configure Release, build everything.
  SONARSIM_BUILD_DIR="$build_dir" ./.ci/setup.sh
fi

SONARSIM_BENCH_COMMAND="bench/run.sh${*:+ $*}" exec "$build_dir/sonarsim_bench" --repo "$repo" --sonarsim "$build_dir/sonarsim" --work "$build_dir/bench" "$@"
