#!/usr/bin/env bash
# Builds a relight scene package around a real interior model: a decimated Crytek Sponza
# atrium (CC BY 3.0, see README.md here), for trying the engine on a mesh of a realistic
# size. Not part of CI: the model is 3.8 MB and comes from outside the repository.
#
#   bash bench/real_interior/make_scene.sh SOURCE [OUT_DIR] [--photo]
#
# SOURCE is sponza_s_lod4.glb itself, or a git directory holding the repository
# nakamura196/3d-progressive-loading-react (the model is read from its HEAD). OUT_DIR
# defaults to /tmp/relight-sponza. --photo also writes a constant 18 % grey photo (needs
# oiiotool): only so that the commands that need a photo run; it says nothing about the
# room. Without it the scene has no photo, which the scene format allows ("a scene without
# photos can be solved but not relit"): `relight solve` runs, with scene.json's
# reflectances (average_reflectance 0.5).
set -euo pipefail

source_arg=${1:?usage: make_scene.sh SOURCE [OUT_DIR] [--photo]}
out=${2:-/tmp/relight-sponza}
photo=no
[ "${3:-}" = "--photo" ] && photo=yes

model_path=public/data/models/sponza/sponza_s_lod4.glb
# The file this script was written for (git blob 9a1b9e99ab14a1c8551cb1a8f82b9b414687b4e3
# at commit 643d7b5978168bacfe0a86c9726be4dd333a063e): another file would not match the
# camera and lamps below.
expected_sha256=1cece4b91d1943ac6933db00ebf5d6f39fd64812d818c5c31d2ea858d6c5fb15

mkdir -p "$out"
if [ -d "$source_arg" ]; then
  git --git-dir="$source_arg" show "HEAD:$model_path" > "$out/sponza.glb"
else
  cp "$source_arg" "$out/sponza.glb"
fi
actual=$(sha256sum "$out/sponza.glb" | cut -d' ' -f1)
if [ "$actual" != "$expected_sha256" ]; then
  echo "make_scene.sh: $out/sponza.glb has sha256 $actual, expected $expected_sha256" >&2
  exit 1
fi

# The model (glTF: metres, +Y up) spans x -16.2..20.0, y -1.1..18.8, z -9.4..10.4: the
# atrium runs along x, its floor near y = 0. The camera stands at (-10, 3, 0) looking
# along +x (world_to_camera rows: camera right = +z, image down = -y, forward = +x;
# t = -R C), 90 degrees wide at 320x240. Two 1 m x 1 m lamps hang at y = 6 over the
# courtyard at x = -5 and x = +5, emitting downwards (counter-clockwise seen from below).
photos=''
if [ "$photo" = yes ]; then
  oiiotool --pattern constant:color=0.18,0.18,0.18 320x240 3 -d half -o "$out/photo.exr"
  photos='"photos": [ { "file": "photo.exr", "encoding": "linear", "lights_on": ["north", "south"] } ],'
fi
cat > "$out/scene.json" <<JSON
{
  "format": "relight-scene/1",
  "geometry": ["sponza.glb"],
  "camera": {
    "width": 320, "height": 240,
    "K": [[160, 0, 159.5], [0, 160, 119.5], [0, 0, 1]],
    "world_to_camera": [[0, 0, 1, 0], [0, -1, 0, 3], [1, 0, 0, 10]]
  },
  $photos
  "lights": [
    { "name": "north", "type": "quad",
      "vertices": [[-5.5, 6, -0.5], [-4.5, 6, -0.5], [-4.5, 6, 0.5], [-5.5, 6, 0.5]],
      "radiance": [20, 20, 20] },
    { "name": "south", "type": "quad",
      "vertices": [[4.5, 6, -0.5], [5.5, 6, -0.5], [5.5, 6, 0.5], [4.5, 6, 0.5]],
      "radiance": [20, 18, 15] }
  ],
  "average_reflectance": 0.5
}
JSON
echo "scene written to $out (geometry $out/sponza.glb, photo: $photo)"
