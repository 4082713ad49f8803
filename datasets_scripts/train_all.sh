#!/usr/bin/env bash
# Trains every model kind on the default training split into OUT_DIR (default
# build/models) and prints each model's summary; ML-JGPM models are trained with both
# full-batch and local learning. Long: the full-batch ML-JGPM runs take about an hour each
# on 2 cores. Logs go to OUT_DIR/<model>.log.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/models}"
mkdir -p "$out"
jgpm=build/tracker/cli/jgpm
train() {  # name, extra arguments
  local name="$1"; shift
  echo "== $name"
  /usr/bin/time -f "wall %e s" "$jgpm" train --out "$out/$name.json" "$@" >"$out/$name.log" 2>&1
  grep -E "learning:|reconstruction|wall" "$out/$name.log"
}
for kind in pca gplvm gpdm bgpdm llgpdm jgpm; do
  train "$kind" --model "$kind"
done
for kind in mljgpm-torus mljgpm-cyl; do
  train "$kind-local" --model "$kind" --learning local
  train "$kind-full" --model "$kind" --learning full --max-iterations 20000
done
