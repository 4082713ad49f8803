#!/usr/bin/env bash
# How InferenceOptions::gain_std (posture adaptation's amplitude-gain prior, issue #15) was
# chosen, from the training subjects alone: leave one subject out over the default `train`
# split's four subjects (ML-JGPM torus, each fold trained on the other three, at most
# MAX_TIME s; reused from OUT/models when present), then for each gain_std of a grid the
# mean error at s = 1 of interpolation and of the three reconstructions (left arm, leg,
# side missing) over the held-out subjects, each weighing alike. The smallest mean of the
# four cases wins. About 13 min on 2 cores the first time, 1 min after.
#
#   datasets_scripts/choose_gain_std.sh [OUT=build/gain_std [MAX_TIME=300]]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/gain_std}"
max_time="${2:-300}"
jgpm=build/tracker/cli/jgpm
[ -x "$jgpm" ] || datasets_scripts/build.sh --target jgpm
mkdir -p "$out"
echo "== fold models (log: $out/folds.log)"
"$jgpm" eval --suite loso --trials train --kinds mljgpm-torus --adapt none --max-time "$max_time" --out "$out" \
  >"$out/folds.log" 2>&1
subjects=$(grep -vE '^\s*(#|$)' datasets_scripts/splits/train.txt | cut -d_ -f1 | sort -u)
for s in $subjects; do grep -E "^${s}_" datasets_scripts/splits/train.txt >"$out/held-$s.txt"; done
cases=("--task interpolation" "--task reconstruction --missing left-arm" "--task reconstruction --missing left-leg"
       "--task reconstruction --missing left-side")
echo "gain_std,interpolation,left_arm,left_leg,left_side,mean" | tee "$out/gain_std.csv"
for g in 0.05 0.1 0.15 0.2 0.3 0.5; do
  row="$g"
  for c in "${cases[@]}"; do
    errors=""
    for s in $subjects; do
      # shellcheck disable=SC2086
      "$jgpm" eval --model "$out/models/mljgpm-torus-without-$s.json" $c --trials "$out/held-$s.txt" \
        --adapt posture --gain-std "$g" --json "$out/e.json" >/dev/null
      errors="$errors $(grep -oE '"mean_error_mm": *[0-9.e+-]+' "$out/e.json" | head -1 | grep -oE '[0-9.e+-]+$')"
    done
    row="$row,$(echo "$errors" | awk '{ s = 0; for (i = 1; i <= NF; ++i) s += $i; printf "%.2f", s / NF }')"
  done
  echo "$row" | awk -F, '{ printf "%s,%.2f\n", $0, ($2 + $3 + $4 + $5) / 4 }' | tee -a "$out/gain_std.csv"
done
best=$(tail -n +2 "$out/gain_std.csv" | sort -t, -k6 -g | head -1 | cut -d, -f1)
echo "best gain_std: $best (InferenceOptions::gain_std; jgpm eval --gain-std)"
