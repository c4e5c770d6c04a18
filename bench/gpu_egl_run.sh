#!/usr/bin/env bash
# The viewer's frames on the device's GPU through EGL (bench/viewer_frames --context egl, a
# pbuffer: no X server), the second of two calls on one warm machine, as .gpuC/run.sh:
#   bash bench/gpu_bundle.sh BUILD REPO            # .gpuA (the libraries) and .gl
#   mkdir REPO/.gpuC; strip -o REPO/.gpuC/viewer_frames BUILD/bench/viewer_frames
#   cp bench/gpu_egl_run.sh REPO/.gpuC/run.sh      # (.gpuC in REPO/.git/info/exclude)
#   device run: `bash .gpuA/stage_a.sh`, carry .gpuA; then `bash .gpuC/run.sh`, carry .gpuC .gl
# The libraries staged by stage_a.sh, the vendor-neutral GL loaders from .gl, NVIDIA's EGL
# vendor library from the driver's folder. Logs to $OUT. (NVIDIA's GLX offers no framebuffer
# configuration on Xvfb: bench/gpu_run.sh's probe, bench/RESULTS.md 2026-11-27.)
export PATH=$PATH:/usr/sbin:/sbin
D=/tmp/relight-gpu
mkdir -p "$OUT"
exec > >(tee "$OUT/run.txt") 2>&1
[ -e "$D/a/ok" ] || { echo "stage A is not here"; exit 3; }
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
ls -la /usr/local/nvidia/share/glvnd/egl_vendor.d/ 2>&1
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
echo "CPU: $(nproc) threads"
L=$D/a/lib:$D/a/stub:/usr/local/nvidia/lib64
bench() {  # bench LOG SECONDS ARGS...
    local log=$1 limit=$2
    shift 2
    echo "=== $log: viewer_frames data $* --context egl"
    local t0=$SECONDS
    env LD_LIBRARY_PATH=$L timeout "$limit" .gpuC/viewer_frames data "$@" --context egl >"$OUT/$log" 2>&1
    echo "exit $? after $((SECONDS - t0)) s"
    grep -E "^renderer" "$OUT/$log"
}
bench egl_room_x1.txt 150 --frames 30
if grep -q "^renderer:.*NVIDIA" "$OUT/egl_room_x1.txt"; then
    bench egl_room_x4.txt 240 --upscale 4 --frames 30
    bench egl_courtyard_x1.txt 120 --scene courtyard --frames 30
else
    tail -20 "$OUT/egl_room_x1.txt"
fi
