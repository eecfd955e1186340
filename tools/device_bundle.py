#!/usr/bin/env python3
"""Packs built programs with the shared libraries they load, for a machine that has a GPU
driver but none of this project's packages (and no network to install them).

    tools/device_bundle.py OUT_DIR build/walkthrough build/render ...

OUT_DIR/bin holds the stripped programs, OUT_DIR/lib every library they need except glibc's.
OpenImageIO links the readers of formats this project never opens (video, DICOM, OpenVDB,
camera raw, HEIF, OpenCV); their libraries and everything behind them are hundreds of
megabytes. Each is replaced by a small library of the same name that defines the symbols the
bundle imports from it, with their versions, as code that traps if it is ever run: the dynamic
loader is satisfied, and a call into one of them would stop the program rather than go on
wrongly. Constructors and destructors return at once instead (OpenImageIO constructs a DCMTK
registration object when it loads) and version queries return the text "not bundled"
(OpenImageIO lists its format libraries' versions when it first looks for a format). Run the bundle with LD_LIBRARY_PATH=OUT_DIR/lib.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

UNUSED_FORMATS = """libopencv_core.so.406 libopencv_imgproc.so.406 libopencv_videoio.so.406
libdcmimage.so.17 libdcmimgle.so.17 libdcmdata.so.17 liboflog.so.17 libofstd.so.17
libavcodec.so.59 libavformat.so.59 libavutil.so.57 libswscale.so.6 libheif.so.1
libopenvdb.so.10.0 libraw_r.so.20""".split()
GLIBC = "libc.so.6 libm.so.6 libpthread.so.0 ld-linux-x86-64.so.2 libdl.so.2 librt.so.1".split()
# NVIDIA's Vulkan driver (libGLX_nvidia) loads the GL vendor-neutral dispatch libraries; a
# machine with the driver but no desktop packages lacks them.
DRIVER_NEEDS = "libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0 libGL.so.1".split()
LIB_DIRS = ["/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu"]


def run(*args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def needed(path):
    return re.findall(r"\(NEEDED\).*\[(.*)\]", run("readelf", "-d", path))


def locate(name):
    for d in LIB_DIRS:
        if os.path.exists(os.path.join(d, name)):
            return os.path.realpath(os.path.join(d, name))
    sys.exit(f"error: library {name} not found in {LIB_DIRS}")


def dynamic_symbols(path):
    """(name, version, defined, type, size) of each dynamic symbol."""
    rows = []
    for line in run("readelf", "--dyn-syms", "-W", path).splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].rstrip(":").isdigit():
            continue
        name, _, version = f[7].partition("@")
        version = version.lstrip("@").split(" ")[0]
        rows.append((name, version, f[6] != "UND", f[3], int(f[2], 0)))
    return rows


def write_stub(real, imported, out_path, soname):
    """A library named soname defining the symbols in imported that real defines."""
    defined = [s for s in dynamic_symbols(real) if s[2] and s[0] in imported]
    asm, versions = [".section .rodata", 'stub_version: .asciz "not bundled"'], {}
    for name, version, _, kind, size in defined:
        versions.setdefault(version, []).append(name)
        if kind == "OBJECT" or kind == "TLS":
            asm += [".data", f'.globl "{name}"', f'.type "{name}",@object',
                    f'.size "{name}",{max(size, 1)}', f'"{name}":', f".zero {max(size, 1)}"]
        else:
            if re.search(r"[CD][0-2]E", name):
                body = "ret"
            elif "version" in name.lower():
                body = "leaq stub_version(%rip), %rax\nret"
            else:
                body = "ud2"
            asm += [".text", f'.globl "{name}"', f'.type "{name}",@function', f'"{name}":', body]
    with tempfile.TemporaryDirectory() as tmp:
        src, script = os.path.join(tmp, "stub.s"), os.path.join(tmp, "stub.map")
        with open(src, "w") as f:
            f.write("\n".join(asm) + "\n")
        with open(script, "w") as f:
            for version, names in versions.items():
                body = "".join(f'"{n}";' for n in names)
                f.write(f"{version} {{ global: {body} }};\n" if version else
                        f"{{ global: {body} }};\n")
        run("gcc", "-shared", "-nostdlib", "-o", out_path, f"-Wl,-soname,{soname}",
            f"-Wl,--version-script={script}", src)
    return len(defined)


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: device_bundle.py OUT_DIR PROGRAM...")
    out, programs = sys.argv[1], sys.argv[2:]
    os.makedirs(os.path.join(out, "bin"), exist_ok=True)
    os.makedirs(os.path.join(out, "lib"), exist_ok=True)
    found = {name: locate(name) for name in DRIVER_NEEDS}
    todo, stubs = [os.path.abspath(p) for p in programs] + list(found.values()), set()
    while todo:
        for name in needed(todo.pop()):
            if name in GLIBC or name in found or name in stubs:
                continue
            if name in UNUSED_FORMATS:
                stubs.add(name)
                continue
            found[name] = locate(name)
            todo.append(found[name])
    imported = set()
    for path in [os.path.abspath(p) for p in programs] + list(found.values()):
        imported |= {s[0] for s in dynamic_symbols(path) if not s[2]}
    for name, path in found.items():
        shutil.copy(path, os.path.join(out, "lib", name))
    for name in sorted(stubs):
        count = write_stub(locate(name), imported, os.path.join(out, "lib", name), name)
        print(f"{name}: {count} symbols, each a trap")
    for program in programs:
        run("strip", "-o", os.path.join(out, "bin", os.path.basename(program)), program)
    print(f"{len(found)} libraries copied, {len(stubs)} replaced")


if __name__ == "__main__":
    main()
