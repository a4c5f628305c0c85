#!/usr/bin/env python3
"""Stripped size of the board programs of hubd for each Raspberry Pi target, for bench/run and
docs/benchmarks.md: each hub type's (target hubd_board_<hub type>, board/<hub type>/hubd: what a
board package installs as /usr/bin/hubd) and, for comparison, hubd_board with every hub type.

For a target whose sysroot toolchain/prepare-target made, builds them in build/cross-<arch> (the
cross presets' flags; configures the preset first when the folder has none), strips copies with the
cross binutils and records their sizes and the sizes of their sections. A target without a sysroot
is recorded as not prepared.
    bench/board_size.py --out FILE [--arch arm64 armhf] [--jobs N]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TRIPLETS = {"arm64": "aarch64-linux-gnu", "armhf": "arm-linux-gnueabihf"}
# Sections reported one by one; the rest is summed as "other".
GROUPS = {
    "code": (".text", ".plt", ".init", ".fini"),
    "unwind": (".eh_frame", ".eh_frame_hdr", ".gcc_except_table", ".ARM.exidx", ".ARM.extab"),
    "constants": (".rodata",),
    "data": (".data", ".data.rel.ro", ".init_array", ".fini_array", ".got", ".got.plt", ".dynamic"),
    "dynamic linking": (".dynsym", ".dynstr", ".gnu.hash", ".gnu.version", ".gnu.version_r", ".rela.dyn",
                        ".rela.plt", ".rel.dyn", ".rel.plt"),
}


def sysroot(arch):
    base = os.environ.get("HUBRT_SYSROOTS", os.path.join(ROOT, "toolchain", ".sysroots"))
    return os.path.join(base, arch)


def cache_value(build, name):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            if key.split(":")[0] == name:
                return value
    return ""


def sections(triplet, path):
    """{section: bytes} of the sections that take room in the file (size -A; .bss takes none)."""
    out = subprocess.run([f"{triplet}-size", "-A", path], check=True, capture_output=True, text=True).stdout
    found = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[0].startswith(".") and parts[0] not in (".bss", ".tbss", ".comment"):
            found[parts[0]] = int(parts[1])
    return found


def hub_types():
    """The hub types, as firmware/hubd names their board programs: hubs/<name>/ registering one."""
    hubs = os.path.join(ROOT, "hubs")
    found = []
    for name in sorted(os.listdir(hubs)):
        cmake = os.path.join(hubs, name, "CMakeLists.txt")
        if os.path.isfile(cmake) and "hubrt_register_hub_type(" in open(cmake).read():
            found.append(name)
    return found


def stripped_size(triplet, program):
    with tempfile.TemporaryDirectory() as scratch:
        stripped = os.path.join(scratch, "hubd")
        subprocess.run([f"{triplet}-strip", "-o", stripped, program], check=True)
        size = os.path.getsize(stripped)
        found = sections(triplet, stripped)
    groups = {name: sum(found.get(s, 0) for s in members) for name, members in GROUPS.items()}
    groups["other"] = sum(found.values()) - sum(groups.values())
    return size, groups


def prepared(arch):
    return os.path.exists(os.path.join(sysroot(arch), ".hubrt-sysroot"))


def cross_build(arch, targets, jobs):
    """build/cross-<arch> with `targets` built (configured with the preset first when it has no cache)."""
    build = os.path.join(ROOT, "build", f"cross-{arch}")
    nice = ["nice", "-n", "19"]
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        subprocess.run(nice + ["cmake", "--preset", f"cross-{arch}"], cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(nice + ["cmake", "--build", build, "-j", str(jobs), "--target"] + targets, check=True,
                   stdout=subprocess.DEVNULL)
    return build


def measure(arch, jobs):
    triplet = TRIPLETS[arch]
    if not prepared(arch):
        return {"arch": arch, "prepared": False}
    types = hub_types()
    build = cross_build(arch, ["hubd_board"] + [f"hubd_board_{t}" for t in types], jobs)
    board_dir = os.path.join(build, "firmware", "hubd", "board")
    programs = []
    for name, program in [("every hub type", os.path.join(board_dir, "hubd"))] + \
            [(t, os.path.join(board_dir, t, "hubd")) for t in types]:
        size, groups = stripped_size(triplet, program)
        programs.append({"program": name, "stripped_bytes": size, "groups": groups})
    return {
        "arch": arch,
        "prepared": True,
        "programs": programs,
        "flags": " ".join(filter(None, (cache_value(build, "CMAKE_CXX_FLAGS"),
                                        cache_value(build, "CMAKE_CXX_FLAGS_RELWITHDEBINFO")))),
        "board_lto": cache_value(build, "HUBRT_BOARD_LTO").upper() in ("ON", "TRUE", "1"),
    }


def measure_targets(tool, archs, measure_one, errors, out):
    """measure_one(arch) for each target, a failure (one of `errors`) recorded as its error; all written
    to `out` as {"targets": [...]}, and returned."""
    results = []
    for arch in archs:
        try:
            results.append(measure_one(arch))
        except errors as error:
            print(f"{tool}: {arch}: {error}", file=sys.stderr)
            results.append({"arch": arch, "prepared": True, "error": str(error)})
    with open(out, "w") as f:
        json.dump({"targets": results}, f, indent=2)
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True)
    parser.add_argument("--arch", nargs="+", default=["arm64", "armhf"], choices=sorted(TRIPLETS))
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    results = measure_targets("board_size", args.arch, lambda arch: measure(arch, args.jobs),
                              (subprocess.CalledProcessError, OSError), args.out)
    for r in results:
        if "programs" not in r:
            print(f"  {r['arch']}: {r.get('error', 'not prepared')}")
            continue
        for p in r["programs"]:
            print(f"  {r['arch']} {p['program']}: {p['stripped_bytes']} bytes")


if __name__ == "__main__":
    main()
