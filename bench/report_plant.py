#!/usr/bin/env python3
"""The picture of bench/plant.py's results for docs/plant.md: how one hub's RSS and CPU, the time a
station started last takes to find its hubs, and the host's load grow with the number of stations,
one line per design.
    bench/report_plant.py [--json build/host-release/bench-results/plant.json] [--svg docs/plant.svg]
Needs python3-matplotlib (toolchain/install-deps --bench)."""
import argparse
import json
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LABELS = {"domains": "one domain per station", "shared": "one shared domain, a namespace per station"}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", default=os.path.join(REPO, "build", "host-release", "bench-results", "plant.json"))
    parser.add_argument("--svg", default=os.path.join(REPO, "docs", "plant.svg"))
    args = parser.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        matplotlib.rcParams["svg.hashsalt"] = "hubrt"  # the same file for the same figures
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("report_plant.py: python3-matplotlib missing (toolchain/install-deps --bench)")
    with open(args.json) as f:
        results = json.load(f)["results"]
    panels = [("Dock ECU RSS (MB, the last station's)", lambda r: r["dock_last"]["rss_mb"], False),
              ("Dock ECU CPU (% of a core)", lambda r: r["dock_last"]["cpu_pct"], False),
              ("last station finds its hubs (s)", lambda r: r.get("discovery_last_s"), True),
              ("host busy (% of 2 cores)", lambda r: r["host"]["busy_pct"], False)]
    fig, axes = plt.subplots(1, len(panels), figsize=(14, 3.4))
    for ax, (title, value, log) in zip(axes, panels):
        for design, style in (("domains", "o-"), ("shared", "s--")):
            rows = sorted((r for r in results if r["design"] == design), key=lambda r: r["stations"])
            points = [(r["stations"], value(r)) for r in rows if value(r) is not None]
            if points:
                ax.plot(*zip(*points), style, label=LABELS[design])
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("stations (7 processes each)", fontsize=8)
        ax.set_xscale("log", base=2)
        if log:
            ax.set_yscale("log")
        ax.set_xticks([1, 4, 16, 32], labels=["1", "4", "16", "32"])
        ax.tick_params(labelsize=8)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.svg, format="svg", metadata={"Date": None})
    print(f"report_plant.py: {args.svg}")


if __name__ == "__main__":
    main()
