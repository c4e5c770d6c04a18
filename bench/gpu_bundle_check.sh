#!/usr/bin/env bash
# Runs the parts that bench/gpu_bundle.sh made on this machine, as the device would, with
# nothing but the bundle on the library path: stage A unpacked under /tmp/relight-gpu, Xvfb
# from .gpuB on display :98 (softpipe, LLVM's stand-in), the bench from .gpuB under
# llvmpipe (the client side here loads this machine's Mesa, there NVIDIA's). Prints each
# library the bench and Xvfb loaded from outside the bundle (glibc, the C++ runtime, GL).
#
#   bash bench/gpu_bundle_check.sh REPO_ROOT [bench arguments, default: --frames 5]
set -u
ROOT=$(realpath "${1:?usage: gpu_bundle_check.sh REPO_ROOT [args]}")
shift
ARGS=${*:---frames 5}
D=/tmp/relight-gpu
rm -rf "$D" && mkdir -p "$D/a" "$D/b"
xz -dc "$ROOT/.gpuA/a.tar.xz" | tar -C "$D/a" -xf -
xz -dc "$ROOT/.gpuB/b.tar.xz" | tar -C "$D/b" -xf -
E="env -i PATH=/usr/bin:/bin HOME=/tmp"
$E LD_LIBRARY_PATH=$D/b/lib:$D/b/stub GALLIUM_DRIVER=softpipe LD_DEBUG=libs \
    LD_DEBUG_OUTPUT=$D/xvfb.ld "$D/b/bin/Xvfb" :98 -screen 0 1920x1080x24 -nolisten tcp \
    >"$D/xvfb.txt" 2>&1 &
XPID=$!
for _ in $(seq 50); do [ -e /tmp/.X11-unix/X98 ] && break; sleep 0.2; done
cd "$ROOT" || exit 1
# shellcheck disable=SC2086
$E DISPLAY=:98 LIBGL_ALWAYS_SOFTWARE=1 LD_LIBRARY_PATH=$D/a/lib:$D/b/lib:$D/a/stub \
    LD_DEBUG=libs LD_DEBUG_OUTPUT=$D/bench.ld "$D/b/bin/viewer_frames" data $ARGS
rc=$?
kill $XPID
wait $XPID 2>/dev/null
echo "bench exit $rc; Xvfb's log:"
cat "$D/xvfb.txt"
echo "loaded from outside the bundle:"
cat "$D"/*.ld.* | sed -n 's/.*calling init: //p' | grep -v "^$D/" | sort -u | tr '\n' ' '
echo
