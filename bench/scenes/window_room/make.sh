#!/bin/sh
# Builds data/window_room: the package (gen.py) and its Cycles truths (render.py), every render
# under the heavy lock (the machine is shared). SPP: samples per pixel (384 by default: about
# 85 s a render on 2 threads). The photo and truth/identity differ only by the seed: their
# rel_rmse is the noise floor.
# Run from the repository root: sh bench/scenes/window_room/make.sh [SPP]
set -e
SPP=${1:-384}
HERE=bench/scenes/window_room
PKG=data/window_room
WORK=$(mktemp -d)
python3 $HERE/gen.py "$WORK"
mkdir -p $PKG/truth $PKG/edits
cp "$WORK/scene.json" "$WORK/window_room.obj" $PKG/
cp "$WORK"/edits/*.json $PKG/edits/
render() { flock /tmp/relight-heavy.lock blender -b --factory-startup -P $HERE/render.py -- "$WORK" "$@" >/dev/null; }
render 4 1 mask "$WORK/mask.exr"
# 255 where the pixel sees no emitter (the sky through the window), 0 where it does.
oiiotool "$WORK/mask.exr" --ch R --mulc 1e30 --clamp:min=0:max=1 --mulc -1 --addc 1 -d uint8 -o $PKG/photo.mask.png
render "$SPP" 1 identity $PKG/photo.exr
for e in identity sun_moved sky_rotated sun_off; do
  render "$SPP" 2 $e $PKG/truth/$e.exr
  cp $PKG/photo.mask.png $PKG/truth/$e.mask.png
done
# Half floats (relative precision 5e-4, far below the noise) keep the package near 2 MB.
for f in $PKG/photo.exr $PKG/truth/*.exr; do
  oiiotool "$f" -d half --compression zip -o "$f"
done
rm -rf "$WORK"
echo "wrote $PKG"
