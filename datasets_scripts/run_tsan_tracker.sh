#!/usr/bin/env bash
# ThreadSanitizer on the threaded particle filter: builds tests/tracker/filter/tracker_test.cc
# (tracker/filter/tracker_test: a short clip tracked end to end with 1 and 2 threads; the filter's
# ThreadPool, per-worker scratch, thread_local kinematics buffers and the pose table's
# build threads) with -fsanitize=thread in ./build-tsan, or the folder given, runs it, and
# fails on a failing test or any data-race report (halt_on_error).
# The libraries we do not build (OpenBLAS, OpenCV's TBB backend) are not instrumented, and
# their thread pools synchronise in ways TSan cannot see (it reports OpenCV's parallel_for_
# in the clip renderer as a race), so they must run single-threaded: OPENBLAS_NUM_THREADS=1,
# and the test is pinned to one CPU (taskset), from which TBB sizes its pool (Debian's
# OpenCV ignores OPENCV_FOR_THREADS_NUM). Our own threads (ThreadPool, the pose table's
# build threads) still run, interleaved: TSan checks the ordering of their accesses, not
# their timing, so one CPU hides no race. One report inside GDAL (OpenCV's imgcodecs loads
# it; a lock-order inversion between its own CPL mutexes while the clip's PNGs are written,
# on the main thread alone) is suppressed.
# -O1 as asked of sanitizer builds (CMAKE_CXX_FLAGS_RELEASE reduced to -DNDEBUG so
# Release's -O3 does not override it). target_clones (prior/numerics/rbf_row.cc, tracker/filter/likelihood.cc)
# is compiled as a plain function here: its ifunc resolver runs while the program is being
# relocated, before TSan's runtime is up, and an instrumented resolver crashes the program
# before main (gcc and clang alike).
# Measured on 2 cores: the build from scratch 2 min 54 s (more while other builds share
# the cores), the test 54 s (about 15x its Release time: TSan, and one CPU).
#
#   datasets_scripts/run_tsan_tracker.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-tsan}"

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-DNDEBUG \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread -g -O1 '-Dtarget_clones(...)=noinline'" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DJGPM_BUILD_TESTS=ON -DJGPM_BENCHMARKS=OFF -DJGPM_FUZZ=OFF >/dev/null
cmake --build "$build" --target tracker_filter_tracker_test

log="$(mktemp)" suppressions="$(mktemp)"
trap 'rm -f "$log" "$suppressions"' EXIT
echo "deadlock:libgdal.so" >"$suppressions"
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$suppressions ${TSAN_OPTIONS:-}"
export OPENBLAS_NUM_THREADS=1
status=0
taskset -c 0 "$build/tests/tracker_tracker_test" 2>&1 | tee "$log" || status=$?
if grep -q "WARNING: ThreadSanitizer" "$log"; then
  echo "run_tsan_tracker.sh: ThreadSanitizer reported a data race (above)" >&2
  status=1
fi
[ "$status" -eq 0 ] && echo "run_tsan_tracker.sh: no data race reported"
exit "$status"
