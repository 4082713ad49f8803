#!/usr/bin/env bash
# CI, step 2: builds everything with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DJGPM_SANITIZE=ON; tests on, benchmarks and fuzzers off) in ./build-asan, or the folder
# given, and runs the whole test suite under them. Fails on a failing test and on any
# sanitizer report (memory error, leak, undefined behaviour), including reports from the
# `jgpm` processes the tests start: every report is written to BUILD_DIR/sanitizer-reports/
# (not to the test's output) and printed at the end.
# Compiler: $CXX if set, else clang++ when installed (it compiles the heaviest files here
# 10-35% faster than g++), else g++, which install_deps.sh installs.
#
#   datasets_scripts/run_sanitized_tests.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-asan}"
if [ -z "${CXX:-}" ]; then
  if command -v clang++ >/dev/null; then export CXX=clang++; else export CXX=g++; fi
fi

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DJGPM_SANITIZE=ON \
  -DJGPM_BUILD_TESTS=ON -DJGPM_BENCHMARKS=OFF -DJGPM_FUZZ=OFF >/dev/null
cmake --build "$build"

case "$build" in /*) reports="$build/sanitizer-reports" ;; *) reports="$PWD/$build/sanitizer-reports" ;; esac
rm -rf "$reports"
mkdir -p "$reports"
# Every report goes to a file $reports/report.PID instead of stderr, so the check below
# also catches reports of child processes whose exit status a test ignores.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:log_path=$reports/report"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$reports/report"
status=0
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" || status=$?

if [ -n "$(ls -A "$reports")" ]; then
  echo "run_sanitized_tests.sh: sanitizer reports (in $reports):" >&2
  for report in "$reports"/*; do
    echo "--- $report" >&2
    head -n 40 "$report" >&2
  done
  status=1
fi
exit "$status"
