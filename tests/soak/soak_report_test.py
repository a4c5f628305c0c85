#!/usr/bin/python3
"""The soak tier's verdict (soak_report.judge) on made-up runs: what passes, what fails and why.

A soak takes an hour, so its pass/fail rules are checked here, in the default suite, on samples
shaped like real runs: Cyclone's receive-buffer saw-tooth (docs/soak.md) must pass, a steady
leak, a climbing thread or fd count, a late or missing heartbeat and a dead process must fail.
"""
import pathlib
import sys
import unittest

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import soak_report  # noqa: E402

NOMINAL = {"dock_ecu": 10.0}


def run(minutes=20, rss=lambda t: 12000, threads=lambda t: 9, fds=lambda t: 20, rate=10.0,
        period_max=lambda t: 130.0, arrival_max=None, gaps=lambda t: 0, host_late=lambda t: 1.0, exit_at=None):
    """Samples of one dock_ecu every 30 s; each figure a function of the time in seconds."""
    rows = []
    for k in range(1, int(minutes * 2) + 1):
        t = 30.0 * k
        row = dict.fromkeys(soak_report.COLUMNS, "")
        row.update(time_s=f"{t}", process="dock_ecu", pid="42")
        if exit_at is not None and t >= exit_at:
            row["note"] = "exited -11"
        else:
            row.update(rss_kb=f"{rss(t):.0f}", threads=str(threads(t)), fds=str(fds(t)), rate_hz=f"{rate}",
                       period_p99_ms="105", period_max_ms=f"{(arrival_max or period_max)(t)}",
                       stamp_period_max_ms=f"{period_max(t)}", seq_gaps=str(gaps(t)),
                       host_late_max_ms=f"{host_late(t)}")
        rows.append(row)
    return soak_report.judge(rows, NOMINAL, minutes)


def sawtooth(t, amplitude_kb=700, cycle_s=170):
    """Cyclone's receive buffer: pages touched as it fills, all returned when it is replaced."""
    return 12000 + amplitude_kb * ((t % cycle_s) / cycle_s)


class VerdictTest(unittest.TestCase):
    def assert_fails_with(self, verdict, words):
        self.assertFalse(verdict.ok, verdict.lines)
        self.assertTrue(any(words in line for line in verdict.lines if line.startswith("FAIL")), verdict.lines)

    def test_a_flat_run_passes(self):
        verdict = run()
        self.assertTrue(verdict.ok, verdict.lines)

    def test_the_receive_buffer_sawtooth_is_not_growth(self):
        verdict = run(rss=sawtooth)
        self.assertTrue(verdict.ok, verdict.lines)

    def test_a_steady_leak_fails_even_under_the_sawtooth(self):
        # 1 kB per reconnect at ~25 reconnects a minute.
        self.assert_fails_with(run(rss=lambda t: sawtooth(t) + 25 * t / 60), "RSS grows")

    def test_growth_during_the_warm_up_is_not_judged(self):
        verdict = run(rss=lambda t: 12000 + min(t, 120) * 10)
        self.assertTrue(verdict.ok, verdict.lines)

    def test_threads_that_climb_fail(self):
        self.assert_fails_with(run(threads=lambda t: 9 + int(t // 300)), "threads climbed")

    def test_fds_that_climb_fail_and_a_small_wobble_does_not(self):
        self.assertTrue(run(fds=lambda t: 20 + int(t // 30) % 2).ok)
        self.assert_fails_with(run(fds=lambda t: 20 + int(t // 60)), "fds climbed")

    def test_a_period_beyond_the_jitter_budget_fails(self):
        self.assertTrue(run(period_max=lambda t: 199.0).ok)
        self.assert_fails_with(run(period_max=lambda t: 250.0 if t == 600 else 130.0), "budget 200")

    def test_a_stall_only_in_the_arrivals_is_the_hosts_not_the_hubs(self):
        # The sampler (or the host) stalled: its arrivals 400 ms apart, the hub's stamps on time.
        verdict = run(period_max=lambda t: 130.0, arrival_max=lambda t: 400.0 if t == 600 else 130.0)
        self.assertTrue(verdict.ok, verdict.lines)
        self.assertTrue(any("400.0 ms between arrivals" in line for line in verdict.lines), verdict.lines)

    def test_a_late_stamp_fails_even_when_the_arrivals_hide_it(self):
        self.assert_fails_with(run(period_max=lambda t: 250.0 if t == 600 else 130.0, arrival_max=lambda t: 130.0),
                               "budget 200")

    def test_a_late_period_while_the_host_stalled_is_the_hosts(self):
        # Every process of the station late together: a bare loop beside them woke 450 ms late.
        verdict = run(period_max=lambda t: 540.0 if t == 600 else 130.0,
                      host_late=lambda t: 450.0 if t == 600 else 2.0)
        self.assertTrue(verdict.ok, verdict.lines)
        self.assertTrue(any("while the host itself stalled" in line for line in verdict.lines), verdict.lines)

    def test_a_hub_later_than_the_host_stalled_still_fails(self):
        self.assert_fails_with(run(period_max=lambda t: 540.0 if t == 600 else 130.0,
                                   host_late=lambda t: 100.0 if t == 600 else 2.0), "the host stalled 100 ms")

    def test_a_csv_without_stamps_is_judged_by_arrival(self):
        row = dict.fromkeys(soak_report.COLUMNS, "")
        row.update(period_max_ms="250.0")
        self.assertEqual(soak_report.judged_period(row), 250.0)

    def test_a_missing_state_fails(self):
        self.assert_fails_with(run(gaps=lambda t: 1 if t == 900 else 0), "sequence gaps")

    def test_a_slow_rate_fails_and_immediate_states_on_top_do_not(self):
        self.assert_fails_with(run(rate=8.5), "State rate")
        self.assertTrue(run(rate=14.0).ok)

    def test_a_process_that_exited_fails(self):
        self.assert_fails_with(run(exit_at=900), "exited")

    def test_a_run_too_short_to_judge_fails(self):
        self.assert_fails_with(run(minutes=2.5), "run longer")


class SlopeTest(unittest.TestCase):
    def test_least_squares_slope_per_minute(self):
        self.assertAlmostEqual(soak_report.slope_per_minute([(0, 0), (60, 5), (120, 10)]), 5.0)
        self.assertEqual(soak_report.slope_per_minute([(0, 7)]), 0.0)


class PictureTest(unittest.TestCase):
    def test_the_picture_is_drawn_or_its_absence_is_said(self):
        # The driver's last line names the picture only when draw() says it drew one.
        import contextlib
        import io
        import tempfile

        rows = []
        for k in range(1, 5):
            row = dict.fromkeys(soak_report.COLUMNS, "")
            row.update(time_s=f"{30.0 * k}", process="dock_ecu", pid="42", rss_kb="12000", threads="8",
                       fds="14", stamp_period_max_ms="101.0")
            rows.append(row)
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "soak.png"
            said = io.StringIO()
            with contextlib.redirect_stdout(said):
                drawn = soak_report.draw(rows, path)
            self.assertEqual(drawn, soak_report.can_draw())
            self.assertEqual(path.exists(), drawn)
            if not drawn:
                self.assertIn("python3-matplotlib is missing", said.getvalue())


if __name__ == "__main__":
    unittest.main()
