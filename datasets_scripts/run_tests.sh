#!/usr/bin/env bash
# Quick start, step 2 (and what CI runs): install missing packages, build everything, run
# the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
datasets_scripts/install_deps.sh
datasets_scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
