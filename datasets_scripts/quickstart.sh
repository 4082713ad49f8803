#!/usr/bin/env bash
# Quick start, step 1: install missing packages, build, and run the main job on its default
# input: prepare the default training gait dataset (one gait cycle per walking trial of
# datasets_scripts/splits/train.txt), learn the ML-JGPM torus prior from it with
# topology-aware local learning (about 4 min on 2 cores) and plot its latent space; then
# render one clip of the tracking suite (subject 07, whom the prior has never seen, in 4
# cameras) and track it with that prior: error against the clip's truth, frames per
# second, poses.json, tracked.bvh and an overlay video per camera.
set -euo pipefail
cd "$(dirname "$0")/.."
datasets_scripts/install_deps.sh
datasets_scripts/build.sh --target jgpm jgpm_python
PYTHONPATH=build/python python3 -c 'import jgpm; print("jgpm", jgpm.__version__, "for Python: PYTHONPATH=build/python")'

# Motion data: --data / $JGPM_DATA / ./data/cmu / ../shared/data/cmu; fetch it when online
# and none is there.
# (A root holds data when a subject folder has its .asf, as jgpm decides: io/gait/data_root.h.)
holds_data() { compgen -G "$1/subjects/*/*.asf" >/dev/null; }
if [ -z "${JGPM_DATA:-}" ] && ! holds_data data/cmu && ! holds_data ../shared/data/cmu; then
  datasets_scripts/fetch_cmu.sh
fi
./build/tracker/cli/jgpm data cycles --split train --out build/train_cycles.json
./build/tracker/cli/jgpm train --model mljgpm-torus --learning local --out build/mljgpm-torus.json
./build/tracker/cli/jgpm plot latent build/mljgpm-torus.json --out build/mljgpm-torus.png
ONLY=07_01-4cam datasets_scripts/render_suite.sh build/tracking_suite
rm -rf build/track-07_01-4cam  # jgpm track refuses a non-empty folder; this one is ours
./build/tracker/cli/jgpm track --model build/mljgpm-torus.json --clip build/tracking_suite/07_01-4cam \
  --out build/track-07_01-4cam
