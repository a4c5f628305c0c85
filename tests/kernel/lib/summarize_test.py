#!/usr/bin/python3
"""The kernel tier's summary (summarize.py) on made-up guest results: skipped cases are counted as
skipped — from gtest XML, from gtest's output when the XML is missing, and from exit status 77 —
never as passed; a program whose every case skipped is a SKIP, not a PASS; failures still fail.
"""
import contextlib
import io
import pathlib
import sys
import tempfile
import unittest

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import summarize  # noqa: E402


def case(name, result="completed", status="run", failure=False):
    body = '<failure message="boom"/>' if failure else ""
    if result == "skipped":
        body = '<skipped message="needs gpio-sim"/>'
    return (f'<testcase name="{name}" status="{status}" result="{result}" classname="Suite">'
            f"{body}</testcase>")


def xml(*cases):
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<testsuites><testsuite name="Suite">'
            + "".join(cases) + "</testsuite></testsuites>\n")


class Share:
    """A share folder as the guest leaves it: tests.list, results/status, NAME.xml, NAME.log."""

    def __init__(self, root: pathlib.Path):
        self.root = root
        (root / "results").mkdir()
        self.planned = []
        self.status = []

    def program(self, name, rc, xml_text=None, log_text=""):
        self.planned.append(f"{name} /bin/{name}")
        self.status.append(f"{name} {rc} 0.5")
        if xml_text is not None:
            (self.root / "results" / f"{name}.xml").write_text(xml_text)
        (self.root / "results" / f"{name}.log").write_text(log_text)

    def summarize(self, guest_ok=True):
        (self.root / "tests.list").write_text("\n".join(self.planned) + "\n")
        (self.root / "results" / "status").write_text("\n".join(self.status) + "\n")
        (self.root / "results" / "guest-exit").write_text("0 done\n" if guest_ok else "1 panic\n")
        out = io.StringIO()
        argv = sys.argv
        sys.argv = ["summarize.py", str(self.root), str(self.root / "console.log")]
        try:
            with contextlib.redirect_stdout(out):
                rc = summarize.main()
        finally:
            sys.argv = argv
        return rc, out.getvalue()


class SummaryCountsSkippedAsSkipped(unittest.TestCase):
    def setUp(self):
        self._dir = tempfile.TemporaryDirectory()
        self.share = Share(pathlib.Path(self._dir.name))

    def tearDown(self):
        self._dir.cleanup()

    def closing(self, output):
        return output.strip().splitlines()[-1]

    def test_gtest_skips_in_the_report_are_skipped(self):
        # GTEST_SKIP() in a body (with <skipped>), in SetUp() (result="skipped" only) and a
        # DISABLED_ case (status="notrun").
        self.share.program("hal_test", 0, xml(case("Runs"), case("Body", "skipped"),
                                              '<testcase name="InSetUp" status="run" result="skipped" '
                                              'classname="Suite"></testcase>',
                                              case("DISABLED_Off", "suppressed", status="notrun")))
        rc, out = self.share.summarize()
        self.assertEqual(rc, 0, out)
        self.assertEqual(self.closing(out), "kernel: 1 passed, 0 failed, 3 skipped")

    def test_a_program_whose_every_case_skipped_is_a_skip_not_a_pass(self):
        self.share.program("plumbing_test", 0, xml(case("A", "skipped"), case("B", "skipped")))
        rc, out = self.share.summarize()
        self.assertEqual(rc, 0, out)
        self.assertIn("[kernel] SKIP plumbing_test: 0 passed, 0 failed, 2 skipped", out)
        self.assertNotIn("PASS", out)
        self.assertEqual(self.closing(out), "kernel: 0 passed, 0 failed, 2 skipped")

    def test_without_a_report_gtest_output_is_counted(self):
        log = ("[ RUN      ] Suite.A\n[       OK ] Suite.A (1 ms)\n[ RUN      ] Suite.B\n"
               "[  SKIPPED ] Suite.B (0 ms)\n[==========] 2 tests from 1 test suite ran. (1 ms total)\n"
               "[  PASSED  ] 1 test.\n[  SKIPPED ] 1 test, listed below:\n[  SKIPPED ] Suite.B\n")
        self.share.program("no_xml_test", 0, None, log)
        rc, out = self.share.summarize()
        self.assertEqual(rc, 0, out)
        self.assertEqual(self.closing(out), "kernel: 1 passed, 0 failed, 1 skipped")

    def test_a_program_that_exits_77_skipped(self):
        self.share.program("script_test", 77, None, "no vcan here: skipping\n")
        rc, out = self.share.summarize()
        self.assertEqual(rc, 0, out)
        self.assertIn("[kernel] SKIP script_test", out)
        self.assertEqual(self.closing(out), "kernel: 0 passed, 0 failed, 1 skipped")

    def test_a_program_without_report_that_exits_0_is_one_pass(self):
        self.share.program("script_test", 0, None, "all good\n")
        rc, out = self.share.summarize()
        self.assertEqual(rc, 0, out)
        self.assertEqual(self.closing(out), "kernel: 1 passed, 0 failed, 0 skipped")

    def test_failures_still_fail_beside_skips(self):
        self.share.program("skips", 0, xml(case("A", "skipped")))
        self.share.program("fails", 1, xml(case("A"), case("B", failure=True)))
        self.share.program("crashes_after_cases", 134, xml(case("A")))
        rc, out = self.share.summarize()
        self.assertEqual(rc, 1, out)
        self.assertIn("[kernel] FAIL fails: 1 passed, 1 failed, 0 skipped", out)
        self.assertIn("[kernel]      failed: Suite.B", out)
        self.assertIn("[kernel] FAIL crashes_after_cases", out)
        self.assertEqual(self.closing(out), "kernel: 2 passed, 2 failed, 1 skipped")

    def test_a_program_that_did_not_finish_fails(self):
        self.share.program("ran", 0, xml(case("A")))
        self.share.planned.append("never_finished /bin/never_finished")
        rc, out = self.share.summarize()
        self.assertEqual(rc, 1, out)
        self.assertIn("[kernel] FAIL never_finished: did not finish", out)


if __name__ == "__main__":
    unittest.main()
