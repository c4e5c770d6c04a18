#!/usr/bin/env bash
# Packs bench/viewer_frames, Xvfb and Mesa's swrast (for Xvfb's GLX) into folders that the
# device tool carries to a GPU machine that has none of them (an Ubuntu CUDA image, nothing
# installable there), for the viewer's frame times on a real GPU (issue 32; bench/RESULTS.md,
# "2026-11-27 (eighth session)").
#
#   bash bench/gpu_bundle.sh BUILD_DIR REPO_ROOT
#
# BUILD_DIR: a Release build holding bench/viewer_frames. REPO_ROOT: the checkout that the
# device tool sends; the script writes REPO_ROOT/.gpuA, .gpuB and .gl there (and adds them to
# its .git/info/exclude). The tracked files of the checkout already take 50 of the 64 MiB that
# one call may carry, so the bundle is cut in two, each under 13 MiB:
#   .gpuA  the libraries the bench loads (Embree alone is 8.8 MB as xz);
#   .gpuB  the bench, bench/gpu_glx_probe.c built, X's client libraries, Xvfb, xkbcomp, the
#          xkb data, Mesa's swrast_dri.so (Xvfb's GLX provider: without it Xvfb has no GLX
#          extension and GLFW cannot make a window), run.sh;
#   .gl    the vendor-neutral GL loaders (glvnd) as Debian packages, as the device README says.
# Two calls on one warm machine: the first stages .gpuA under /tmp (stage_a.sh), the second
# (within the 30 s the machine stays warm) carries .gpuB and .gl and runs run.sh.
# Libraries that a carried one links but that these runs never call (OpenImageIO's ffmpeg,
# OpenVDB, DCMTK, OpenCV...; the assimp of the mesh reader, which a .obj scene skips; Mesa's
# LLVM, which softpipe in Xvfb never calls) are replaced by stand-ins that trap
# (bench/gpu_stub_lib.py): a run that called one would die with SIGILL, not print a figure.
# So llvmpipe (which needs the real 117 MB LLVM) cannot run there; the llvmpipe figures
# come from this machine (bench/RESULTS.md says which machine gave each).
set -euo pipefail
BUILD=$(realpath "${1:?usage: gpu_bundle.sh BUILD_DIR REPO_ROOT}")
ROOT=$(realpath "${2:?usage: gpu_bundle.sh BUILD_DIR REPO_ROOT}")
HERE=$(dirname "$(realpath "$0")")
LIBDIR=/usr/lib/x86_64-linux-gnu
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# Loaded from the machine itself: glibc, the C++ runtime (the device's Ubuntu 24.04 has newer
# ones, which run what Debian 12's built) and glvnd's loaders (from .gl).
SYSTEM=" libc.so.6 libm.so.6 libdl.so.2 libpthread.so.0 librt.so.1 ld-linux-x86-64.so.2 \
libresolv.so.2 libutil.so.1 libstdc++.so.6 libgcc_s.so.1 libGL.so.1 libGLX.so.0 \
libGLdispatch.so.0 libEGL.so.1 libOpenGL.so.0 "

# Stand-ins that return 0 rather than trap: what carried code calls at start and exit
# whatever it does, found by running the bundle here (bench/gpu_bundle_check.sh, gdb on the
# SIGILL): DCMTK's image-format registration (OpenImageIO's initialisers), systemd's socket
# activation and readiness (Xvfb: "no sockets passed"), LLVM's thread-safety switch (Mesa's
# initialisers; softpipe, which Xvfb's GLX uses there, never calls LLVM again).
RETURNS='^_ZN10DiRegister(C[12]|D[012])Ev$|^sd_(listen_fds|notify|notifyf|booted)$'
RETURNS+='|^LLVM(IsMultithreaded|StartMultithreaded|LinkInMCJIT)$'
# ... and those that return the string "stand-in": the version functions of the libraries
# whose plugins OpenImageIO lists before it opens any file.
TEXTS='^(opj_version|libraw_version|TIFFGetVersion|WebPGetDecoderVersion)$'

needed() { readelf -dW "$1" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'; }
resolve() {
    local p
    for p in "$LIBDIR/$1" "/lib/x86_64-linux-gnu/$1"; do
        [[ -e $p ]] && { realpath "$p"; return; }
    done
    echo "gpu_bundle: $1 not found" >&2
    exit 1
}

# pack DEST KEEP ELSEWHERE ROOT_FILE...: the real libraries in KEEP (and what they need, if
# kept) into DEST/lib, stand-ins for every other library that they or the roots need, except
# those in ELSEWHERE (packed in the other part).
pack() {
    local dest=$1 keep elsewhere
    keep=" $(echo $2) "  # one space between names, none at the ends
    elsewhere=" $(echo $3) "
    shift 3
    mkdir -p "$dest/lib" "$dest/stub"
    local -a queue=("$@") consumers=("$@")
    local -A seen=() stubs=()
    while ((${#queue[@]})); do
        local f=${queue[0]}
        queue=("${queue[@]:1}")
        local n
        for n in $(needed "$f"); do
            [[ $SYSTEM == *" $n "* || $elsewhere == *" $n "* || -n ${seen[$n]:-} ]] && continue
            seen[$n]=1
            if [[ $keep == *" $n "* ]]; then
                local real
                real=$(resolve "$n")
                cp "$real" "$dest/lib/$n"
                strip --strip-unneeded "$dest/lib/$n" 2>/dev/null || true
                queue+=("$real")
                consumers+=("$real")
            else
                stubs[$n]=1
            fi
        done
    done
    local s
    for s in "${!stubs[@]}"; do
        python3 "$HERE/gpu_stub_lib.py" --ret "$RETURNS" --str "$TEXTS" "$(resolve "$s")" "$dest/stub" "${consumers[@]}" >/dev/null
    done
    echo "$(basename "$dest"): ${#seen[@]} libraries, ${#stubs[@]} stand-ins:" ${!stubs[*]} >&2
}

# X's client libraries, in .gpuB for Xvfb; the bench loads them from there.
XCLIENT="libX11.so.6 libxcb.so.1 libXau.so.6 libXdmcp.so.6 libbsd.so.0 libmd.so.0"

# --- .gpuA: the libraries of the bench (the bench itself is in .gpuB, which has room) ---
A=$WORK/a
pack "$A" "libOpenImageIO.so.2.4 libOpenImageIO_Util.so.2.4 libembree3.so.3 libtbb.so.12
 libglfw.so.3 libepoxy.so.0 libOpenEXR-3_1.so.30 libOpenEXRCore-3_1.so.30 libIex-3_1.so.30 libImath-3_1.so.29
 libIlmThread-3_1.so.30 libz.so.1 libpng16.so.16 libjpeg.so.62 libboost_thread.so.1.74.0
 libtiff.so.6 liblzma.so.5 libdeflate.so.0 libzstd.so.1" \
    "$XCLIENT" "$BUILD/bench/viewer_frames"

# --- .gpuB: Xvfb, its GLX provider (Mesa's swrast), xkb ---
B=$WORK/b
mkdir -p "$B/bin" "$B/dri" "$B/xkb"
cp /usr/bin/Xvfb /usr/bin/xkbcomp "$BUILD/bench/viewer_frames" "$B/bin/"
strip "$B/bin/viewer_frames"
gcc -O1 -o "$B/bin/gpu_glx_probe" "$HERE/gpu_glx_probe.c" -lX11 -lGL
cp "$LIBDIR/dri/swrast_dri.so" "$B/dri/"
# What GLFW opens with dlopen (X extensions) and NVIDIA's GLX library links (libXext): an
# image without X has none of them.
DLOPENED="libXcursor.so.1 libXi.so.6 libXinerama.so.1 libXrandr.so.2 libXrender.so.1
 libX11-xcb.so.1 libXxf86vm.so.1 libXext.so.6 libXfixes.so.3"
mkdir -p "$B/lib"
for n in $DLOPENED; do cp "$(resolve "$n")" "$B/lib/$n"; done
cp -r /usr/share/X11/xkb/. "$B/xkb/"
rm -rf "$B/xkb/compiled"
pack "$B" "$XCLIENT libunwind.so.8 liblzma.so.5 libpixman-1.so.0 libXfont2.so.2 libfontenc.so.1 libxkbfile.so.1 libselinux.so.1 libpcre2-8.so.0 libglapi.so.0
 libdrm.so.2 libexpat.so.1 libz.so.1 libzstd.so.1 libxcb-dri3.so.0 $DLOPENED" "" \
    "$B/bin/Xvfb" "$B/bin/xkbcomp" "$B/dri/swrast_dri.so" "$B"/lib/*

for part in A B; do
    dest=$ROOT/.gpu$part
    rm -rf "$dest"
    mkdir -p "$dest"
    src=$WORK/${part,,}
    tar -C "$src" -cf - . | xz -9 -T2 >"$dest/${part,,}.tar.xz"
done
cp "$HERE/gpu_stage_a.sh" "$ROOT/.gpuA/stage_a.sh"
cp "$HERE/gpu_run.sh" "$ROOT/.gpuB/run.sh"

# --- .gl: glvnd's loaders, as /work/.library/device/README.md says ---
if ! ls "$ROOT"/.gl/libglx0_*.deb >/dev/null 2>&1; then
    mkdir -p "$ROOT/.gl" /tmp/amd64/partial
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    apt-get $o update >/dev/null
    (cd "$ROOT/.gl" && apt-get $o download libegl1 libglvnd0 libopengl0 libgl1 libglx0 >/dev/null)
fi
ex=$ROOT/.git/info/exclude
mkdir -p "$(dirname "$ex")"
for d in /.gl/ /.gpuA/ /.gpuB/; do grep -qxF "$d" "$ex" 2>/dev/null || echo "$d" >>"$ex"; done
du -b -s "$ROOT/.gpuA" "$ROOT/.gpuB" "$ROOT/.gl"
