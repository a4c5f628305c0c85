#!/usr/bin/env python3
"""The tails of a hub as the plant grows (issue 33, docs/plant.md): from the results of
`bench/plant.py --tails`, each figure's p99 in milliseconds (the median over hubrt_bench_tails'
rounds, the hub's and its baseline's) for every plant size, and each size against the smallest.
Rows of one design and one way of running hubs and probes are compared with each other only. Given
several result files (repeated runs), the rows of one group and N are pooled: their rounds together,
the median over all of them (ten rounds per run).
    bench/report_plant_tails.py [--json FILE [FILE ...]] [--aim 1.05]
(default FILE: build/host-release/bench-results/plant.json)
Prints a Markdown table; exit status 0 whether or not the aim is met (it is a report, not a gate)."""
import argparse
import json
import os
import statistics
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# (figure, the hub's key, the baseline's key, the baseline's name) in each of tails' per_round entries.
FIGURES = [("echo, sparse, own planner", "own_sparse_hub", "own_sparse_raw", "raw pong"),
           ("echo, back to back, own planner", "own_back_to_back_hub", "own_back_to_back_raw", "raw pong"),
           ("echo, sparse, C planner", "c_planner_sparse_hub", "c_planner_sparse_raw", "raw pong"),
           ("echo, back to back, C planner", "c_planner_back_to_back_hub", "c_planner_back_to_back_raw",
            "raw pong"),
           ("heartbeat jitter at a subscriber", "heartbeat_hub_jitter_ms", "heartbeat_raw_jitter_ms",
            "raw writer")]


def median_p99(rounds, key):
    """The median over the rounds of each round's p99, ms; None when no round has it."""
    values = [r[key]["p99"] for r in rounds if key in r and r[key].get("n", 0) > 0]
    return statistics.median(values) if values else None


def group_name(r):
    parts = [r["design"]]
    if r.get("hubd_args"):
        parts.append(f"hubd {r['hubd_args']}")
    if r.get("probes_under"):
        parts.append(f"probes under {r['probes_under']}")
    return ", ".join(parts)


def pooled(rows):
    """One row per N: the rounds of every run of that N together."""
    by_n = {}
    for r in rows:
        if r["stations"] in by_n:
            first = by_n[r["stations"]]
            by_n[r["stations"]] = dict(first, tails_per_round=first["tails_per_round"] + r["tails_per_round"],
                                       runs=first.get("runs", 1) + 1)
        else:
            by_n[r["stations"]] = r
    return list(by_n.values())


def report(results, aim):
    groups = {}
    for r in results:
        if r.get("tails_per_round"):
            groups.setdefault(group_name(r), []).append(r)
    if not groups:
        return None
    groups = {name: pooled(rows) for name, rows in groups.items()}
    lines = []
    for name, rows in groups.items():
        rows.sort(key=lambda r: r["stations"])
        smallest = rows[0]
        rounds = ", ".join(f"N = {r['stations']}: {len(r['tails_per_round'])} rounds"
                           + (f" of {r['runs']} runs" if r.get("runs", 1) > 1 else "") for r in rows)
        lines.append(f"**{name}**: p99 in ms, the median of the rounds ({rounds}); hub / baseline; "
                     f"each N against N = {smallest['stations']}, aim <= {aim:.2f}x for the hub\n")
        columns = ["figure"] + [f"N = {r['stations']}" for r in rows]
        columns += [f"N = {r['stations']} / N = {smallest['stations']}, hub / baseline" for r in rows[1:]]
        lines.append("| " + " | ".join(columns) + " |")
        lines.append("|---" * len(columns) + "|")
        keyed = FIGURES + [("bare clock_nanosleep loop, lateness", "bare_p99_ms", None, "")]
        for figure, hub_key, raw_key, baseline in keyed:
            cells, ratios = [], []
            first = None
            for r in rows:
                per_round = r["tails_per_round"]
                if raw_key is None:
                    values = [x[hub_key] for x in per_round if hub_key in x]
                    hub, raw = (statistics.median(values) if values else None), None
                else:
                    hub, raw = median_p99(per_round, hub_key), median_p99(per_round, raw_key)
                cells.append("-" if hub is None else
                             f"{hub:.3f}" + ("" if raw is None else f" / {raw:.3f} ({baseline})"))
                if first is None:
                    first = (hub, raw)
                    continue
                if hub is None or not first[0]:
                    ratios.append("-")
                    continue
                hub_ratio = hub / first[0]
                met = "" if raw_key is None else (" (met)" if hub_ratio <= aim else " (not met)")
                raw_ratio = "" if raw is None or not first[1] else f" / {raw / first[1]:.2f}x"
                ratios.append(f"{hub_ratio:.2f}x{raw_ratio}{met}")
            lines.append(f"| {figure} | " + " | ".join(cells + ratios) + " |")
        lines.append("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", nargs="+",
                        default=[os.path.join(REPO, "build", "host-release", "bench-results", "plant.json")])
    parser.add_argument("--aim", type=float, default=1.05, help="N against the smallest N, for the hub's p99")
    args = parser.parse_args()
    results = []
    for path in args.json:
        try:
            with open(path) as f:
                results += json.load(f)["results"]
        except (OSError, ValueError, KeyError) as e:
            sys.exit(f"report_plant_tails.py: {path}: {e}")
    text = report(results, args.aim)
    if text is None:
        sys.exit(f"report_plant_tails.py: {' '.join(args.json)}: no row with tails (bench/plant.py --tails)")
    print(text)


if __name__ == "__main__":
    main()
