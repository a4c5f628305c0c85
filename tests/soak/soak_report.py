#!/usr/bin/python3
"""Judges and draws a soak run's samples (soak.csv, written by tests/soak/soak).

  tests/soak/soak_report.py SOAK_CSV [--minutes N]    re-judge a run, redraw its picture

The thresholds, and why they are what they are (docs/soak.md says the same at more length):
  - warm-up: the first WARMUP_SHARE of the run (at least 2, at most 10 minutes) is not judged:
    Cyclone's and malloc's free lists, the discovery tables and the first rounds of every command
    fill up then, which is growth that stops.
  - RSS: the growth of its peaks. Cyclone bump-allocates received messages through a receive
    buffer per receive thread (1 MiB by default) and frees the buffer when it is used up, so RSS
    is a saw-tooth whose teeth are one buffer high, whatever the uptime (docs/soak.md). A straight
    line through such samples says nothing; the highest RSS of the second half of the judged
    samples against the highest of the first half does: equal for a saw-tooth, apart by the leak
    for a leak. That difference per minute must stay below RSS_SLOPE_KB_MIN: the load brings ~25
    new participants a minute and continuous commands, so a leak of 1 kB per reconnect shows as
    ~25 kB/min, and the saw-tooth sampled every 30 s leaves a few kB/min of noise.
    The least-squares slope is printed too, for the record.
  - threads and fds: after the warm-up never above their value at the end of the warm-up + a
    small allowance (THREADS_ALLOWANCE, FDS_ALLOWANCE): Cyclone's thread and socket count per
    participant is fixed, so any climb is a leak of the hub's own.
  - heartbeat: every sampling window of every process: no State sequence gap, the longest period
    between the States' own stamps at most twice the nominal period (the conformance suite's
    jitter_max_pct of 100 %: beyond it a planner would call the hub silent), the rate no lower than
    RATE_TOLERANCE below nominal (a hub also sends an immediate State when a command changes
    something, so more is not a miss). As in `hubctl conformance`, periods are judged on the
    stamps, when the process itself published: the sampler's arrival periods also hold every
    stall of the sampling process and of the host, so they are reported, not judged. And a
    process cannot publish while the host runs nothing at all: the longest period less the
    longest stall of a bare loop at the same priority in the same window (host_late_max_ms) is
    what is judged, so a shared machine's stalls are reported as the host's, and a hub that is
    late by more than the host stalled still fails.
  - no process exited (checked by the driver, and shown here as rows that say "exited").
"""
import csv
import dataclasses
import sys

# period_*: between arrivals at the sampler (this host's delays included); stamp_period_max_ms:
# between the States' own header stamps (when the process published), which is what is judged;
# host_late_max_ms: the longest a bare 10 ms loop beside them woke late in the same window.
COLUMNS = ["time_s", "process", "pid", "rss_kb", "threads", "fds", "rate_hz", "period_p99_ms",
           "period_max_ms", "stamp_period_max_ms", "seq_gaps", "host_late_max_ms", "note"]
WARMUP_SHARE = 0.2
RSS_SLOPE_KB_MIN = 8.0
THREADS_ALLOWANCE = 0
FDS_ALLOWANCE = 2
MAX_PERIOD_FACTOR = 2.0
RATE_TOLERANCE = 0.10


@dataclasses.dataclass
class Verdict:
    ok: bool = True
    lines: list = dataclasses.field(default_factory=list)

    def fail(self, text):
        self.ok = False
        self.lines.append("FAIL " + text)

    def info(self, text):
        self.lines.append(text)


def load(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def by_process(rows):
    out = {}
    for row in rows:
        out.setdefault(row["process"], []).append(row)
    return out


def warmup_minutes(minutes):
    return min(10.0, max(2.0, minutes * WARMUP_SHARE))


def slope_per_minute(points):
    """Least-squares slope of (seconds, value) points, in value per minute."""
    n = len(points)
    if n < 2:
        return 0.0
    mean_t = sum(t for t, _ in points) / n
    mean_v = sum(v for _, v in points) / n
    var = sum((t - mean_t) ** 2 for t, _ in points)
    if var == 0:
        return 0.0
    return 60.0 * sum((t - mean_t) * (v - mean_v) for t, v in points) / var


def peak_growth_per_minute(points):
    """(peak of the second half - peak of the first half) / minutes between the halves' middles."""
    half = len(points) // 2
    first, second = points[:half], points[len(points) - half:]
    if half < 1:
        return 0.0
    minutes = (sum(t for t, _ in second) / half - sum(t for t, _ in first) / half) / 60.0
    if minutes <= 0:
        return 0.0
    return (max(v for _, v in second) - max(v for _, v in first)) / minutes


def judged_period(sample):
    """The longest period by the States' stamps; by arrival in a CSV written before stamps were kept."""
    return float(sample.get("stamp_period_max_ms") or sample["period_max_ms"])


def host_stall(sample):
    return float(sample.get("host_late_max_ms") or 0)


def judge(rows, nominal_hz, minutes):
    """nominal_hz: process -> its heartbeat's nominal rate. Returns a Verdict."""
    verdict = Verdict()
    warm_s = warmup_minutes(minutes) * 60
    verdict.info(f"judged after a {warm_s / 60:g}-minute warm-up; RSS peak growth limit {RSS_SLOPE_KB_MIN:g} kB/min")
    for name, samples in sorted(by_process(rows).items()):
        if any(s["note"].startswith("exited") for s in samples):
            verdict.fail(f"{name} {next(s['note'] for s in samples if s['note'])}")
            continue
        judged = [s for s in samples if float(s["time_s"]) >= warm_s]
        if len(judged) < 3:
            verdict.fail(f"{name}: only {len(judged)} samples after the warm-up; run longer")
            continue
        rss = [(float(s["time_s"]), float(s["rss_kb"])) for s in judged]
        slope = slope_per_minute(rss)
        growth = peak_growth_per_minute(rss)
        text = (f"{name}: RSS {rss[0][1]:.0f} -> {rss[-1][1]:.0f} kB (peak {max(v for _, v in rss):.0f}), peak "
                f"growth {growth:+.2f} kB/min, least-squares slope {slope:+.2f} kB/min; threads "
                f"{judged[0]['threads']}..{max(int(s['threads']) for s in judged)}, fds "
                f"{judged[0]['fds']}..{max(int(s['fds']) for s in judged)}")
        if growth >= RSS_SLOPE_KB_MIN:
            verdict.fail(text + f" (RSS grows faster than {RSS_SLOPE_KB_MIN:g} kB/min)")
        else:
            verdict.info(text)
        for key, allowance in (("threads", THREADS_ALLOWANCE), ("fds", FDS_ALLOWANCE)):
            base = int(judged[0][key])
            peak = max(int(s[key]) for s in judged)
            if peak > base + allowance:
                verdict.fail(f"{name}: {key} climbed from {base} to {peak} after the warm-up")
        nominal = nominal_hz.get(name)
        if nominal is None:
            continue
        budget_ms = MAX_PERIOD_FACTOR * 1000.0 / nominal
        worst = max(judged_period(s) for s in samples)
        worst_arrival = max(float(s["period_max_ms"]) for s in samples)
        gaps = sum(int(s["seq_gaps"] or 0) for s in samples)
        stalled = [s for s in samples if judged_period(s) > budget_ms >= judged_period(s) - host_stall(s)]
        verdict.info(f"{name}: heartbeat {nominal:g} Hz, longest period {worst:.1f} ms by its stamps (budget "
                     f"{budget_ms:.0f} ms; {worst_arrival:.1f} ms between arrivals), {gaps} sequence gaps")
        if stalled:
            verdict.info(f"{name}: {len(stalled)} window(s) with a period over the budget while the host "
                         f"itself stalled (bare loop up to {max(host_stall(s) for s in stalled):.0f} ms late): "
                         "the host's, not judged against the process")
        for s in samples:
            rate = float(s["rate_hz"])
            when = f"{name} at {float(s['time_s']) / 60:.1f} min"
            if rate < (1 - RATE_TOLERANCE) * nominal:
                verdict.fail(f"{when}: State rate {rate:.2f} Hz, nominal {nominal:g} Hz")
            if judged_period(s) - host_stall(s) > budget_ms:
                verdict.fail(f"{when}: a State period of {judged_period(s):.1f} ms (budget {budget_ms:.0f}; the "
                             f"host stalled {host_stall(s):.0f} ms in that window)")
            if int(s["seq_gaps"] or 0) > 0:
                verdict.fail(f"{when}: {s['seq_gaps']} States missing (sequence gaps)")
    return verdict


def can_draw():
    """Whether the picture can be drawn: checked before an hour of soak, not after it."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def draw(rows, path):
    """Draws the picture into path; False (and says why) where matplotlib is missing."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"soak: no picture ({path}): python3-matplotlib is missing (toolchain/install-deps --bench)")
        return False
    fig, axes = plt.subplots(4, 1, figsize=(9, 11), sharex=True)
    for name, samples in sorted(by_process(rows).items()):
        alive = [s for s in samples if s["rss_kb"]]
        t = [float(s["time_s"]) / 60 for s in alive]
        axes[0].plot(t, [float(s["rss_kb"]) / 1024 for s in alive], marker=".", label=name)
        axes[1].plot(t, [int(s["threads"]) for s in alive], marker=".", label=name)
        axes[2].plot(t, [int(s["fds"]) for s in alive], marker=".", label=name)
        axes[3].plot(t, [judged_period(s) for s in alive], marker=".", label=name)
    for ax, label in zip(axes, ["RSS (MiB)", "threads", "open fds", "longest State period by stamps (ms)"]):
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="upper left", fontsize="small")
    axes[-1].set_xlabel("minutes")
    fig.suptitle("hubrt soak: the simulated station under reconnects, floods and faults")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return True


def main(argv):
    import argparse

    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("--minutes", type=float, default=None, help="run length (default: from the samples)")
    args = parser.parse_args(argv)
    rows = load(args.csv)
    minutes = args.minutes or max(float(r["time_s"]) for r in rows) / 60
    nominal = {"tool_ecu": 10.0, "rsp_ecu": 10.0, "dock_ecu": 10.0, "hubsim": 50.0}
    verdict = judge(rows, nominal, minutes)
    for line in verdict.lines:
        print(line)
    draw(rows, args.csv.rsplit(".", 1)[0] + ".png")
    return 0 if verdict.ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
