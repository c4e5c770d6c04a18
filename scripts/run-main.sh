#!/usr/bin/env bash
# README command 1: install, build, and run the main job on the bundled room.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p out
./build/relight/relight solve data/room -o out/room-radiosity.exr --report out/room-report.json
./build/relight/relight solve data/room --spp 4 -o out/room-radiosity.png >/dev/null
echo "main job done: out/room-radiosity.exr, out/room-radiosity.png, out/room-report.json"
