#!/usr/bin/env python3
"""Summarises a kernel-tier run from what the guest wrote to the share.

usage: summarize.py SHARE_DIR SERIAL_LOG

Reads SHARE_DIR/tests.list (what should have run), results/status ("NAME EXIT_STATUS SECONDS" per
finished program), results/NAME.xml (gtest) and results/NAME.log (the program's output). Prints a
line per program (PASS, SKIP when every case it has skipped, FAIL), the guest's output of every
failing one, and a closing "kernel: N passed, N failed, N skipped" counted in gtest cases.

A skipped case is counted as skipped, never as passed: GTEST_SKIP() (gtest XML result="skipped",
and a case that did not run, e.g. DISABLED_), and, for a program without gtest XML, gtest's own
closing lines in its output ("[  SKIPPED ] N tests") or exit status 77 (the skip status of ctest's
SKIP_RETURN_CODE and of automake; a program that is not gtest skips with it). Without either, a
program counts as one case. Exit status: 0 when every program ran and none failed, 1 otherwise.
"""
import pathlib
import re
import sys
import xml.etree.ElementTree as ElementTree

# Exit status of a program that skipped as a whole (ctest SKIP_RETURN_CODE, automake).
SKIP_EXIT_STATUS = 77

LOG_HEAD_LINES = 80
LOG_TAIL_LINES = 320


def gtest_counts(xml_path: pathlib.Path):
    """(passed, failed, skipped, names of failed cases) from a gtest XML report, or None."""
    try:
        root = ElementTree.parse(xml_path).getroot()
    except (OSError, ElementTree.ParseError):
        return None
    passed = failed = skipped = 0
    failed_names = []
    for case in root.iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
            failed_names.append(f"{case.get('classname')}.{case.get('name')}")
        elif case.find("skipped") is not None or case.get("result") == "skipped":
            skipped += 1
        elif case.get("status") == "run":
            passed += 1
        else:
            skipped += 1  # status="notrun": a disabled case did not pass either
    return passed, failed, skipped, failed_names


# gtest's closing lines: "[  PASSED  ] 3 tests.", "[  SKIPPED ] 1 test, listed below:",
# "[  FAILED  ] 2 tests, listed below:".
GTEST_TOTAL = re.compile(r"^\[  (PASSED|SKIPPED|FAILED)  ?\] (\d+) tests?[.,]")


def gtest_log_counts(log_path: pathlib.Path):
    """(passed, failed, skipped) from gtest's closing lines in a program's output, or None."""
    try:
        lines = log_path.read_text(errors="replace").splitlines()
    except OSError:
        return None
    totals = {}
    for line in lines:
        match = GTEST_TOTAL.match(line)
        if match:
            totals[match.group(1)] = int(match.group(2))
    if not totals:
        return None
    return totals.get("PASSED", 0), totals.get("FAILED", 0), totals.get("SKIPPED", 0)


def program_counts(results: pathlib.Path, name: str, rc: int):
    """(passed, failed, skipped, names of failed cases, how counted) for one finished program."""
    counts = gtest_counts(results / f"{name}.xml")
    if counts is not None:
        return (*counts, "gtest report")
    from_log = gtest_log_counts(results / f"{name}.log")
    if from_log is not None:
        return (*from_log, [], "no gtest report, gtest output")
    if rc == SKIP_EXIT_STATUS:
        return 0, 0, 1, [], "no gtest report, skip status"
    return (1, 0, 0, [], "no gtest report") if rc == 0 else (0, 1, 0, [], "no gtest report")


def show_log(name: str, log: pathlib.Path) -> None:
    print(f"---------- guest output of {name} ({log}) ----------")
    try:
        lines = log.read_text(errors="replace").splitlines()
    except OSError:
        print("(no output file: the program did not start or the guest stopped first)")
        lines = []
    if len(lines) > LOG_HEAD_LINES + LOG_TAIL_LINES:
        skipped = len(lines) - LOG_HEAD_LINES - LOG_TAIL_LINES
        lines = lines[:LOG_HEAD_LINES] + [f"... ({skipped} lines left out) ..."] + lines[-LOG_TAIL_LINES:]
    for line in lines:
        print(f"  {line}")
    print(f"---------- end of {name} ----------")


def describe_status(rc: int) -> str:
    if rc == SKIP_EXIT_STATUS:
        return "skipped (exit status 77)"
    if rc == 124 or rc == 137:
        return "timed out"
    if rc == 125:
        return "guest set-up failed"
    if rc > 128:
        return f"killed by signal {rc - 128}"
    return f"exit status {rc}"


def main() -> int:
    share, serial_log = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    results = share / "results"
    planned = [line.split()[0] for line in (share / "tests.list").read_text().splitlines()
               if line.strip() and not line.startswith("#")]
    finished = {}
    status_file = results / "status"
    if status_file.exists():
        for line in status_file.read_text().splitlines():
            name, rc, seconds = line.split()
            finished[name] = (int(rc), float(seconds))

    total_passed = total_failed = total_skipped = 0
    failing = []
    for name in planned:
        if name not in finished:
            print(f"[kernel] FAIL {name}: did not finish (guest stopped or --timeout hit)")
            total_failed += 1
            failing.append(name)
            continue
        rc, seconds = finished[name]
        passed, failed, skipped, failed_names, source = program_counts(results, name, rc)
        ok = rc == 0 or (rc == SKIP_EXIT_STATUS and passed == 0 and failed == 0)
        if not ok and failed == 0:
            failed = 1  # crashed, sanitizer report or leak check after the cases: still a failure
        total_passed += passed
        total_failed += failed
        total_skipped += skipped
        if not ok:
            verdict = "FAIL"
        elif passed == 0 and skipped > 0:
            verdict = "SKIP"
        else:
            verdict = "PASS"
        detail = "" if rc == 0 else f", {describe_status(rc)}"
        print(f"[kernel] {verdict} {name}: {passed} passed, {failed} failed, {skipped} skipped ({source}) "
              f"in {seconds:.1f} s{detail}")
        for case in failed_names:
            print(f"[kernel]      failed: {case}")
        if not ok:
            failing.append(name)

    guest_exit = results / "guest-exit"
    guest_done = False
    if guest_exit.exists():
        guest_rc, _, message = guest_exit.read_text().strip().partition(" ")
        guest_done = guest_rc == "0"
        if not guest_done:
            print(f"[kernel] guest: {message}")
    if not guest_done:
        print(f"[kernel] the guest did not finish cleanly; last console lines ({serial_log}):")
        try:
            for line in serial_log.read_text(errors="replace").splitlines()[-40:]:
                print(f"  {line}")
        except OSError:
            print("  (no console log)")

    for name in failing:
        show_log(name, results / f"{name}.log")

    print(f"kernel: {total_passed} passed, {total_failed} failed, {total_skipped} skipped")
    return 0 if not failing and guest_done and planned else 1


if __name__ == "__main__":
    sys.exit(main())
