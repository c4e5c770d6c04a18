#!/usr/bin/env bash
# The fuzz targets for 1000000 executions each (CI runs 100000): prints the command and, per
# target, the executions, the seconds and the findings. Figures: bench/RESULTS.md.
#   bash bench/fuzz.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-1000000}
echo "command: bash bench/fuzz.sh $runs (scripts/fuzz.sh $runs: build-fuzz/, clang, RelWithDebInfo)"
bash scripts/fuzz.sh "$runs"
