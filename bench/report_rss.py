"""Memory (issue 16 point 3) for bench/report.py: why a hub's RSS exceeds the bare Cyclone writer's,
and the board build's RSS row (hubrt_bench_heartbeat --board-build)."""

# Where hubd's resident set goes beyond the bare writer's, by /proc/<pid>/smaps of both side by side
# (x86, 100 Hz, Debian 12's libraries; docs: bench/README.md, the row of hubrt_bench_heartbeat --board-hubd).
WHERE_IT_GOES = (
    "Where the difference goes, by /proc/<pid>/smaps of both side by side (2026-11-28, x86, the Dock ECU's board "
    "program built with the board packages' flags, as bench/run measures it: build/host-board): hubd's own code, "
    "0.66 MB resident against the bare writer program's 0.25 MB (file pages of its 0.79 MB of -Os text, which "
    "the kernel maps around every fault, most of them start-up code; the development build's -O2 hubd, which "
    "also holds the simulators, 2.3 MB); yaml-cpp (0.32 MB), which the bare writer does not load; libgpiod (0.04 MB: a "
    "board's program links the device libraries of its hub type's kinds only, hubs/HubTypes.cmake DEVICES; "
    "libevdev, libmodbus and libsocketcan had cost the Dock ECU 0.16 MB more); heap 0.26 MB more (the nodes' "
    "message storage, the command, diagnostics and "
    "twin-check entities; the development build adds 0.45 MB of fake GPIO level histories and the simulation "
    "bridge); libstdc++ 0.12 MB more (code the start-up uses and the bare writer does not). spdlog is compiled "
    "into hubrt's static builds (base/spdlog): Debian's libspdlog.so had cost 0.5 MB, 0.2 MB of it its symbol "
    "and relocation tables, against ~60 kB of code linked in. Cyclone's own share is the same in both: "
    "libddsc, OpenSSL (libddsc itself needs libssl and libcrypto), iceoryx, its threads' stacks, its two "
    "192 KiB receive buffers (mappings of their own, resident as far as datagrams fill them: the 1 MiB buffer "
    "hubd once read its YAML files into had raised glibc's mmap threshold, putting them in dirtied heap pages, "
    "+0.34 MB). cpp-httplib, whose Debian build initialised OpenSSL's error strings (+1.7 MB of libcrypto "
    "pages) in every hubd, is loaded only by a hub with an HTTP device (the module hubrt-http.so).")


def anon_of(sample):
    """' (1.4 anonymous)' for a table cell, or '' for results without the figure."""
    return f" ({sample['anon_mb']:.1f} anonymous)" if sample.get("anon_mb", -1) >= 0 else ""


def split(hub, raw, rss_key="rss_mb", anon_key="anon_mb"):
    """The hub's resident memory beyond the bare writer's, split into file pages and anonymous memory
    (bench/support/guest_memory.h); None when a figure is missing (results of an older bench)."""
    if hub.get(anon_key, -1) < 0 or raw.get(anon_key, -1) < 0:
        return None
    anon = hub[anon_key] - raw[anon_key]
    return {"file": (hub[rss_key] - hub[anon_key]) - (raw[rss_key] - raw[anon_key]), "anon": anon}


def split_text(parts):
    """'; beyond the writer: +0.86 MB file pages, +0.21 MB anonymous', or '' without the figures."""
    if parts is None:
        return ""
    return f"; beyond the writer: {parts['file']:+.2f} MB file pages, {parts['anon']:+.2f} MB anonymous"


def split_why(parts):
    if parts is None:
        return ""
    return (f"Measured in the same run: {parts['file']:+.2f} MB of the difference are pages of files (code and "
            f"read-only data of the program and the libraries it loads, which the kernel drops under memory "
            f"pressure and reads again) and {parts['anon']:+.2f} MB anonymous memory (heap, stacks, written data: "
            "RssAnon, or the Anonymous lines of the guest's mappings under qemu-user), which only swap could take "
            "back. ")


def rss_why(rss, raw_rss, build="development", parts=None):
    return (f"{rss:.1f} MB ({build} build), of which a bare Cyclone participant with one writer already takes "
            f"{raw_rss:.1f} MB here (ENVIRONMENT.md: about 7.5 MB per participant). " + split_why(parts) +
            WHERE_IT_GOES)


def board_rss_aims(report, heartbeat_board):
    """The board build's RSS against the bare writer of the same run, at 100 Hz; nothing if not measured."""
    if heartbeat_board is None:
        return
    at100 = next((e for e in heartbeat_board["rates"] if e["rate_hz"] == 100), None)
    if at100 is None:
        return
    rss, raw_rss = at100["hub"]["rss_mb"], at100["raw"]["rss_mb"]
    # bench/run measures build/host-board's program (the packages' flags); older results, or a run
    # where that build failed, measured the bench build's own.
    program = at100.get("hubd_program", "")
    build = ("board build: the packages' -Os, --gc-sections flags, build/host-board" if "/host-board/" in program
             else "board build, with the bench build's flags")
    parts = split(at100["hub"], at100["raw"])
    why = rss_why(rss, raw_rss, build, parts)
    report.aim("<= 9 MB RSS per hub at 100 Hz (board build, rpi4-dock-ecu)",
               f"{rss:.1f} MB (bare Cyclone writer: {raw_rss:.1f} MB)", rss <= 9.0, why,
               alternative=f"bare Cyclone writer {raw_rss:.1f} MB")
    report.aim("RSS <= a bare Cyclone writer of the same State (board build, 100 Hz, same run)",
               f"{rss / raw_rss:.2f}x ({rss:.1f} vs {raw_rss:.1f} MB{split_text(parts)})", rss <= raw_rss, why,
               alternative=f"bare Cyclone writer {raw_rss:.1f} MB")
    # What the packages install, without simulators: its CPU beside the bare loop of the same run too.
    cpu, raw_cpu, ratio = at100["hub"]["cpu_pct"], at100["raw"]["cpu_pct"], at100.get("ratio_cpu", 0.0)
    spread = (f", rounds {at100['ratio_cpu_min']:.2f}-{at100['ratio_cpu_max']:.2f}"
              if "ratio_cpu_min" in at100 else "")
    turns = at100.get("cpu_turns", {})
    side = (f"; side by side {at100['ratio_cpu_side_by_side']:.2f}x ({cpu:.2f} % vs {raw_cpu:.2f} % of a core)"
            if "ratio_cpu_side_by_side" in at100 else "")
    report.aim("CPU per hub <= bare loop + dds_write (board build, 100 Hz, same run)",
               f"{ratio:.2f}x in turns, median of {len(turns.get('ratios', []))} rounds{spread}{side}",
               0 < ratio <= 1.0,
               f"the board hub takes {ratio:.2f}x the bare loop's CPU. Its four GPIO sensors are missing on this "
               "machine, so its State carries four error messages of ~190 bytes, serialised every cycle (their "
               "text is formatted only when it changes: runtime/error_list.h); per cycle it also arms its "
               "timerfd and waits in epoll_wait where the loop makes one clock_nanosleep.",
               alternative=f"bare loop + dds_write: {raw_cpu:.2f} %")


def target_rss_aims(report, rss_boards):
    """The board hubd's memory on the Raspberry Pi targets, under qemu-user (bench/board_rss.py):
    the guest program's own share beside the bare writer's, both run by the same emulated bench."""
    aim = "<= 9 MB RSS per hub at 100 Hz ({arch} board build, guest memory under qemu-user)"
    if rss_boards is None:
        report.aim(aim.format(arch="arm64"), "not measured", False, "bench/board_rss.py did not run.")
        return
    lines = [
        "## Memory of the board hubd on the Raspberry Pi targets",
        "",
        "`bench/board_rss.py`: the cross-built heartbeat bench run under qemu-user with `--board-build`: the "
        "Dock ECU's board program and the bare Cyclone writer of the same State side by side at 100 Hz, each "
        "with a subscriber, read at the end of a 10 s window. Under qemu-user each process is qemu: its RSS "
        "holds qemu itself (executable, translation buffer, heap) and the guest. The guest's own share is "
        "every mapping below qemu's executable and heap, where qemu places the guest "
        "(bench/support/guest_memory.h): the program's files from the sysroot, its heap, its threads' "
        "stacks. That is the figure judged; the process's is shown for the reason it is not.",
        "",
        "| target | board hubd (guest) | bare writer (guest) | ratio | of it anonymous (hub / bare) | "
        "qemu processes' RSS (hub / bare) |",
        "|---|---|---|---|---|---|",
    ]
    for target in rss_boards["targets"]:
        arch = target["arch"]
        if not target.get("prepared"):
            lines.append(f"| {arch} | not prepared (no sysroot: `toolchain/prepare-target {arch}`) | | | | |")
            continue
        if "hub" not in target:
            lines.append(f"| {arch} | failed: {target.get('error', '?')} | | | | |")
            report.aim(aim.format(arch=arch), "failed", False, f"bench/board_rss.py: {target.get('error', '?')}")
            continue
        hub, raw = target["hub"]["guest_rss_mb"], target["raw"]["guest_rss_mb"]
        parts = split(target["hub"], target["raw"], "guest_rss_mb", "guest_anon_mb")
        anon = (f"{target['hub']['guest_anon_mb']:.2f} / {target['raw']['guest_anon_mb']:.2f} MB" if parts else "-")
        lines.append(f"| {arch} | **{hub:.2f} MB** | {raw:.2f} MB | {hub / raw:.2f}x | {anon} | "
                     f"{target['hub']['process_rss_mb']:.1f} / {target['raw']['process_rss_mb']:.1f} MB |")
        why = (f"on {arch} the board hubd holds {hub:.2f} MB against the bare writer's {raw:.2f} MB (guest memory "
               "under qemu-user). " + split_why(parts) + "Beyond the writer: yaml-cpp, hubd's own code (spdlog "
               "compiled in), libgpiod and its nodes' storage (the x86 breakdown above).")
        report.aim(aim.format(arch=arch), f"{hub:.2f} MB (bare Cyclone writer {raw:.2f} MB)", hub <= 9.0, why,
                   alternative=f"bare Cyclone writer {raw:.2f} MB")
        report.aim(f"RSS <= a bare Cyclone writer of the same State ({arch} board build, guest memory, same run)",
                   f"{hub / raw:.2f}x ({hub:.2f} vs {raw:.2f} MB{split_text(parts)})", hub <= raw, why,
                   alternative=f"bare Cyclone writer {raw:.2f} MB")
    report.sections.append("\n".join(lines) + "\n")
