#!/usr/bin/env python3
"""A stand-in for a shared library that a bundled program links but never calls.

    python3 bench/gpu_stub_lib.py [--ret REGEX] [--str REGEX] REAL_LIB OUT_DIR [CONSUMER...]

Writes OUT_DIR/<soname>: a library with the real one's soname, symbol versions and
exported symbols (those the CONSUMERs import, when some are named), whose functions trap (ud2: SIGILL if one is ever called) and whose
objects are zeroed storage of the real sizes. The loader is satisfied (DT_NEEDED,
version needs, BIND_NOW relocations) without the real library's own dependencies.
bench/gpu_bundle.sh uses it to fit the viewer bench and Xvfb into the device machine's
64 MiB transfer: OpenImageIO links ffmpeg, OpenVDB, DCMTK, OpenCV... that reading an EXR
never calls, and Mesa's swrast_dri.so links LLVM, which Xvfb's GLX with softpipe never
calls. A run that does call one dies with SIGILL, so a stand-in cannot change a figure.
--ret: functions whose (mangled) names match return (0) instead: static registrations
that a consumer's initialisers call at load (DCMTK's DiRegister), whose skipping the runs
cannot see. --str: functions whose names match return a pointer to the string "stand-in"
(the libraries' version functions, which OpenImageIO calls when it lists its plugins).
"""
import os
import re
import subprocess
import sys
import tempfile


def soname(lib):
    out = subprocess.run(["readelf", "-dW", lib], capture_output=True, text=True, check=True)
    m = re.search(r"\(SONAME\)\s+Library soname: \[(.+)\]", out.stdout)
    return m.group(1) if m else os.path.basename(lib)


def symbols(lib):
    """(name, version or None, default version?, type, size) of each defined dynamic symbol."""
    out = subprocess.run(["readelf", "-W", "--dyn-syms", lib], capture_output=True, text=True,
                         check=True)
    syms = []
    for line in out.stdout.splitlines():
        f = line.split()
        if len(f) < 8 or not f[0][:-1].isdigit() or f[6] in ("UND", "ABS"):
            continue
        _, _, size, typ, bind, _, _, name = f[:8]
        if bind == "LOCAL" or typ in ("SECTION", "FILE"):
            continue
        version, default = None, True
        if "@@" in name:
            name, version = name.split("@@", 1)
        elif "@" in name:
            name, version = name.split("@", 1)
            default = False
        if name == version:  # the version's own definition symbol
            continue
        size = int(size, 16) if size.startswith("0x") else int(size)
        syms.append((name, version, default, typ, size))
    return syms


def imports(libs):
    """Names of the symbols that `libs` import (undefined in their dynamic tables)."""
    names = set()
    for lib in libs:
        out = subprocess.run(["readelf", "-W", "--dyn-syms", lib], capture_output=True,
                             text=True, check=True)
        for line in out.stdout.splitlines():
            f = line.split()
            if len(f) >= 8 and f[0][:-1].isdigit() and f[6] == "UND":
                names.add(f[7].split("@", 1)[0])
    return names


def version_defs(lib):
    """Version names this library defines (its verdef), base name left out."""
    out = subprocess.run(["readelf", "-W", "-V", lib], capture_output=True, text=True,
                         check=True)
    names, in_def = [], False
    for line in out.stdout.splitlines():
        if line.startswith("Version definition section"):
            in_def = True
            continue
        if line.startswith("Version needs section") or line.startswith("Version symbols"):
            in_def = False
        if in_def:
            m = re.search(r"Flags: (\S+)\s+Version: \d+\s+Cnt: \d+\s+Name: (\S+)", line)
            if m and m.group(1) != "BASE":
                names.append(m.group(2))
    return names


def write_stub(lib, out_dir, consumers=(), ret=None, text=None):
    name = soname(lib)
    syms = symbols(lib)
    if consumers:
        wanted = imports(consumers)
        syms = [s for s in syms if s[0] in wanted]
    versions = version_defs(lib)
    asm, script = [], {v: [] for v in versions}
    unversioned = []
    for i, (sym, ver, default, typ, size) in enumerate(syms):
        label = sym if default else f"__stub_hidden_{i}"
        if typ == "TLS":
            asm += [".section .tbss,\"awT\",@nobits", f".globl {label}",
                    f".type {label}, @object", f".size {label}, {max(size, 1)}", f"{label}:",
                    f".zero {max(size, 1)}"]
        elif typ == "OBJECT" or (typ == "NOTYPE" and size > 0):
            asm += [".bss", ".balign 16", f".globl {label}", f".type {label}, @object",
                    f".size {label}, {max(size, 1)}", f"{label}:", f".zero {max(size, 1)}"]
        else:  # FUNC, IFUNC, NOTYPE: a trap, or a return where --ret says
            body = ["ud2"]
            if ret and re.search(ret, sym):
                body = ["xorl %eax, %eax", "ret"]
            elif text and re.search(text, sym):
                body = ["leaq .Lstub_text(%rip), %rax", "ret"]
            asm += [".text", f".globl {label}", f".type {label}, @function", f"{label}:"] + body
        if not default:
            asm.append(f".symver {label}, {sym}@{ver}")
            script.setdefault(ver, [])
        elif ver:
            script.setdefault(ver, []).append(sym)
        else:
            unversioned.append(sym)
    asm += [".section .rodata", ".Lstub_text:", ".string \"stand-in\""]
    with tempfile.TemporaryDirectory() as tmp:
        s = os.path.join(tmp, "stub.s")
        with open(s, "w") as f:
            f.write("\n".join(asm) + "\n")
        cmd = ["gcc", "-shared", "-nostdlib", "-o", os.path.join(out_dir, name), s,
               f"-Wl,-soname,{name}", "-Wl,-z,noexecstack"]
        if script:
            vs = os.path.join(tmp, "vs")
            with open(vs, "w") as f:
                first = True
                for ver, names in script.items():
                    f.write(f"{ver} {{\n")
                    if names or (first and unversioned):
                        f.write("  global:\n")
                        for n in names:
                            f.write(f"    \"{n}\";\n")
                        if first:
                            for n in unversioned:
                                f.write(f"    \"{n}\";\n")
                    if first:
                        f.write("  local: *;\n")
                    f.write("};\n")
                    first = False
            cmd.append(f"-Wl,--version-script={vs}")
        subprocess.run(cmd, check=True)
    return name, len(syms)


if __name__ == "__main__":
    args, opts = sys.argv[1:], {"--ret": None, "--str": None}
    while args[:1] and args[0] in opts and len(args) > 1:
        opts[args[0]], args = args[1], args[2:]
    if len(args) < 2:
        sys.exit("usage: gpu_stub_lib.py [--ret REGEX] [--str REGEX] REAL_LIB OUT_DIR [CONSUMER...]")
    n, count = write_stub(args[0], args[1], args[2:], opts["--ret"], opts["--str"])
    print(f"stub {n}: {count} symbols")
