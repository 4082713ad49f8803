#!/usr/bin/env bash
# Downloads the CMU motion-capture trials named in the splits (and their subjects' ASF
# skeletons) from the CMU site into ./data/cmu, in the CMU layout jgpm reads:
#   data/cmu/subjects/NN/NN.asf, data/cmu/subjects/NN/NN_TT.amc
# For users who are online; nothing in the build or the tests runs it.
#
#   datasets_scripts/fetch_cmu.sh [SPLIT_FILE ...]   (default: every file in splits/)
#   JGPM_CMU_URL=...  to use a mirror (default http://mocap.cs.cmu.edu)
set -euo pipefail
cd "$(dirname "$0")/.."
base="${JGPM_CMU_URL:-http://mocap.cs.cmu.edu}"
out="data/cmu"
splits=("$@")
[ ${#splits[@]} -gt 0 ] || splits=(datasets_scripts/splits/*.txt)

if command -v curl >/dev/null; then
  get() { curl -fsSL --retry 3 -o "$2" "$1"; }
elif command -v wget >/dev/null; then
  get() { wget -q --tries=3 -O "$2" "$1"; }
else
  echo "fetch_cmu.sh: needs curl or wget (apt-get install -y curl)" >&2
  exit 1
fi

fetch() {  # url, destination; skips files already there, never leaves partial files
  local url="$1" destination="$2"
  [ -s "$destination" ] && return 0
  mkdir -p "$(dirname "$destination")"
  if get "$url" "$destination.part"; then
    mv "$destination.part" "$destination"
    echo "fetched $destination"
  else
    rm -f "$destination.part"
    echo "fetch_cmu.sh: could not download $url" >&2
    return 1
  fi
}

trials=$(sed -e 's/#.*//' "${splits[@]}" | tr -s ' \t' '\n' | grep -E '^[0-9]+_[0-9A-Za-z]+$' | sort -u)
failed=0
for trial in $trials; do
  subject="${trial%%_*}"
  fetch "$base/subjects/$subject/$subject.asf" "$out/subjects/$subject/$subject.asf" || failed=1
  fetch "$base/subjects/$subject/$trial.amc" "$out/subjects/$subject/$trial.amc" || failed=1
done
if [ "$failed" -ne 0 ]; then
  echo "fetch_cmu.sh: some files are missing (see above); the CMU site may be unreachable" >&2
  exit 1
fi
echo "fetch_cmu.sh: $(echo "$trials" | wc -w) trials in $out"
