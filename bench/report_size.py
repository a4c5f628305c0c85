"""The board hubd's stripped size per Raspberry Pi target (issue 16 point 3), from
bench/board_size.py's results, for bench/report.py."""

AIM_BYTES = 1_000_000  # issue 16 point 3: a board build of hubd <= 1 MB (arm64)
GROUP_ORDER = ("code", "unwind", "constants", "data", "dynamic linking", "other")


def _mb(value):
    return f"{value / 1e6:.2f} MB"


def size_section(report, size):
    """`report`: bench/report.py's Report; `size`: size.json (None when the step did not run)."""
    if size is None:
        report.aim("board hubd (stripped, arm64) <= 1 MB", "not measured", False, "bench/board_size.py did not run.")
        return
    lines = [
        "## Size of the board hubd",
        "",
        "`bench/board_size.py`: `hubd_board` (the board build the packages install as /usr/bin/hubd: Linux "
        "backend only, no simulators) cross-built with the presets' flags, stripped as the packages ship it. "
        "Sections grouped: code (.text, .plt), unwind tables (.eh_frame, .gcc_except_table, ARM .exidx; kept: "
        "C++ exceptions and the crash handler need them), constants (.rodata), data (.data, .data.rel.ro, GOT), "
        "dynamic linking (symbols, relocations). How each flag changed it: docs/board-size.md.",
        "",
        "| target | stripped | " + " | ".join(GROUP_ORDER) + " | flags |",
        "|---|---|" + "---|" * len(GROUP_ORDER) + "---|",
    ]
    arm64 = None
    for target in size["targets"]:
        arch = target["arch"]
        if not target.get("prepared"):
            lines.append(f"| {arch} | not prepared (no sysroot: `toolchain/prepare-target {arch}`) |"
                         + " |" * len(GROUP_ORDER) + " |")
            continue
        if "stripped_bytes" not in target:
            lines.append(f"| {arch} | build failed: {target.get('error', '?')} |" + " |" * len(GROUP_ORDER) + " |")
            continue
        groups = target["groups"]
        flags = target["flags"] + (" + LTO (board hubd only)" if target.get("board_lto") else "")
        lines.append(f"| {arch} | **{_mb(target['stripped_bytes'])}** ({target['stripped_bytes']} bytes) | "
                     + " | ".join(f"{groups.get(g, 0) / 1000:.0f} kB" for g in GROUP_ORDER) + f" | `{flags}` |")
        if arch == "arm64":
            arm64 = target
    report.sections.append("\n".join(lines) + "\n")
    if arm64 is None:
        report.aim("board hubd (stripped, arm64) <= 1 MB", "not measured", False,
                   "no arm64 sysroot on this machine (toolchain/prepare-target arm64), or its build failed.")
        return
    bytes_ = arm64["stripped_bytes"]
    others = ", ".join(f"{t['arch']} {_mb(t['stripped_bytes'])}" for t in size["targets"]
                       if t["arch"] != "arm64" and "stripped_bytes" in t)
    report.aim("board hubd (stripped, arm64) <= 1 MB", _mb(bytes_) + (f" ({others})" if others else ""),
               bytes_ <= AIM_BYTES,
               f"{_mb(bytes_)} with -Os and sections per function collected at link" +
               (", and LTO for the board hubd" if arm64.get("board_lto") else
                "; LTO for the board hubd alone (1.12 MB) is off: where binutils loads GCC's plugin by itself, "
                "the test programs linked without LTO from fat objects failed with multiple definitions") +
               " (docs/board-size.md). What remains is spread thin: CLI11's parser and help formatter (~90 kB), "
               "six hub types' node and wiring templates, the board file parser, fmt's formatting code "
               "(instantiated in hubd although Debian's libfmt and libspdlog carry copies), the unwind tables "
               "and the PIE relocations (binutils 2.40 cannot pack them on arm64: -z pack-relative-relocs needs "
               "2.41).")
