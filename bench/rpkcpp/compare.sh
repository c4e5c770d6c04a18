#!/usr/bin/env bash
# relight's offline solve against rpkCpp (RenderPark's hierarchical Galerkin radiosity) on
# data/cornell: time against error, in one run, both pinned to the same core (taskset -c 0).
#   bash bench/rpkcpp/build.sh /tmp/rpkcpp            # once: the peer, from its public source
#   RPK=/tmp/rpkcpp/build/rpk bash bench/rpkcpp/compare.sh [quick]
# Every image is scored by `relight eval data/cornell identity IMG` (the spec's metric
# against truth/identity.exr: 4x4 blocks, emitter masks; noise floor 0.0132).
# - relight (photo ρ): `relight solve data/cornell -o IMG` at each setting: reflectance
#   estimated from the photo, 16 samples per pixel. solve s: the solver's own times summed
#   (the `time:` line: build, refine+visibility, gather, push-pull, over every solve of the
#   reflectance rounds); image s: the per-pixel lighting for -o (direct light per sample,
#   final gather per pixel); wall s: the whole command.
# - relight (given ρ): the same with --no-photo-reflectance on a copy of the scene whose
#   scene.json holds the reflectances data/cornell/README.md publishes: the forward problem
#   rpkCpp solves.
# - rpkCpp: Galerkin radiosity (its defaults: hierarchical, clustered, linear basis, Jacobi)
#   at each link error threshold, its solution written after every iteration; solve s: the
#   CPU time it reports (one thread); the image: bench/rpkcpp/render_vrml.py, its elements'
#   corner radiances interpolated at relight's camera, 16 rays per pixel. It is given the
#   true reflectances (relight estimates them).
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${RELIGHT:-./build/relight/relight}
RPK=${RPK:?set RPK to the rpk binary that bench/rpkcpp/build.sh made}
PY=${PYTHON:-/usr/bin/python3}  # Debian's python3 with python3-openimageio, python3-numpy
scene=data/cornell
quick=${1:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "command: RPK=$RPK bash bench/rpkcpp/compare.sh $quick"
echo "relight $(git rev-parse --short HEAD), rpk: $RPK; both on core 0 (taskset -c 0)"
$PY bench/rpkcpp/cornell_mgf.py $scene "$tmp/cornell.mgf" --scene-copy "$tmp/given"
score() { $B eval $scene identity "$1" | awk '/^rel_rmse/ {print $2}'; }

printf '%-16s %-44s %9s %9s %9s %9s %8s\n' solver setting solve_s image_s wall_s elements rel_rmse
relight_row() {  # label, scene dir, args...
  local label=$1 dir=$2
  shift 2
  local t0 t1 log=$tmp/relight.log
  t0=$(date +%s.%N)
  taskset -c 0 $B solve "$dir" -o "$tmp/r.exr" "$@" > "$log" 2>&1
  t1=$(date +%s.%N)
  local solve image leaves
  solve=$(awk '/^time:/ {gsub(/,/, ""); print $3 + $6 + $9 + $12}' "$log")
  image=$(awk '/^per-pixel lighting/ {s = $(NF-1)} END {print s + 0}' "$log")
  leaves=$(sed -nE 's/.*\(leaves ([0-9]+)\).*/\1/p' "$log")
  printf '%-16s %-44s %9.3f %9.3f %9.2f %9s %8s\n' "$label" "$*" "$solve" "$image" \
    "$(awk "BEGIN {print $t1 - $t0}")" "$leaves" "$(score "$tmp/r.exr")"
}
if [ "$quick" = quick ]; then eps="1e-3 1e-4"; else eps="3e-3 1e-3 3e-4 1e-4 3e-5 1e-5 3e-6"; fi
for e in $eps; do relight_row "relight photo" $scene --epsilon $e; done
if [ "$quick" != quick ]; then
  for tb in 1 2 4; do relight_row "relight photo" $scene --epsilon 1e-6 --time-budget $tb; done
  relight_row "relight photo" $scene --epsilon 1e-4 --min-rays 1 --max-rays 4
  relight_row "relight photo" $scene --epsilon 1e-4 --min-rays 16 --max-rays 64
fi
for e in $eps; do relight_row "relight given" "$tmp/given" --no-photo-reflectance --epsilon $e; done

if [ "$quick" = quick ]; then ths="1e-5"; its="3 7"; else ths="1e-5 3e-6 1e-6 3e-7 1e-7"; its="2 4 6 8 10 12"; fi
for th in $ths; do
  rm -f "$tmp"/m_*.wrl
  log=$tmp/rpk_$th.log
  t0=$(date +%s.%N)
  # The model is written after every iteration (VRML writing is not in its CPU time).
  taskset -c 0 "$RPK" "$tmp/cornell.mgf" -radiance-method Galerkin -iterations 12 \
    -gr-link-error-threshold $th -radiance-model-savefile "$tmp/m_%d.wrl" > "$log" 2>&1
  t1=$(date +%s.%N)
  for it in $its; do
    cpu=$(grep 'CPU time' "$log" | sed -n "${it}p" | awk '{print $3}')
    el=$(grep 'Nr. elements' "$log" | sed -n "${it}p" | awk '{print $3}')
    $PY bench/rpkcpp/render_vrml.py $scene "$tmp/m_$((it - 1)).wrl" "$tmp/p.exr" > /dev/null
    wall=-
    [ "$it" = 12 ] && wall=$(awk "BEGIN {printf \"%.2f\", $t1 - $t0}")
    printf '%-16s %-44s %9.3f %9s %9s %9s %8s\n' "rpkCpp Galerkin" "threshold $th, $it iterations" \
      "$cpu" - "$wall" "$el" "$(score "$tmp/p.exr")"
  done
done
