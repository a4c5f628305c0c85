"""Memory (issue 16 point 3) for bench/report.py: why a hub's RSS exceeds the bare Cyclone writer's,
and the board build's RSS row (hubrt_bench_heartbeat --board-build)."""

# Where hubd's resident set goes beyond the bare writer's, by /proc/<pid>/smaps of both side by side
# (x86, 100 Hz, Debian 12's libraries; docs: bench/README.md, "Memory").
WHERE_IT_GOES = (
    "The rest, by /proc/<pid>/smaps of both side by side (2026-11-28, x86): the hubd program's own code, "
    "1.4 MB resident in the board build (the Dock ECU's board program: its whole 1.15 MB of x86 -O2 text, file "
    "pages the kernel maps around every fault, most of them start-up code; the arm64 packages' -Os, "
    "--gc-sections program has 0.47 MB of code) and 2.3 MB in the development build (which also holds the "
    "simulators); spdlog (0.5 MB, 0.2 MB of it its symbol and relocation tables, which the dynamic linker "
    "reads) and yaml-cpp (0.3 MB), which the bare writer does not load; libevdev, libgpiod, libmodbus and "
    "libsocketcan (0.2 MB: "
    "the Linux backend links every device library, though the Dock ECU opens only GPIO lines); libstdc++ "
    "0.13 MB more (code the start-up uses and the bare writer does not); heap and anonymous memory 0.2 MB "
    "more in the board build (the "
    "nodes' message storage, the command, diagnostics and twin-check entities; the development build adds "
    "0.45 MB of fake GPIO level histories and the simulation bridge). Cyclone's own share is the same in both: "
    "libddsc, OpenSSL (libddsc itself needs libssl and libcrypto), iceoryx, its threads' stacks, its two "
    "192 KiB receive buffers (mappings of their own, resident as far as datagrams fill them: the 1 MiB buffer "
    "hubd once read its YAML files into had raised glibc's mmap threshold, putting them in dirtied heap pages, "
    "+0.34 MB). cpp-httplib, whose Debian build initialised OpenSSL's error strings (+1.7 MB of libcrypto "
    "pages) in every hubd, is loaded only by a hub with an HTTP device (the module hubrt-http.so).")


def rss_why(rss, raw_rss, build="development"):
    return (f"{rss:.1f} MB ({build} build), of which a bare Cyclone participant with one writer already takes "
            f"{raw_rss:.1f} MB here (ENVIRONMENT.md: about 7.5 MB per participant). " + WHERE_IT_GOES)


def board_rss_aims(report, heartbeat_board):
    """The board build's RSS against the bare writer of the same run, at 100 Hz; nothing if not measured."""
    if heartbeat_board is None:
        return
    at100 = next((e for e in heartbeat_board["rates"] if e["rate_hz"] == 100), None)
    if at100 is None:
        return
    rss, raw_rss = at100["hub"]["rss_mb"], at100["raw"]["rss_mb"]
    why = rss_why(rss, raw_rss, "board")
    report.aim("<= 9 MB RSS per hub at 100 Hz (board build, rpi4-dock-ecu)",
               f"{rss:.1f} MB (bare Cyclone writer: {raw_rss:.1f} MB)", rss <= 9.0, why,
               alternative=f"bare Cyclone writer {raw_rss:.1f} MB")
    report.aim("RSS <= a bare Cyclone writer of the same State (board build, 100 Hz, same run)",
               f"{rss / raw_rss:.2f}x ({rss:.1f} vs {raw_rss:.1f} MB)", rss <= raw_rss, why,
               alternative=f"bare Cyclone writer {raw_rss:.1f} MB")
    # What the packages install, without simulators: its CPU beside the bare loop of the same run too.
    cpu, raw_cpu, ratio = at100["hub"]["cpu_pct"], at100["raw"]["cpu_pct"], at100.get("ratio_cpu", 0.0)
    spread = (f", rounds {at100['ratio_cpu_min']:.2f}-{at100['ratio_cpu_max']:.2f}"
              if "ratio_cpu_min" in at100 else "")
    report.aim("CPU per hub <= bare loop + dds_write (board build, 100 Hz, same run)",
               f"{ratio:.2f}x median of rounds{spread} ({cpu:.2f} % vs {raw_cpu:.2f} % of a core over the window)",
               0 < ratio <= 1.0,
               f"the board hub takes {ratio:.2f}x the bare loop's CPU. Its four GPIO sensors are missing on this "
               "machine, so its State carries four error messages of ~190 bytes, serialised every cycle (their "
               "text is formatted only when it changes: runtime/error_list.h); per cycle it also arms its "
               "timerfd and waits in epoll_wait where the loop makes one clock_nanosleep.",
               alternative=f"bare loop + dds_write: {raw_cpu:.2f} %")
