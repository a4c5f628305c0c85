#!/usr/bin/env python3
"""bench/report_plant_tails.py: the medians it reports and the N-against-N = 1 verdicts."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import report_plant_tails  # noqa: E402

KEYS = [k for _, hub, raw, _ in report_plant_tails.FIGURES for k in (hub, raw)]


def plant_row(stations, hub_p99s, raw_p99s, bare=0.2, probes_under=""):
    """A plant.py result row whose tails rounds have these p99s (ms) for every hub and raw figure."""
    rounds = []
    for hub, raw in zip(hub_p99s, raw_p99s):
        r = {"bare_p99_ms": bare}
        for k in KEYS:
            r[k] = {"n": 100, "p99": hub if k.endswith("_hub") or k.startswith("heartbeat_hub") else raw}
        rounds.append(r)
    return {"stations": stations, "design": "domains", "hubd_args": "--realtime", "probes_under": probes_under,
            "tails_per_round": rounds}


class ReportPlantTails(unittest.TestCase):
    def test_the_median_of_the_rounds_is_compared_not_one_round(self):
        one = plant_row(1, [0.5, 0.6, 9.0], [0.4, 0.4, 0.4])  # one stalled round: the median is 0.6
        many = plant_row(32, [0.61, 0.62, 0.1], [0.5, 0.5, 0.5])  # median 0.61: 1.02x
        text = report_plant_tails.report([one, many], 1.05)
        row = next(line for line in text.splitlines() if line.startswith("| echo, sparse, own planner"))
        self.assertIn("0.600 / 0.400 (raw pong)", row)
        self.assertIn("0.610 / 0.500 (raw pong)", row)
        self.assertIn("1.02x / 1.25x (met)", row)

    def test_a_hub_that_grows_past_the_aim_is_not_met(self):
        text = report_plant_tails.report([plant_row(1, [0.5] * 3, [0.5] * 3), plant_row(32, [0.6] * 3, [0.5] * 3)],
                                         1.05)
        self.assertIn("1.20x / 1.00x (not met)", text)
        self.assertNotIn("(met)", text)

    def test_rows_run_differently_are_not_compared(self):
        ordinary = plant_row(1, [0.5] * 3, [0.5] * 3)
        realtime = plant_row(32, [5.0] * 3, [5.0] * 3, probes_under="chrt --fifo 40")
        text = report_plant_tails.report([ordinary, realtime], 1.05)
        self.assertEqual(text.count("**domains"), 2)
        self.assertNotIn("10.00x", text)

    def test_every_line_of_a_table_has_as_many_cells_as_its_header(self):
        for rows in ([plant_row(1, [0.5], [0.5])], [plant_row(1, [0.5], [0.5]), plant_row(32, [0.5], [0.5])]):
            table = [line for line in report_plant_tails.report(rows, 1.05).splitlines() if line.startswith("|")]
            self.assertEqual({line.count("|") for line in table}, {table[0].count("|")}, "\n".join(table))

    def test_repeated_runs_are_pooled_round_by_round(self):
        # Run 1 alone: 0.4 at N = 1 against 0.5 at N = 32 (1.25x). Pooled with run 2, the medians
        # of six rounds: N = 1 [0.4, 0.4, 0.4, 0.6, 0.6, 0.6] -> 0.5; N = 32 [0.5 x3, 0.45 x3] -> 0.475.
        rows = [plant_row(1, [0.4] * 3, [0.4] * 3), plant_row(32, [0.5] * 3, [0.4] * 3),
                plant_row(1, [0.6] * 3, [0.4] * 3), plant_row(32, [0.45] * 3, [0.4] * 3)]
        text = report_plant_tails.report(rows, 1.05)
        self.assertIn("N = 1: 6 rounds of 2 runs, N = 32: 6 rounds of 2 runs", text)
        row = next(line for line in text.splitlines() if line.startswith("| echo, sparse, own planner"))
        self.assertIn("| 0.500 / 0.400 (raw pong) | 0.475 / 0.400 (raw pong) | 0.95x / 1.00x (met) |", row)

    def test_rows_without_tails_give_no_report(self):
        self.assertIsNone(report_plant_tails.report([{"stations": 1, "design": "domains"}], 1.05))


if __name__ == "__main__":
    unittest.main()
