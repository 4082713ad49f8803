#!/usr/bin/env bash
# The paper's validation (issue #4): trains each model on the default split if OUT_DIR
# (default build/paper) has no model file for it yet (about 15 min on 2 cores; the ML-JGPM
# models by local learning), then runs every task x scale x condition on the test split
# with `jgpm eval --suite paper` (about 5 min) and writes OUT_DIR/paper.csv with
# interpolation.png, reconstruction.png and filtering.png.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/paper}"
mkdir -p "$out/models"
jgpm=build/tracker/cli/jgpm
[ -x "$jgpm" ] || datasets_scripts/build.sh --target jgpm
models=()
for kind in pca gplvm gpdm bgpdm llgpdm jgpm mljgpm-cyl mljgpm-torus; do
  model="$out/models/$kind.json"
  if [ ! -f "$model" ]; then
    learning=full
    case "$kind" in mljgpm-*) learning=local ;; esac
    echo "== training $kind ($learning learning), log in $model.log"
    "$jgpm" train --model "$kind" --learning "$learning" --out "$model" >"$model.log" 2>&1
    grep -E "learning:|reconstruction" "$model.log"
  fi
  models+=(--model "$model")
done
"$jgpm" eval --suite paper "${models[@]}" --out "$out"
