#!/usr/bin/env bash
# Downloads the CMU motion-capture trials named in the splits (and their subjects' ASF
# skeletons) from the CMU site into ./data/cmu, in the CMU layout jgpm reads:
#   data/cmu/subjects/NN/NN.asf, data/cmu/subjects/NN/NN_TT.amc
# For users who are online; the build never runs it (tests/io/fetch_cmu_test runs it
# against a closed port, a server that never answers and a local file:// mirror).
#
# Files already in the output folder are kept. The others are downloaded into
# OUT.partial-PID beside it and moved into OUT only when every one has arrived, so a
# failed or interrupted run leaves no empty or half-filled data root behind. One connection
# check comes first (the server must answer within 10 s): offline, the script fails within
# seconds with one message saying where to put the data instead.
#
#   datasets_scripts/fetch_cmu.sh [SPLIT_FILE ...]   (default: every file in splits/,
#       walking16.txt included: 66 trials of 16 subjects, 11 of them not in
#       ../shared/data/cmu)
#   datasets_scripts/fetch_cmu.sh datasets_scripts/splits/walking16.txt   (just walking16)
#   JGPM_CMU_URL=URL   to use a mirror (default http://mocap.cs.cmu.edu)
#   JGPM_DATA_OUT=DIR  to download into DIR instead of ./data/cmu (relative to the
#                      repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
base="${JGPM_CMU_URL:-http://mocap.cs.cmu.edu}"
out="${JGPM_DATA_OUT:-data/cmu}"
out="${out%/}"
splits=("$@")
[ ${#splits[@]} -gt 0 ] || splits=(datasets_scripts/splits/*.txt)
where_to_put="Put the CMU data (subjects/NN/NN.asf, NN_TT.amc) in ./data/cmu, or point \
\$JGPM_DATA or --data at a folder holding it, or place it in ../shared/data/cmu; or run this \
again when online (JGPM_CMU_URL=URL for a mirror)."

if command -v curl >/dev/null; then
  # Any answer, even an HTTP error, shows the server is reachable.
  check() { curl -sS --connect-timeout 5 --max-time 10 --head -o /dev/null "$1"; }
  get() { curl -fsS --connect-timeout 10 --speed-limit 1000 --speed-time 30 --retry 3 -o "$2" "$1"; }
elif command -v wget >/dev/null; then
  check() {  # exit 8: the server answered with an error
    local status=0
    timeout 10 wget -nv --spider --timeout=5 --tries=1 "$1" || status=$?
    [ "$status" -eq 0 ] || [ "$status" -eq 8 ]
  }
  get() { wget -nv --timeout=30 --tries=3 -O "$2" "$1"; }
else
  echo "fetch_cmu.sh: needs curl or wget (apt-get install -y curl). $where_to_put" >&2
  exit 1
fi

trials=$(sed -e 's/#.*//' "${splits[@]}" | tr -s ' \t' '\n' | grep -E '^[0-9]+_[0-9A-Za-z]+$' | sort -u || true)
if [ -z "$trials" ]; then
  echo "fetch_cmu.sh: no trial ids in ${splits[*]}" >&2
  exit 1
fi
num_trials=$(echo "$trials" | wc -w)

# Files (relative to the data root) not yet in $out.
needed=()
for trial in $trials; do
  subject="${trial%%_*}"
  for file in "subjects/$subject/$subject.asf" "subjects/$subject/$trial.amc"; do
    [ -s "$out/$file" ] && continue
    case " ${needed[*]-} " in *" $file "*) continue ;; esac
    needed+=("$file")
  done
done
if [ ${#needed[@]} -eq 0 ]; then
  echo "fetch_cmu.sh: all $num_trials trials already in $out"
  exit 0
fi

if ! reason=$(check "$base/${needed[0]}" 2>&1); then
  reason="${reason//$'\n'/ }"
  echo "fetch_cmu.sh: cannot reach $base (${reason:-no answer within 10 s}); nothing was" \
    "written. $where_to_put" >&2
  exit 1
fi

# Work in $partial beside $out; on any exit before the move, remove it and the parent
# folders this run created.
parent=$(dirname "$out")
created=""
probe="$parent"
while [ ! -e "$probe" ]; do
  created="$probe"
  probe=$(dirname "$probe")
done
partial="$out.partial-$$"
cleanup() {
  rm -rf "$partial"
  if [ -n "$created" ]; then
    local folder="$parent"
    while rmdir "$folder" 2>/dev/null && [ "$folder" != "$created" ]; do
      folder=$(dirname "$folder")
    done
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP
mkdir -p "$partial"
echo "fetch_cmu.sh: downloading ${#needed[@]} files from $base for $out"
for file in "${needed[@]}"; do
  mkdir -p "$partial/$(dirname "$file")"
  if ! reason=$(get "$base/$file" "$partial/$file" 2>&1); then
    reason="${reason//$'\n'/ }"
    echo "fetch_cmu.sh: cannot download $base/$file (${reason:-failed}); nothing was" \
      "written to $out. $where_to_put" >&2
    exit 1
  fi
done

# Complete: rename the folder into place (when $out is missing or empty), else merge,
# motions before skeletons so a subject is only seen as data once its files are there.
if ! mv -T "$partial" "$out" 2>/dev/null; then
  for file in "${needed[@]}"; do
    [ "${file##*.}" = amc ] || continue
    mkdir -p "$out/$(dirname "$file")"
    mv -f "$partial/$file" "$out/$file"
  done
  for file in "${needed[@]}"; do
    [ "${file##*.}" = asf ] || continue
    mkdir -p "$out/$(dirname "$file")"
    mv -f "$partial/$file" "$out/$file"
  done
fi
echo "fetch_cmu.sh: $num_trials trials in $out (${#needed[@]} files downloaded)"
