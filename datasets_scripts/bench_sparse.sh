#!/usr/bin/env bash
# Sparse (inducing-point) learning against local and full-batch learning (issue #17), all in
# one run so that the machine's drift touches every row alike:
#   1. `jgpm bench learning`: one objective evaluation, exact and sparse, against N
#      (synthetic data, one thread): OUT/scaling/scaling.csv and scaling.png.
#   2. ML-JGPM torus on the default split (N = 1800): local learning, sparse learning with
#      M = 100 and 200, and full-batch learning for a time budget (it takes hours).
#   3. Time to converge against N: local and sparse (M = 100) learning on half the default
#      split (N = 900) and on the `walking` split (41 clean cycles, N = 3690).
#   4. The paper suite (35 cases) for the sparse and local torus and cylinder models.
#   5. `jgpm bench inducing`: how many inducing inputs each learned model's objective
#      needs (the bound at its own parameters, greedy inducing inputs; for the local torus
#      also optimised): OUT/inducing/NAME/inducing_gap.csv and .png.
# Prints one table of wall time, iterations, exact final objective and training
# reconstruction; takes about 60 min on 2 cores with MAX_SECONDS = 300.
#
#   datasets_scripts/bench_sparse.sh [OUT_DIR [MAX_SECONDS]]
#
# MAX_SECONDS (default 300) bounds every training.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/bench_sparse}"
max="${2:-300}"
jgpm=build/tracker/cli/jgpm
[ -x "$jgpm" ] || datasets_scripts/build.sh --target jgpm
mkdir -p "$out"

"$jgpm" bench learning --out "$out/scaling"

# Half the default split (one trial each of 02 and 05, four each of 35 and 39): N = 900.
grep -E '^(02_01|05_01|35_0[1-4]|39_0[1-4])$' datasets_scripts/splits/train.txt >"$out/train-half.txt"

train() {  # name, model kind, split, extra options; stdout to OUT/name.out, progress to .log
  local name="$1" kind="$2" split="$3"; shift 3
  echo "== $name: jgpm train --model $kind --split $split $*" >&2
  "$jgpm" train --model "$kind" --split "$split" --out "$out/$name.json" "$@" >"$out/$name.out" 2>"$out/$name.log"
}
train torus-local mljgpm-torus train --learning local --max-time "$max"
train torus-sparse100 mljgpm-torus train --learning sparse --inducing 100 --max-time "$max"
train torus-sparse200 mljgpm-torus train --learning sparse --inducing 200 --max-time "$max"
train torus-full mljgpm-torus train --learning full --max-iterations 1000000 --max-time "$max"
train half-local mljgpm-torus "$out/train-half.txt" --learning local --max-time "$max"
train half-sparse100 mljgpm-torus "$out/train-half.txt" --learning sparse --inducing 100 --max-time "$max"
train walking-local mljgpm-torus walking --learning local --max-time "$max"
train walking-sparse100 mljgpm-torus walking --learning sparse --inducing 100 --max-time "$max"
train cyl-local mljgpm-cyl train --learning local --max-time "$max"
train cyl-sparse200 mljgpm-cyl train --learning sparse --inducing 200 --max-time "$max"

printf '\n%-18s | %5s | %-44s | %10s | %9s | %12s | %s\n' model N "how it ended" iterations "wall (s)" \
  "exact objective" "training reconstruction (mm)"
for name in torus-full torus-local torus-sparse100 torus-sparse200 half-local half-sparse100 walking-local \
  walking-sparse100 cyl-local cyl-sparse200; do
  f="$out/$name.out"
  n=$(sed -nE 's/^.*model: ([0-9]+) latent points.*/\1/p' "$f" | head -n 1)
  # "LEARNING learning: HOW after I iterations, objective A -> B, max jitter J, S s[; M inducing inputs, exact objective E]"
  line=$(grep -E '^[a-z]+ learning: ' "$f" | head -n 1)
  how=$(sed -nE 's/^[a-z]+ learning: (.*) after [0-9]+ iterations.*/\1/p' <<<"$line")
  iterations=$(sed -nE 's/.* after ([0-9]+) iterations.*/\1/p' <<<"$line")
  seconds=$(sed -nE 's/.*, ([0-9.]+) s(;.*)?$/\1/p' <<<"$line")
  objective=$(sed -nE 's/.*exact objective ([^ ]+)$/\1/p' <<<"$line")
  [ -n "$objective" ] || objective=$(sed -nE 's/.* -> ([^,]+),.*/\1/p' <<<"$line")
  mm=$(sed -nE 's/^training reconstruction error: ([0-9.]+) mm.*/\1/p' "$f")
  printf '%-18s | %5s | %-44s | %10s | %9s | %12s | %s\n' "$name" "$n" "$how" "$iterations" "$seconds" \
    "$objective" "$mm"
done

# When full-batch learning first passed local learning's final objective (its progress lines:
# "train  ITER/MAX iterations  (full)  objective F ... T s, ...").
local_objective=$(sed -nE 's/.* -> ([^,]+),.*/\1/p' "$out/torus-local.out" | head -n 1)
tr '\r' '\n' <"$out/torus-full.log" | awk -v target="$local_objective" '
  /\(full\)/ && !found { for (i = 1; i < NF; ++i) if ($i == "objective" && $(i + 1) + 0 <= target + 0) found = 1
                          if (found) for (i = 1; i < NF; ++i) if ($(i + 1) == "s,") print "full-batch learning passed local learning'"'"'s objective (" target ") after " $i " s" }
  END { if (!found) print "full-batch learning did not reach local learning'"'"'s objective (" target ") in its budget" }'

echo
"$jgpm" eval --suite paper --model "$out/torus-local.json" --model "$out/torus-sparse200.json" \
  --model "$out/cyl-local.json" --model "$out/cyl-sparse200.json" --out "$out/paper" >"$out/paper.log" 2>&1
echo "paper suite (35 cases, mean mm): $out/paper/paper.csv"
awk -F, 'NR > 1 { sum[$1] += $6; n[$1]++ } END { for (m in sum) printf "  %-20s %6.2f mm over %d cases\n", m, sum[m] / n[m], n[m] }' \
  "$out/paper/paper.csv" | sort

echo
for name in torus-local torus-full torus-sparse200 cyl-local walking-local; do
  echo "== bench inducing: $name"
  "$jgpm" bench inducing --model "$out/$name.json" --m 100,200,400,600,800,1000,1200,1800 --out "$out/inducing/$name"
done
echo "== bench inducing: torus-local, inducing inputs optimised"
"$jgpm" bench inducing --model "$out/torus-local.json" --m 200,400,600,800 --optimise-iterations 300 \
  --out "$out/inducing/torus-local-optimised"
