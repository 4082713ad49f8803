#!/usr/bin/env bash
# How InferenceOptions::gain_std and common_gain_std (posture adaptation's amplitude-gain
# prior, issue #15) were chosen, from the training subjects alone: leave one subject out
# over the default `train` split's four subjects (ML-JGPM torus, each fold trained on the
# other three, at most MAX_TIME s; reused from OUT/models when present). A held-out
# subject's score is its mean error at s = 1 over interpolation and the three
# reconstructions (left arm, leg, side missing); subjects weigh alike.
#  1. gain_std: the grid value with the smallest mean score (at the default common_gain_std).
#  2. common_gain_std, at that gain_std: the scores are flat from 0.05 up, so the one-standard-
#     error rule (Hastie et al., ESL 7.10) on the subjects' paired differences to the best
#     value: the smallest value whose mean difference is within one standard error of it.
# About 13 min on 2 cores the first time, 3 min after.
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
# error SUBJECT CASE OPTIONS...: the held-out subject's mean error (mm) in one case.
error() {
  # shellcheck disable=SC2086
  "$jgpm" eval --model "$out/models/mljgpm-torus-without-$1.json" $2 --trials "$out/held-$1.txt" --adapt posture \
    "${@:3}" --json "$out/e.json" >/dev/null
  grep -oE '"mean_error_mm": *[0-9.e+-]+' "$out/e.json" | head -1 | grep -oE '[0-9.e+-]+$'
}
mean() { awk '{ s = 0; for (i = 1; i <= NF; ++i) s += $i; printf "%.3f", s / NF }'; }
echo "gain_std,interpolation,left_arm,left_leg,left_side,mean" | tee "$out/gain_std.csv"
for g in 0.05 0.1 0.15 0.2 0.3 0.5; do
  row="$g"
  for c in "${cases[@]}"; do
    errors=""
    for s in $subjects; do errors="$errors $(error "$s" "$c" --gain-std "$g")"; done
    row="$row,$(echo "$errors" | mean)"
  done
  echo "$row" | awk -F, '{ printf "%s,%.2f\n", $0, ($2 + $3 + $4 + $5) / 4 }' | tee -a "$out/gain_std.csv"
done
best=$(tail -n +2 "$out/gain_std.csv" | sort -t, -k6 -g | head -1 | cut -d, -f1)
echo "best gain_std: $best (InferenceOptions::gain_std; jgpm eval --gain-std)"

echo "common_gain_std,$(paste -sd, <<<"$subjects"),mean" | tee "$out/common_gain_std.csv"
for t in 0 0.05 0.1 0.2 0.3 0.5 1; do
  row="$t"
  for s in $subjects; do
    errors=""
    for c in "${cases[@]}"; do errors="$errors $(error "$s" "$c" --gain-std "$best" --common-gain-std "$t")"; done
    row="$row,$(echo "$errors" | mean)"
  done
  echo "$row" | awk -F, '{ s = 0; for (i = 2; i <= NF; ++i) s += $i; printf "%s,%.3f\n", $0, s / (NF - 1) }' |
    tee -a "$out/common_gain_std.csv"
done
tail -n +2 "$out/common_gain_std.csv" | awk -F, '
  { n = NF - 2; value[NR] = $1; for (i = 1; i <= n; ++i) score[NR, i] = $(i + 1); total[NR] = $NF
    if (NR == 1 || $NF < total[best]) best = NR }
  END {
    for (r = 1; r <= NR; ++r) {
      m = 0; for (i = 1; i <= n; ++i) m += score[r, i] - score[best, i]; m /= n
      v = 0; for (i = 1; i <= n; ++i) v += (score[r, i] - score[best, i] - m) ^ 2
      se = sqrt(v / (n - 1) / n)
      printf "common_gain_std %s: %.2f mm above the best (%s), standard error %.2f\n", value[r], m, value[best], se
      if (!chosen && m <= se) chosen = value[r]
    }
    print "chosen common_gain_std: " chosen " (InferenceOptions::common_gain_std; jgpm eval --common-gain-std)"
  }'
