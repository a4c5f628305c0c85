#!/usr/bin/env python3
"""The "Command -> echo latency" section of docs/benchmarks.md and its rows of the aims table, from
hubrt_bench_echo_latency's results (echo.json): hubd against a raw Cyclone pong of the same types,
a planner commanding every 20-120 ms and back to back (issue 16 point 8). report.py calls
echo_section()."""

# DESIGN.md section 8: the ROS 1 rebuild of the paper's ECU, measured on this machine.
ROS1_P50_MS = 0.34
ROS1_P99_MS = 0.43


def ms(value, digits=3):
    return f"{value:.{digits}f} ms"


# Issue 16 point 8: command -> echo p50 and p99 within this factor of the raw Cyclone pong, in both
# regimes.
ECHO_AIM_RATIO = 1.10
ECHO_REGIMES = (("sparse", "planner every 20-120 ms"), ("back_to_back", "back to back"))


def ros1_echo_alternative(ros1):
    """The roscpp ECU's round trip: measured in this run when the ROS 1 bench ran, else DESIGN.md's."""
    if ros1 and ros1.get("ros1_ecu", {}).get("echo_ms", {}).get("n"):
        e = ros1["ros1_ecu"]["echo_ms"]
        return f"roscpp ECU (ROS 1, this run): p50 {ms(e['p50'])}, p99 {ms(e['p99'])}"
    return f"roscpp ECU (DESIGN.md section 8): p50 {ROS1_P50_MS} ms, p99 {ROS1_P99_MS} ms"


def rounds_text(echo):
    """How the ratios were taken: the median of rounds (each both sides interleaved) and the pinning."""
    rounds = echo.get("rounds")
    if not rounds:
        return "The ratios are those of the pooled percentiles."
    pin = echo.get("pinning", {})
    pinned = (f"both answering processes pinned to CPU {pin['peers_cpu']} (every thread: raw {pin['raw_threads']}, "
              f"hub {pin['hub_threads']}), the planner to CPU(s) {pin['planner_cpus']}"
              if pin.get("peers_cpu") is not None else "no CPU pinning")
    return (f"Each regime is measured in {rounds} rounds, each round both sides interleaved (so a load that drifts "
            "during the run hits both alike); a ratio is the median of the rounds' ratios, with their spread (lowest "
            f"- highest round) in brackets; {pinned}. The percentiles in the table are pooled over all rounds.")


def ratio_label(r):
    return ", median of rounds" if "rounds" in r else ""


def spread(r, key, prefix=None):
    """The lowest and highest round's ratio: " (a-b)", or prefix + "a-b"."""
    if key not in r:
        return ""
    low, high = r[key]
    return f" ({low:.2f}-{high:.2f})" if prefix is None else f"{prefix}{low:.2f}-{high:.2f}"


def heartbeat_lines(echo):
    """The hub's round trips that found it publishing its heartbeat (another State arrived first)."""
    parts = []
    for key, name in ECHO_REGIMES:
        r = echo[key]
        if "hub_with_heartbeat_between" not in r:
            return []
        clean = r["hub_without_heartbeat_ms"]
        parts.append(f"{name}: {r['hub_with_heartbeat_between']} of {r['hub_ms']['n']}, the others p50 "
                     f"{ms(clean['p50'])}, p99 {ms(clean['p99'])} (all: p99 {ms(r['hub_ms']['p99'])})")
    return ["", "Hub round trips during which its heartbeat went out first (another State arrived before the echo: "
            "the command came while the cycle thread was publishing the periodic State, and waited for it): "
            + "; ".join(parts) + "."]


def echo_section(report, echo, ros1=None):
    if echo is None or "sparse" not in echo:
        for _, name in ECHO_REGIMES:
            report.aim(f"command -> echo, {name}: p50 and p99 <= {ECHO_AIM_RATIO:.1f} x raw Cyclone pong",
                       "not measured", False, "the echo benchmark did not run.")
        return
    lines = [
        "## Command -> echo latency",
        "",
        f"`hubrt_bench_echo_latency`: payload {echo['payload']}; QoS {echo['qos']}. The hub (hubd, "
        f"{echo['hub_rate_hz']:g} Hz) and a raw C API pong process (`hubrt_bench_raw_peer pong`: takes the command "
        "from a waitset and writes the State with its echo at once) answer the same planner (C API, waitset), "
        "taking turns. Each command differs from the one before, so it takes effect and the hub publishes its "
        "State at once. Two regimes: **sparse**, a command every 20-120 ms (random gaps, as Sequence Planner "
        "sends them), where every command finds both processes asleep and wake-ups dominate; **back to back**, "
        "each command written as soon as the echo of the one before is back, in bursts of "
        f"{echo['burst']} (the hub's budget of immediate States: a token bucket of {echo['burst']} refilled one "
        f"per 10 ms; the planner pauses {echo['refill_ms']:.0f} ms between bursts, and the first command of a "
        "burst, which comes after that pause, is not recorded).",
        "",
        rounds_text(echo),
        "",
        "| regime | | n | p50 | p90 | p99 | max |",
        "|---|---|---|---|---|---|---|",
    ]
    alternative = ros1_echo_alternative(ros1)
    for key, name in ECHO_REGIMES:
        r = echo[key]
        raw, hub = r["raw_ms"], r["hub_ms"]
        lines += [
            f"| {name} | raw Cyclone pong | {raw['n']} | {ms(raw['p50'])} | {ms(raw['p90'])} | {ms(raw['p99'])} | "
            f"{ms(raw['max'])} |",
            f"| {name} | hub | {hub['n']} | {ms(hub['p50'])} | {ms(hub['p90'])} | {ms(hub['p99'])} | "
            f"{ms(hub['max'])} |",
            f"| {name} | ratio hub / raw{ratio_label(r)} | | {r['ratio_p50']:.2f}x{spread(r, 'ratio_p50_spread')} | | "
            f"{r['ratio_p99']:.2f}x{spread(r, 'ratio_p99_spread')} | |",
        ]
        ok = r["ratio_p50"] <= ECHO_AIM_RATIO and r["ratio_p99"] <= ECHO_AIM_RATIO
        report.aim(f"command -> echo, {name}: p50 and p99 <= {ECHO_AIM_RATIO:.1f} x raw Cyclone pong",
                   f"hub p50 {ms(hub['p50'])} ({r['ratio_p50']:.2f}x{spread(r, 'ratio_p50_spread', ', rounds ')}), p99 "
                   f"{ms(hub['p99'])} ({r['ratio_p99']:.2f}x{spread(r, 'ratio_p99_spread', ', rounds ')})",
                   ok,
                   f"{name}: hub p50 {ms(hub['p50'])} against raw {ms(raw['p50'])} ({r['ratio_p50']:.2f}x), p99 "
                   f"{ms(hub['p99'])} against {ms(raw['p99'])} ({r['ratio_p99']:.2f}x). Both pay the same transport "
                   "and the same thread hand-offs (Cyclone's receive thread delivers the command and wakes the "
                   "thread that answers: the raw pong's waitset, the hub's cycle thread); the rest is what the hub "
                   "does per command (take and validate it, run the node, rebuild and write the State), which "
                   "after a sleep runs from colder caches than the pong's few lines (the sparse ratio grows when "
                   "the hub runs at 10 Hz instead of 100 Hz), and, in the tail, a heartbeat cycle the command "
                   "arrives behind. On a shared, loaded machine the p99 of both sides is set by scheduling delays "
                   "of milliseconds, so it moves from run to run by more than the aim's 10 %.",
                   alternative=f"raw pong p50 {ms(raw['p50'])}, p99 {ms(raw['p99'])}; {alternative}")
    lines += heartbeat_lines(echo)
    lines += [
        "",
        f"Lost (no echo within 1 s): raw {echo['raw_lost']}, hub {echo['hub_lost']}. Best known alternative: "
        f"{alternative}. The DESIGN.md section 8 raw round trip of about 9 us was ddsperf free-running with "
        "12-byte samples; this run's raw figure is the same measurement with this payload and this planner.",
        "",
        "Thread hand-offs from the command's datagram to the State's (counted with strace on both processes, "
        "issue 16): one in each. Cyclone's receive thread reads the datagram and delivers it synchronously "
        "(SynchronousDeliveryLatencyBound is infinite by default, so every user writer's samples are delivered "
        "from the receive thread: Cyclone 0.10 ddsi_proxy_endpoint.c); in hubd it calls the reader's "
        "data-available listener, which writes the cycle timer's eventfd, and the cycle thread's poll returns, "
        "takes the command, runs the node and writes the State (`dds_write`, `sendmsg` on the cycle thread); in "
        "the raw pong the receive thread signals the waitset's condition variable and the main thread takes and "
        "writes. No intermediate thread (delivery queue, executor) sits between them to remove; the hub's "
        "hand-off costs two system calls more (eventfd write and read).",
    ]
    report.sections.append("\n".join(lines) + "\n")
