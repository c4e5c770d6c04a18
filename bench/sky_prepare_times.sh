#!/usr/bin/env bash
# Preparation time with and without the sky's transfer vectors (issue 31). There is no
# switch (the transfer is measured inside each point's unitIrradiance, radiosity/emitter.cpp),
# so "without" is a copy of the scene with its environment light taken out (and out of the
# photos' lights_on). Each copy is prepared from scratch (`relight render --edit identity
# --no-cache --report`), ROUNDS rounds interleaved; prints time_s of the report's phases,
# the wall time and the peak memory.
#   bash bench/sky_prepare_times.sh [SCENE_DIR...]   (default: data/window_room data/courtyard;
#   ROUNDS=2)
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(data/window_room data/courtyard)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: bash bench/sky_prepare_times.sh ${*:-}"
for scene in "${scenes[@]}"; do
    /usr/bin/python3 - "$scene" "$work" <<'PY'
import json, os, sys
src, work = os.path.abspath(sys.argv[1]), sys.argv[2]
s = json.load(open(os.path.join(src, "scene.json")))
for var in ("sky", "nosky"):
    d = os.path.join(work, os.path.basename(src) + "_" + var)
    os.makedirs(d)
    for f in os.listdir(src):
        if f not in ("scene.json", ".relight"):
            os.symlink(os.path.join(src, f), os.path.join(d, f))
    t = json.loads(json.dumps(s))
    if var == "nosky":
        sky = [l["name"] for l in t["lights"] if l["type"] == "environment"]
        t["lights"] = [l for l in t["lights"] if l["type"] != "environment"]
        for p in t["photos"]:
            if "lights_on" in p:
                p["lights_on"] = [n for n in p["lights_on"] if n not in sky]
    json.dump(t, open(os.path.join(d, "scene.json"), "w"), indent=1)
PY
done
for round in $(seq "${ROUNDS:-2}"); do
    for scene in "${scenes[@]}"; do
        for var in sky nosky; do
            d="$work/$(basename "$scene")_$var"
            /usr/bin/time -f "%e %M" -o "$work/t.txt" "$relight" render "$d" \
                --edit "$d/edits/identity.json" -o "$work/o.exr" --no-cache \
                --report "$work/r.json" >/dev/null 2>&1
            /usr/bin/python3 - "$round $(basename "$scene") $var" "$work/r.json" "$work/t.txt" <<'PY'
import json, sys
r = json.load(open(sys.argv[2]))["time_s"]
wall, kb = open(sys.argv[3]).read().split()
phases = " ".join(f"{k} {r[k]:.2f}" for k in ("reflectance", "vertex_lighting") if k in r)
print(f"{sys.argv[1]:24s} prepare {r['prepare']:.2f} {phases} wall {wall} s peak {int(kb) / 1024:.0f} MB")
PY
        done
    done
done
