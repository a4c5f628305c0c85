"""The "Start -> first State" section of docs/benchmarks.md (hubrt_bench_startup), for bench/report.py.
`report` is report.py's Report: sections (Markdown strings) and aim(aim, measured, ok, why_not)."""

# DESIGN.md section 8: a roscpp node's launch to its first state message.
ROS1_FIRST_STATE_MS = 280


def ms(value, digits=3):
    return f"{value:.{digits}f} ms"


def rate_rows(entry, hub_label, ratio_label):
    """The table rows of one rate's runs: the raw writer, the hub (as `hub_label`), their ratio."""
    rows = []
    for source, label in (("raw", "raw Cyclone writer"), ("hub", hub_label)):
        d = entry[source]
        f = d["first_state_ms"]
        rows.append(f"| {entry['rate_hz']:g} Hz | {label} | {f['n']} | {ms(f['p50'], 1)} | {ms(f['min'], 1)} | "
                    f"{ms(f['max'], 1)} | {d['runs_that_got_seq_1']} of {f['n']} |")
    rows.append(f"| {entry['rate_hz']:g} Hz | {ratio_label} | | {entry['ratio_p50']:.2f}x | | | |")
    return rows


def no_twin_rows(no_twin):
    """Table rows of the 1 kHz run without the start-up twin check (hubd --twin-check-ms=0), and a sentence."""
    entry = next((e for e in (no_twin or {}).get("rates", []) if e["rate_hz"] == 1000), None)
    if entry is None:
        return [], ""
    rows = rate_rows(entry, "hubd --twin-check-ms=0 (no start-up twin check)", "ratio hub without the twin check / raw")
    h, r = entry["hub"]["first_state_ms"], entry["raw"]["first_state_ms"]
    sentence = (f" Measured in the same bench without the start-up twin check (hubd --twin-check-ms=0, another "
                f"1 kHz run of its own): hubd p50 {ms(h['p50'], 1)} against {ms(r['p50'], 1)} for the raw writer "
                f"beside it, {entry['ratio_p50']:.2f}x; the rest of the gap above is the check.")
    return rows, sentence


def startup_section(report, startup, no_twin=None):
    if startup is None:
        report.aim("first State within 50 ms of start", "not measured", False, "did not run.")
        return
    lines = [
        "## Start -> first State",
        "",
        "`hubrt_bench_startup`: a subscriber waits on the State topic; then hubd (Dock ECU) or a raw C API writer "
        "at the same rate is spawned, and the time to the first State arriving is taken. Both include process "
        "start, Cyclone start-up and discovery in both directions; the hub also loads and checks its board and "
        "hub files, watches discovery for a twin until it has settled (no participant newly discovered for 15 ms; "
        "the whole `--twin-check-ms`, 300 ms, only while a hub of an older hubrt is on the domain; its /diagnostics "
        "writer, the sim bridge's endpoints and its hub object are made inside that window) and builds its nodes, "
        "whose State writers may only be made after the verdict. "
        "States written before discovery completes reach nobody (volatile durability): the raw writer's first "
        "State received is the first one written after it, so at the shipped 10 Hz its figure rounds up to a "
        "100 ms period; the hub publishes its State at once when a new reader matches, so its figure is when it "
        "became reachable at every rate. Runs alternate hub and raw.",
        "",
        "| rate | | runs | p50 | min | max | first State received was seq 1 |",
        "|---|---|---|---|---|---|---|",
    ]
    for entry in startup["rates"]:
        lines += rate_rows(entry, "hubd", "ratio hub / raw")
    no_twin_table, no_twin_sentence = no_twin_rows(no_twin)
    lines += no_twin_table
    lines += ["", f"DESIGN.md section 8 reference: ROS 1 roscpp {ROS1_FIRST_STATE_MS} ms from launch to first state."]
    report.sections.append("\n".join(lines) + "\n")
    for entry in startup["rates"]:
        h, r = entry["hub"]["first_state_ms"], entry["raw"]["first_state_ms"]
        rate = entry["rate_hz"]
        why = (f"at {rate:g} Hz the p50 is {ms(h['p50'], 1)} from spawn to the first State at a waiting subscriber; "
               f"a raw Cyclone program writing at the same rate needs {ms(r['p50'], 1)} for the same (process "
               f"start, DDS start-up, discovery), so {max(h['p50'] - r['p50'], 0):.1f} ms is the hub's own start-up "
               "(loading and validating YAML, building the fake backend and the nodes, more DDS entities to "
               "discover).")
        why += (" The twin check ends once discovery has settled (15 ms without a newly discovered participant: "
                "README, \"One hub name, one hub\"), not after its 300 ms window; the rest is process start "
                "(hubd links more libraries than the raw program) and the hub's files, nodes and DDS entities.")
        report.aim(f"first State within 50 ms of start ({rate:g} Hz)",
                   f"p50 {ms(h['p50'], 1)}, max {ms(h['max'], 1)} (raw writer p50 {ms(r['p50'], 1)})",
                   h["p50"] <= 50, why)
        report.aim(f"start -> first State hub / raw writer <= 1.0 ({rate:g} Hz)", f"{entry['ratio_p50']:.2f}x",
                   entry["ratio_p50"] <= 1.0,
                   f"hubd p50 {ms(h['p50'], 1)} against {ms(r['p50'], 1)} for the raw writer. " +
                   ("The raw writer does not publish when a reader matches, so at 10 Hz its first State received "
                    "waits for the next period; the hub's does not." if rate < 100 else
                    "At this rate both are reachable as soon as discovery completes: the difference is hubd's own "
                    "start-up. Most of it is the twin check, which is safety (README, \"One hub name, one hub\"): "
                    "it ends 15 ms after the last participant answered hubd's SPDP (the waiting subscriber answers "
                    "within a loopback round trip), and a hub with the same name that answers within that time must "
                    "be refused before any device is opened or any State written; the DDS entities that need no "
                    "verdict are made while it waits. The rest: process start (hubd loads and relocates more "
                    "shared libraries than the raw program), reading the two YAML files, and the nodes with their "
                    "command reader and State writer after the verdict (hubrt's pooled writer probes the topic's "
                    "sertype with a reader and writer of its own, firmware/dds/src/sertype_probe.cc)." +
                    no_twin_sentence))
