#!/usr/bin/env bash
# Second of the two device calls of bench/gpu_bundle.sh (copied there as .gpuB/run.sh), run
# from the checkout's root with .gpuB and .gl carried: Xvfb from the bundle (its GLX through
# Mesa's swrast, softpipe), the bench's GL through NVIDIA's GLX vendor library
# (__GLX_VENDOR_LIBRARY_NAME=nvidia), logs to $OUT. The renderer each run got is the
# "renderer:" line of its log (glGetString(GL_RENDERER) of the bench's window).
# Here, for a dry run: SKIP_INSTALL=1 GLX_VENDOR=mesa EXPECT=llvmpipe FRAMES=3.
export PATH=$PATH:/usr/sbin:/sbin
D=/tmp/relight-gpu
OUT=${OUT:-$D/out}
FRAMES=${FRAMES:-30}
VENDOR=${GLX_VENDOR:-nvidia}
EXPECT=${EXPECT:-NVIDIA}
mkdir -p "$OUT"
exec > >(tee "$OUT/run.txt") 2>&1
[ -e "$D/a/ok" ] || { echo "stage A is not here: the machine was not kept warm"; exit 3; }
mkdir -p "$D/b"
xz -dc .gpuB/b.tar.xz | tar -C "$D/b" -xf - || exit 1
DRI=/usr/lib/x86_64-linux-gnu/dri  # where Xvfb looks for swrast_dri.so (compiled in)
if [ -z "${SKIP_INSTALL:-}" ]; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    mkdir -p $DRI /var/lib/xkb /usr/share/X11 /tmp/.X11-unix
    [ -e $DRI/swrast_dri.so ] || cp "$D/b/dri/swrast_dri.so" $DRI/
    [ -x /usr/bin/xkbcomp ] || cp "$D/b/bin/xkbcomp" /usr/bin/  # Xvfb runs it from /usr/bin
    [ -d /usr/share/X11/xkb ] || cp -r "$D/b/xkb" /usr/share/X11/xkb
fi
NV=$(ldconfig -p | sed -n 's/.*libGLX_nvidia.so.0 .*=> //p' | head -1)
[ -n "$NV" ] || NV=$(find / -name 'libGLX_nvidia.so.0' -not -path '/proc/*' 2>/dev/null | head -1)
echo "NVIDIA GLX vendor library: ${NV:-none found}"
NVDIR=$(dirname "${NV:-/nonexistent/x}")
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
echo "CPU: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo)"

N=99  # the first display number free here
while [ -e /tmp/.X11-unix/X$N ] || [ -e /tmp/.X$N-lock ]; do N=$((N + 1)); done
LD_LIBRARY_PATH=$D/b/lib:$D/b/stub GALLIUM_DRIVER=softpipe "$D/b/bin/Xvfb" :$N \
    -screen 0 1920x1080x24 -nolisten tcp -fp built-ins >"$OUT/xvfb.txt" 2>&1 &
XPID=$!
for _ in $(seq 50); do [ -e /tmp/.X11-unix/X$N ] && break; sleep 0.2; done
if [ ! -e /tmp/.X11-unix/X$N ] || ! kill -0 $XPID 2>/dev/null; then
    echo "Xvfb did not start:"
    cat "$OUT/xvfb.txt"
    exit 4
fi

echo "=== what the GLX client library ($VENDOR) offers on Xvfb (bench/gpu_glx_probe.c):"
env LD_LIBRARY_PATH=$D/b/lib:$NVDIR DISPLAY=:$N __GLX_VENDOR_LIBRARY_NAME=$VENDOR \
    timeout 30 "$D/b/bin/gpu_glx_probe"

bench() {  # bench LOG SECONDS ARGS...: the bench, SECONDS at most
    local log=$1 limit=$2
    shift 2
    echo "=== $log: viewer_frames data $*"
    local t0=$SECONDS
    env LD_LIBRARY_PATH=$D/a/lib:$D/b/lib:$D/a/stub:$NVDIR DISPLAY=:$N \
        __GLX_VENDOR_LIBRARY_NAME=$VENDOR timeout "$limit" "$D/b/bin/viewer_frames" data "$@" \
        >"$OUT/$log" 2>&1
    echo "exit $? after $((SECONDS - t0)) s"
    grep -E "^renderer" "$OUT/$log"
}
bench gpu_room_x1.txt 120 --frames "$FRAMES"
if grep -q "^renderer:.*$EXPECT" "$OUT/gpu_room_x1.txt"; then
    bench gpu_room_x4.txt 200 --upscale 4 --frames "$FRAMES"
    bench gpu_courtyard_x1.txt 90 --scene courtyard --frames "$FRAMES"
else
    echo "the run did not get the $EXPECT renderer; its log:"
    tail -20 "$OUT/gpu_room_x1.txt"
fi
kill $XPID
