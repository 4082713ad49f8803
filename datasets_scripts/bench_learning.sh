#!/usr/bin/env bash
# Local vs full-batch learning of the ML-JGPM torus on the default training split (issue #3's
# benchmark): trains it both ways, each to convergence unless a full-batch time limit is
# given, then prints how each ended, its final full objective, wall time and training
# reconstruction error, and when full-batch learning first reached the objective local
# learning ends at. Full-batch learning takes hours on 2 cores.
#
#   datasets_scripts/bench_learning.sh [OUT_DIR [FULL_MAX_SECONDS [THREADS]]]
#
# Models and logs go to OUT_DIR (default build/bench_learning); extra options for both runs
# can be passed in $JGPM_TRAIN_OPTIONS (e.g. "--data DIR").
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/bench_learning}"
full_max="${2:-0}"
threads="${3:-0}"
jgpm=build/tracker/cli/jgpm
[ -x "$jgpm" ] || datasets_scripts/build.sh --target jgpm
mkdir -p "$out"

run() {  # name, extra arguments; progress lines go to OUT_DIR/name.log
  local name="$1"; shift
  echo "== $name: jgpm train --model mljgpm-torus $* (log: $out/$name.log)" >&2
  # shellcheck disable=SC2086
  "$jgpm" train --model mljgpm-torus --threads "$threads" --out "$out/$name.json" "$@" \
    ${JGPM_TRAIN_OPTIONS:-} >"$out/$name.out" 2>"$out/$name.log"
}
run local --learning local
run full --learning full --max-iterations 1000000 --max-time "$full_max"

summary() {  # name -> "how|iterations|objective|seconds|reconstruction mm"
  local f="$out/$1.out"
  sed -nE 's/^[a-z]+ learning: (.*) after ([0-9]+) iterations, objective [^ ]+ -> ([^,]+), max jitter [^,]+, ([0-9.]+) s$/\1|\2|\3|\4/p' "$f" | head -n 1 |
    tr -d '\n'
  sed -nE 's/^training reconstruction error: ([0-9.]+) mm.*/|\1/p' "$f"
}
IFS='|' read -r l_how l_it l_obj l_s l_mm <<<"$(summary local)"
IFS='|' read -r f_how f_it f_obj f_s f_mm <<<"$(summary full)"

printf '\n%-8s | %-40s | %10s | %12s | %9s | %s\n' learning "how it ended" iterations objective "wall (s)" "training reconstruction (mm)"
printf '%-8s | %-40s | %10s | %12s | %9s | %s\n' local "$l_how" "$l_it" "$l_obj" "$l_s" "$l_mm"
printf '%-8s | %-40s | %10s | %12s | %9s | %s\n' full "$f_how" "$f_it" "$f_obj" "$f_s" "$f_mm"
# Progress lines: "full  ITER/MAX  objective F  jitter J  R it/s  T s, <= L s left".
awk -v target="$l_obj" -v local_s="$l_s" -v full_obj="$f_obj" -v full_s="$f_s" '
  $1 == "full" && $4 + 0 <= target + 0 && !found { found = 1; iter = $2; secs = $9 }
  END {
    gap = (target - full_obj) / (full_obj < 0 ? -full_obj : full_obj) * 100
    printf "\nlocal learning ends %.1f%% %s the full-batch objective (%s vs %s)\n", gap < 0 ? -gap : gap,
           gap < 0 ? "below" : "above", target, full_obj
    if (found) {
      sub("/.*", "", iter)
      printf "full-batch learning first reached the local objective at iteration %s, after %s s: local learning got there %.1fx faster\n", iter, secs, secs / local_s
    } else {
      print "full-batch learning never reached the local objective"
    }
    printf "full-batch learning to its end took %.1fx the time of local learning\n", full_s / local_s
  }' "$out/full.log"
