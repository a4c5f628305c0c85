#!/usr/bin/env python3
"""Resident memory of the board hubd on each Raspberry Pi target, beside the bare Cyclone writer of
the same State, for bench/run and docs/benchmarks.md (issue 16, point 3: "<= 9 MB on x86 and
arm64, qemu figure with the reason").

This machine is x86, so the target programs run under qemu-user. For a target whose sysroot
toolchain/prepare-target made, builds the Dock ECU's board program and the heartbeat bench in
build/cross-<arch> and runs that bench under qemu exactly as on x86 (hubrt_bench_heartbeat
--board-build: hubd and the bare writer side by side at 100 Hz, each with a subscriber; here the
subscriber is the emulated bench itself). What it records per process:
  - the process's RSS, which is qemu's: qemu itself (its executable, translation buffer and heap,
    about 21 MB) plus the guest program;
  - the guest's own share, the mappings qemu placed the guest in (bench/support/guest_memory.h):
    what the program would hold on the board, to within how qemu maps (the same files, the same
    heap; file pages the guest never ran but qemu's loader read may differ).
The bench's timing figures under qemu mean nothing and are not reported.
    bench/board_rss.py --out FILE [--arch arm64 armhf] [--seconds S] [--jobs N]
"""
import argparse
import json
import os
import subprocess
import tempfile

import board_size

QEMU = {"arm64": "qemu-aarch64-static", "armhf": "qemu-arm-static"}
TARGETS = ["hubd_board_dock_ecu", "hubrt_bench_heartbeat", "hubrt_bench_raw_peer"]


def measure(arch, seconds, jobs):
    if not board_size.prepared(arch):
        return {"arch": arch, "prepared": False}
    build = board_size.cross_build(arch, TARGETS, jobs)
    emulator = [QEMU[arch], "-L", board_size.sysroot(arch)]
    env = dict(os.environ, HUBRT_TARGET_EMULATOR=" ".join(emulator))
    with tempfile.TemporaryDirectory() as scratch:
        out = os.path.join(scratch, "heartbeat.json")
        bench = os.path.join(build, "bench", "hubrt_bench_heartbeat")
        # One short turn: the CPU figures under qemu are not reported, the memory is read at the end
        # of the side-by-side window.
        subprocess.run(emulator + [bench, "--board-build", "--rates", "100", "--seconds", str(seconds),
                                   "--cpu-turns", "1", "--cpu-turn-seconds", "0.5", "--out", out,
                                   "--periods", os.path.join(scratch, "periods.csv")],
                       check=True, env=env, stdout=subprocess.DEVNULL, timeout=600)
        with open(out) as f:
            entry = json.load(f)["rates"][0]
    processes = {}
    for source in ("hub", "raw"):
        s = entry[source]
        if s.get("guest_rss_mb", -1) < 0:
            raise RuntimeError(f"{source}: no guest memory figure (was it run under {QEMU[arch]}?)")
        processes[source] = {"process_rss_mb": s["rss_mb"], "guest_rss_mb": s["guest_rss_mb"],
                             "guest_anon_mb": s.get("guest_anon_mb", -1)}
    return {"arch": arch, "prepared": True, "emulator": QEMU[arch], "seconds": seconds, **processes}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True)
    parser.add_argument("--arch", nargs="+", default=["arm64", "armhf"], choices=sorted(QEMU))
    parser.add_argument("--seconds", type=float, default=10.0, help="side-by-side window under qemu")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    results = board_size.measure_targets(
        "board_rss", args.arch, lambda arch: measure(arch, args.seconds, args.jobs),
        (subprocess.CalledProcessError, subprocess.TimeoutExpired, OSError, RuntimeError, KeyError), args.out)
    for r in results:
        if "hub" not in r:
            print(f"  {r['arch']}: {r.get('error', 'not prepared')}")
            continue
        print(f"  {r['arch']}: board hubd {r['hub']['guest_rss_mb']:.2f} MB, bare writer "
              f"{r['raw']['guest_rss_mb']:.2f} MB (guest memory; the qemu processes "
              f"{r['hub']['process_rss_mb']:.1f} and {r['raw']['process_rss_mb']:.1f} MB)")


if __name__ == "__main__":
    main()
