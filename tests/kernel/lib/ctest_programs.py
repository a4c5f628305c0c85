#!/usr/bin/env python3
"""Prints the gtest programs (one path per line, each once) of the ctest tests with a label.

usage: ctest_programs.py BUILD_DIR LABEL_REGEX

ctest lists gtest cases one by one (gtest_discover_tests: "PROGRAM --gtest_filter=CASE ..."), or a
unit program as one test ("PROGRAM --gtest_brief=1", toolchain/cmake/HubrtTargets.cmake); the
kernel tier runs each program once with all its cases, so only the distinct programs matter.
Tests that are not gtest cases (e.g. "cmake -P script") depend on their ctest working directory
and often write into the build folder, which is read-only in the guest: they are left out, and
named on stderr.
"""
import json
import subprocess
import sys


def main() -> int:
    build, label = sys.argv[1], sys.argv[2]
    listing = subprocess.run(
        ["ctest", "--test-dir", build, "--label-regex", label, "--show-only=json-v1"],
        check=True, capture_output=True, text=True)
    programs = []
    for test in json.loads(listing.stdout).get("tests", []):
        command = test.get("command") or []
        if not any(arg.startswith(("--gtest_filter=", "--gtest_brief=")) for arg in command[1:]):
            print(f"not a gtest case, left out: {test.get('name')}", file=sys.stderr)
            continue
        if command[0] not in programs:
            programs.append(command[0])
    print("\n".join(programs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
