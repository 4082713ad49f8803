#!/usr/bin/env bash
# Renders the tracking benchmark (datasets_scripts/tracking_suite.txt, or the suite file
# SUITE names, e.g. SUITE=datasets_scripts/realism_suite.txt or crowd_suite.txt) into OUT_DIR (default
# build/tracking_suite), one folder per clip; clips already there are kept.
# Data root: $JGPM_DATA, else ./data/cmu, else ../shared/data/cmu. Extra arguments go to
# every `jgpm render` (e.g. --max-frames 10 for a quick look). ONLY=NAME renders that clip
# alone; JGPM=PATH renders with that jgpm (default build/tracker/cli/jgpm, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/tracking_suite}"
shift || true
jgpm="${JGPM:-build/tracker/cli/jgpm}"
[ -x "$jgpm" ] || [ -n "${JGPM:-}" ] || datasets_scripts/build.sh --target jgpm
root="${JGPM_DATA:-}"
if [ -z "$root" ]; then
  for candidate in data/cmu ../shared/data/cmu; do
    if [ -d "$candidate/subjects" ]; then root="$candidate"; break; fi
  done
fi
[ -n "$root" ] || { echo "render_suite: no CMU data (set JGPM_DATA)" >&2; exit 1; }
mkdir -p "$out"
while read -r name trial options; do
  case "$name" in ''|'#'*) continue ;; esac
  if [ -n "${ONLY:-}" ] && [ "$name" != "$ONLY" ]; then continue; fi
  if [ -f "$out/$name/ground_truth.json" ]; then
    echo "== $name: already rendered"
    continue
  fi
  echo "== $name: $trial $options"
  amcs=()  # one --amc per walker: TRIAL may be several joined by '+'
  IFS='+' read -ra walkers <<< "$trial"
  for walker in "${walkers[@]}"; do amcs+=(--amc "$root/subjects/${walker%%_*}/$walker.amc"); done
  # shellcheck disable=SC2086  # the options are words
  "$jgpm" render "${amcs[@]}" --out "$out/$name" $options "$@"
done < "${SUITE:-datasets_scripts/tracking_suite.txt}"
echo "tracking suite in $out"
