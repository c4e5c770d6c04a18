#!/usr/bin/env bash
# README command 2: install, build (warnings as errors), and run the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DRELIGHT_WERROR=ON
cd build
ctest --output-on-failure -j"$(nproc)"
