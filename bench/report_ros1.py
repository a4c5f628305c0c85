#!/usr/bin/env python3
"""The "ROS 1 ECU and hubbridge" section of docs/benchmarks.md, from hubrt_bench_ros1's results
(ros1.json): a roscpp Dock ECU (10 Hz loop, immediate echo) beside hubd, and the latency hubbridge
adds. report.py calls ros1_section(); `report_ros1.py --results DIR --markdown FILE` puts the
section into an existing docs/benchmarks.md alone (a run of this benchmark only)."""
import argparse
import json
import os
import re

TITLE = "## ROS 1 ECU and hubbridge"


def _ms(x):
    return "%.3f ms" % x


def _ratio(a, b):
    return "%.2fx" % (a / b) if b else "n/a"


def section_lines(data):
    hubd, ecu, bridged = data["hubd"], data["ros1_ecu"], data["ros1_ecu_bridged"]
    lines = [TITLE, "",
             "`hubrt_bench_ros1`: a Dock ECU written the ROS 1 way in roscpp (`bench/programs/ros1_ecu.cc`: 10 Hz "
             "state loop, immediate echo from its command callback, DockState/DockCommand as ShapeShifter with the "
             "ROS 1 form of ros2/hub_msgs) side by side with hubd's Dock ECU (10 Hz), in one run: the roscpp ECU "
             "measured by a roscpp planner over ROS 1 (TCPROS, tcp_nodelay, loopback), the same ECU measured from "
             "DDS through `hubbridge` (docs/ros1-bridge.md), hubd measured from DDS. CPU and RSS are the ECU "
             "process's (for the bridged row: hubbridge's own) over the heartbeat window.", "",
             "| | command -> echo p50 | p99 | lost | start -> first State p50 | period jitter p50 | p99 | CPU | RSS |",
             "|---|---|---|---|---|---|---|---|---|"]

    def row(name, d):
        e, h = d["echo_ms"], d["heartbeat"]
        first = d.get("first_state_ms")
        lines.append("| %s | %s | %s | %d | %s | %s | %s | %.2f %% | %.1f MB |" % (
            name, _ms(e["p50"]), _ms(e["p99"]), e.get("lost", 0), _ms(first["p50"]) if first and first.get("n") else "-",
            _ms(h["jitter_ms"]["p50"]), _ms(h["jitter_ms"]["p99"]), h.get("cpu_pct", 0), h.get("rss_mb", 0)))
    row("hubd (DDS)", hubd)
    row("roscpp ECU (ROS 1 direct)", ecu)
    row("roscpp ECU through hubbridge (DDS)", bridged)
    added = bridged["echo_ms"]["p50"] - ecu["echo_ms"]["p50"]
    lines += ["",
              "Ratios: command -> echo p50 roscpp ECU / hubd = %s; start -> first State roscpp ECU / hubd = %s; "
              "RSS roscpp ECU / hubd = %s; CPU roscpp ECU / hubd = %s. hubbridge adds %s at p50 (%s of the direct "
              "ROS 1 round trip; p99 %s vs %s): a command and its echo each cross one more process and one "
              "more serialisation." % (
                  _ratio(ecu["echo_ms"]["p50"], hubd["echo_ms"]["p50"]),
                  _ratio(ecu["first_state_ms"]["p50"], hubd["first_state_ms"]["p50"]),
                  _ratio(ecu["heartbeat"].get("rss_mb", 0), hubd["heartbeat"].get("rss_mb", 0)),
                  _ratio(ecu["heartbeat"].get("cpu_pct", 0), hubd["heartbeat"].get("cpu_pct", 0)),
                  _ms(added), _ratio(bridged["echo_ms"]["p50"], ecu["echo_ms"]["p50"]),
                  _ms(bridged["echo_ms"]["p99"]), _ms(ecu["echo_ms"]["p99"])), ""]
    return lines


def ros1_section(report, data):
    """Adds the section to report.py's Report (nothing when the benchmark did not run)."""
    if data:
        report.sections += section_lines(data)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", required=True)
    parser.add_argument("--markdown", required=True)
    parser.add_argument("--run", default="", help="when and how this section was measured, for its text")
    args = parser.parse_args()
    with open(os.path.join(args.results, "ros1.json")) as f:
        lines = section_lines(json.load(f))
    if args.run:
        lines.insert(2, "This section alone: %s." % args.run)
        lines.insert(3, "")
    with open(args.markdown) as f:
        doc = f.read()
    text = "\n".join(lines) + "\n"
    pattern = re.compile(re.escape(TITLE) + r"\n.*?(?=\n## |\Z)", re.S)
    if pattern.search(doc):
        doc = pattern.sub(lambda _: text.rstrip("\n"), doc)
    else:
        doc = doc.rstrip("\n") + "\n\n" + text
    with open(args.markdown, "w") as f:
        f.write(doc)


if __name__ == "__main__":
    main()
