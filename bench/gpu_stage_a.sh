#!/usr/bin/env bash
# First of the two device calls of bench/gpu_bundle.sh (copied there as .gpuA/stage_a.sh):
# unpacks the bench's libraries under /tmp/relight-gpu/a, where the second call (on the same
# warm machine) finds them, checks that each loads there, and says what the machine has.
export PATH=$PATH:/usr/sbin:/sbin
D=/tmp/relight-gpu
OUT=${OUT:-/tmp/relight-gpu/out}
mkdir -p "$D/a" "$OUT"
xz -dc .gpuA/a.tar.xz | tar -C "$D/a" -xf - || exit 1
{
    head -2 /etc/os-release; ldd --version | head -1; nproc
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
    echo "--- GL/GLX/EGL libraries known to ldconfig:"
    ldconfig -p | grep -E 'libGLX|libEGL|libGL\.|nvidia-glcore|libLLVM|libglapi' || true
    echo "--- Mesa, Xvfb, xkbcomp already there:"
    ls /usr/lib/x86_64-linux-gnu/dri 2>&1 | head -5; command -v Xvfb xkbcomp
    ls -d /usr/share/X11/xkb 2>&1
} 2>&1 | tee "$OUT/stage_a.txt"
echo "--- each library loads (RTLD_NOW):" | tee -a "$OUT/stage_a.txt"
LD_LIBRARY_PATH=$D/a/lib:$D/a/stub python3 -c '
import ctypes, glob, os, sys
bad = 0
libs = sorted(glob.glob(sys.argv[1] + "/lib/*"))
for f in libs:
    try:
        ctypes.CDLL(f, mode=os.RTLD_NOW)
    except OSError as e:
        bad += 1
        print("FAILED", e)
print(len(libs), "libraries,", bad, "failed")
sys.exit(1 if bad else 0)' "$D/a" 2>&1 | tee -a "$OUT/stage_a.txt"
[ "${PIPESTATUS[0]}" -eq 0 ] && touch "$D/a/ok" && echo "stage A ok"
