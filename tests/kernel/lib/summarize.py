#!/usr/bin/env python3
"""Summarises a kernel-tier run from what the guest wrote to the share.

usage: summarize.py SHARE_DIR SERIAL_LOG

Reads SHARE_DIR/tests.list (what should have run), results/status ("NAME EXIT_STATUS SECONDS" per
finished program), results/NAME.xml (gtest) and results/NAME.log (the program's output). Prints a
line per program, the guest's output of every failing one, and a closing
"kernel: N passed, N failed, N skipped" counted in gtest cases (a program without gtest XML counts
as one case). Exit status: 0 when every program ran and passed, 1 otherwise.
"""
import pathlib
import sys
import xml.etree.ElementTree as ElementTree

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
    return passed, failed, skipped, failed_names


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
        counts = gtest_counts(results / f"{name}.xml")
        if counts is None:
            passed, failed, skipped, failed_names = (1, 0, 0, []) if rc == 0 else (0, 1, 0, [])
            cases = "no gtest report"
        else:
            passed, failed, skipped, failed_names = counts
            if rc != 0 and failed == 0:
                failed = 1  # crashed, sanitizer report or leak check after the cases: still a failure
            cases = f"{passed} passed, {failed} failed, {skipped} skipped"
        total_passed += passed
        total_failed += failed
        total_skipped += skipped
        verdict = "PASS" if rc == 0 else "FAIL"
        detail = "" if rc == 0 else f", {describe_status(rc)}"
        print(f"[kernel] {verdict} {name}: {cases} in {seconds:.1f} s{detail}")
        for case in failed_names:
            print(f"[kernel]      failed: {case}")
        if rc != 0:
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
