#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang) into ./build-fuzz and runs each for RUNS
# executions (default 100000). Each starts from the bundled scenes' files of its kind
# (data/*/scene.json, data/*/edits/*.json, data/*/*.obj and data/*/objects/*.obj, copied
# here at each run) and from fuzz/corpus/<target>/ (inputs that once failed, kept so that
# they are tried again; for colmap, whose inputs are a COLMAP model's files behind a byte
# that picks the file, its seeds too). Prints per target the executions, the time and the findings;
# libFuzzer writes a finding to build-fuzz/findings/. Exits non-zero when any target has a
# finding.
#   bash scripts/fuzz.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
runs=${1:-100000}

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DRELIGHT_FUZZ=ON -DRELIGHT_WERROR=ON -DRELIGHT_BUILD_TESTS=OFF -DRELIGHT_BUILD_BENCH=OFF \
    -DRELIGHT_BUILD_VIEWER=OFF >/dev/null
cmake --build build-fuzz --target relight_fuzzers -j"$(nproc)"

# Seeds: one file per bundled input, named after its path (data/room/edits/x.json ->
# room_edits_x.json).
seed() {
    local target=$1
    shift
    rm -rf "build-fuzz/seeds/$target"
    mkdir -p "build-fuzz/seeds/$target"
    for f in "$@"; do cp "$f" "build-fuzz/seeds/$target/$(echo "${f#data/}" | tr / _)"; done
}
seed scene_json data/*/scene.json
seed edit_json data/*/edits/*.json
seed obj data/*/*.obj data/*/objects/*.obj
# COLMAP models: the first byte picks the file (fuzz/colmap_fuzz.cpp); their seeds are
# in fuzz/corpus/colmap/.
seed colmap

failed=0
printf '%-12s %10s %8s %9s  %s\n' target executions seconds findings seeds \
    >build-fuzz/fuzz-summary.txt
for target in scene_json edit_json obj colmap; do
    # The corpus libFuzzer grows starts empty, so that every run starts from the same seeds.
    rm -rf "build-fuzz/corpus/$target" "build-fuzz/findings/$target"
    mkdir -p "build-fuzz/corpus/$target" "build-fuzz/findings/$target" build-fuzz/logs
    log=build-fuzz/logs/$target.log
    corpora=("build-fuzz/corpus/$target" "build-fuzz/seeds/$target")
    [ -d "fuzz/corpus/$target" ] && corpora+=("fuzz/corpus/$target")
    cmd=(build-fuzz/fuzz/fuzz_$target -runs="$runs" -timeout=10 -rss_limit_mb=2048
        -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$target/" "${corpora[@]}")
    echo "== ${cmd[*]}"
    start=$(date +%s%N)
    status=0
    "${cmd[@]}" >"$log" 2>&1 || status=$?
    seconds=$(awk -v ns=$(($(date +%s%N) - start)) 'BEGIN { printf "%.1f", ns / 1e9 }')
    executions=$(awk '/stat::number_of_executed_units/ {print $NF}' "$log")
    findings=$(find "build-fuzz/findings/$target" -type f | wc -l)
    nseeds=$(find "${corpora[@]:1}" -type f | wc -l)
    printf '%-12s %10s %8s %9s  %s\n' "$target" "${executions:-?}" "$seconds" "$findings" \
        "$nseeds" | tee -a build-fuzz/fuzz-summary.txt
    if [ "$status" -ne 0 ] || [ "$findings" -ne 0 ]; then
        echo "fuzz: $target failed (exit $status); the input is in build-fuzz/findings/$target/:"
        tail -n 40 "$log"
        failed=1
    fi
done
echo
cat build-fuzz/fuzz-summary.txt
exit "$failed"
