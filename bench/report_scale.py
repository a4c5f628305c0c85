"""The "Many hubs on one host" section of docs/benchmarks.md (hubrt_bench_scale), for bench/report.py.
`report` is report.py's Report: sections (Markdown strings) and aim(aim, measured, ok, why_not)."""


def ms(value, digits=3):
    return f"{value:.{digits}f} ms"


def scale_row(s):
    failed = ", ".join(f"{k} x{v}" for k, v in sorted(s["failed_checks"].items())) or "none"
    late = s.get("late_planner", {}).get("heard_ms", [])
    late_text = ms(max(late), 0) if late else "-"
    after = ms(s["heard_after_last_spawn_ms"], 0) if "heard_after_last_spawn_ms" in s else "-"
    exited = s.get("hubs_exited", 0)
    conformance = f"{s['conformance_s']:.0f} s" if "conformance_s" in s else "-"
    start_cpu = f"{s['start_cpu_s']:.1f} s" if "start_cpu_s" in s else "-"
    return (f"| {s['hubs']} | {s['rate_hz']:g} Hz | {ms(s['all_heard_ms'], 0)} | {after} | {start_cpu} | {late_text} | "
            f"{s['cpu_total_pct']:.1f} % | {s['cpu_per_hub_pct']:.2f} % | {s['rss_per_hub_mb'] * s['hubs']:.0f} MB | "
            f"{s['rss_per_hub_mb']:.1f} MB | {s['conforming']}/{s['hubs']} | {failed} | {exited} | {conformance} |")


def scale_section(report, scale):
    if scale is None or not scale.get("sizes"):
        report.aim("32 hubs on one host all conforming", "not measured", False, "the scale run did not complete.")
        return
    per_host = scale.get("loopback_participants_per_host", scale.get("max_auto_participant_index"))
    lines = [
        "## Many hubs on one host",
        "",
        "`hubrt_bench_scale`: N Dock ECU hubs (hubd processes), each with its own name and ROS namespace, at the "
        "shipped Dock ECU's 10 Hz (and 32 of them at 100 Hz). All heard: from spawning the first hub to a planner "
        "waiting since before having matched every State writer and received a State from each; after the last "
        "start: the same from the last hub's spawn, with the CPU time all hubs spent until then (start-up and "
        "discovery: on 2 cores the wall time cannot be less than half of it); late planner: a planner that starts when every hub is up, from "
        "creating its participant to a State from each hub (worst of 3). CPU and RSS: all hubs over a window. "
        "Conformance: one `hubctl conformance --parallel` against all of them at once with the default thresholds "
        "(short phases), and how long it took. Exited: hubs that ended by themselves. Every process uses hubrt's "
        f"loopback configuration, which admits {per_host} DDS processes per host. Load average during the run: "
        f"{scale.get('load_start', '?')} at start, {scale.get('load_end', '?')} at end.",
        "",
        "| hubs | rate | all heard | after the last start | hubs' CPU until then | late planner | CPU total | "
        "CPU per hub | RSS total | RSS per hub | conforming | failed checks | exited | conformance run |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [scale_row(s) for s in scale["sizes"]]
    report.sections.append("\n".join(lines) + "\n")

    def at(hubs, rate=10):
        return next((s for s in scale["sizes"] if s["hubs"] == hubs and s["rate_hz"] == rate), None)

    def failed_text(s):
        return ", ".join(f"{k} x{v}" for k, v in sorted(s["failed_checks"].items())) or "none"

    s32 = at(32)
    if s32 is None:
        report.aim("32 hubs on one host all conforming", "not measured", False, "the 32-hub size did not run.")
    else:
        report.aim("32 hubs on one host all conforming", f"{s32['conforming']}/32 at 10 Hz",
                   s32["conforming"] == 32 and s32.get("hubs_exited", 0) == 0,
                   f"with 32 hubs at 10 Hz {s32['conforming']} passed (failed checks: {failed_text(s32)}; "
                   f"{s32.get('hubs_exited', 0)} hubs ended by themselves). 32 hub processes, the suite's 32 "
                   "parallel sessions and every other job share 2 cores.")
        late = s32.get("late_planner", {}).get("heard_ms", [])
        if late:
            worst = max(late)
            report.aim("discovery of all 32 hubs in under 500 ms",
                       f"late planner {ms(worst, 0)} (worst of {len(late)}); "
                       f"{ms(s32['heard_after_last_spawn_ms'], 0)} after the last hub's start"
                       + (f" (the hubs' start-up took {s32['start_cpu_s']:.1f} CPU-s on 2 cores)"
                          if "start_cpu_s" in s32 else ""),
                       worst < 500,
                       f"a planner joining 32 running hubs heard every one after {ms(worst, 0)} at worst.")
    s64 = at(64)
    if s64 is not None:
        report.aim("64 hubs on one host conforming", f"{s64['conforming']}/64 at 10 Hz",
                   s64["conforming"] == 64 and s64.get("hubs_exited", 0) == 0,
                   f"with 64 hubs at 10 Hz {s64['conforming']} passed (failed checks: {failed_text(s64)}; "
                   f"{s64.get('hubs_exited', 0)} hubs ended by themselves): 64 hubs and hubctl's 64 parallel "
                   "sessions on 2 shared cores; the timing checks are what fails first. Discovery grows with the "
                   "square of the hubs (each hub learns every other hub's endpoints)"
                   + (f": the 64 hubs spent {s64['start_cpu_s']:.1f} CPU-s starting and discovering each other"
                      if "start_cpu_s" in s64 else "") + ".")
