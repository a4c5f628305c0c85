"""The board hubd's stripped size per Raspberry Pi target (issue 16 point 3), from
bench/board_size.py's results, for bench/report.py."""

AIM_BYTES = 1_000_000  # issue 16 point 3: a board build of hubd <= 1 MB (arm64)
GROUP_ORDER = ("code", "unwind", "constants", "data", "dynamic linking", "other")


def _mb(value):
    return f"{value / 1e6:.2f} MB"


def size_section(report, size):
    """`report`: bench/report.py's Report; `size`: size.json (None when the step did not run)."""
    aim = "board hubd (stripped, arm64) <= 1 MB"
    if size is None:
        report.aim(aim, "not measured", False, "bench/board_size.py did not run.")
        return
    lines = [
        "## Size of the board hubd",
        "",
        "`bench/board_size.py`: each hub type's board program (`hubd_board_<hub type>`, board/<hub type>/hubd: "
        "what a board package installs as /usr/bin/hubd, the board's hub type alone, Linux backend only, no "
        "simulators) and, for comparison, `hubd_board` with every hub type, cross-built with the presets' flags "
        "and stripped as the packages ship them. Sections grouped: code (.text, .plt), unwind tables (.eh_frame, "
        ".gcc_except_table, ARM .exidx; kept: C++ exceptions and the crash handler need them), constants "
        "(.rodata), data (.data, .data.rel.ro, GOT), dynamic linking (symbols, relocations). How each flag and "
        "the split by hub type changed it: docs/board-size.md.",
        "",
        "| target | program | stripped | " + " | ".join(GROUP_ORDER) + " |",
        "|---|---|---|" + "---|" * len(GROUP_ORDER),
    ]
    flags = {}
    arm64 = None
    for target in size["targets"]:
        arch = target["arch"]
        if not target.get("prepared"):
            lines.append(f"| {arch} | not prepared (no sysroot: `toolchain/prepare-target {arch}`) | |"
                         + " |" * len(GROUP_ORDER))
            continue
        if "programs" not in target:
            lines.append(f"| {arch} | build failed: {target.get('error', '?')} | |" + " |" * len(GROUP_ORDER))
            continue
        flags[arch] = target["flags"] + (" + LTO (board programs only)" if target.get("board_lto") else "")
        for program in target["programs"]:
            groups = program["groups"]
            lines.append(f"| {arch} | {program['program']} | **{_mb(program['stripped_bytes'])}** "
                         f"({program['stripped_bytes']} bytes) | "
                         + " | ".join(f"{groups.get(g, 0) / 1000:.0f} kB" for g in GROUP_ORDER) + " |")
        if arch == "arm64":
            arm64 = target
    lines += ["", "Flags: " + "; ".join(f"{arch} `{f}`" for arch, f in flags.items())]
    report.sections.append("\n".join(lines) + "\n")
    if arm64 is None:
        report.aim(aim, "not measured", False,
                   "no arm64 sysroot on this machine (toolchain/prepare-target arm64), or its build failed.")
        return
    shipped = [p for p in arm64["programs"] if p["program"] != "every hub type"]
    largest = max(shipped, key=lambda p: p["stripped_bytes"])
    smallest = min(shipped, key=lambda p: p["stripped_bytes"])
    every = next((p for p in arm64["programs"] if p["program"] == "every hub type"), None)
    others = []
    for target in size["targets"]:
        if target["arch"] == "arm64" or "programs" not in target:
            continue
        sizes = [p["stripped_bytes"] for p in target["programs"] if p["program"] != "every hub type"]
        others.append(f"{target['arch']} {_mb(min(sizes))} to {_mb(max(sizes))}")
    report.aim(aim, f"{_mb(smallest['stripped_bytes'])} ({smallest['program']}) to "
               f"{_mb(largest['stripped_bytes'])} ({largest['program']})" + "".join(f"; {o}" for o in others),
               largest["stripped_bytes"] <= AIM_BYTES,
               "each board package installs the board program of its hub type, linked with that hub type "
               "alone: without the other hub types' logic, messages and device protocols" +
               (f" (every hub type in one program: {_mb(every['stripped_bytes'])})" if every else "") +
               "; -Os and sections per function collected at link. LTO is off: where binutils loads GCC's "
               "plugin by itself, the test programs linked without LTO from fat objects failed with multiple "
               "definitions (docs/board-size.md).")
