#!/usr/bin/env python3
"""Fails when a test run skipped anything: CI's check that the README's test command, in a fresh
clone with nothing beside it, runs every test.

    scripts/check_no_skips.py build/ctest-junit.xml

The file is what `ctest --output-junit` wrote. A ctest test counts as skipped when its testcase
has a <skipped> element or a status other than "run" (GoogleTest's GTEST_SKIP, a test's skip
exit code or skip message, a test that did not run) and other than "disabled" (a GoogleTest
DISABLED_ helper, off by design, is not a skip); the pytest suite inside ctest (python_tests)
counts its own skips, which ctest does not see, from pytest's closing line in the test's output.
Exit status 0 when nothing was skipped, 1 otherwise (each skipped test named on stderr).
"""

import re
import sys
import xml.etree.ElementTree as ET


def skipped_tests(root: ET.Element) -> list[str]:
    out = []
    for case in root.iter("testcase"):
        name = case.get("name", "?")
        status = case.get("status", "run")
        if status != "disabled" and (case.find("skipped") is not None or
                                     status not in ("run", "fail")):
            out.append(f"{name} (status {status})")
        # pytest inside one ctest test: its closing line, e.g. "312 passed, 2 skipped in 41.2s".
        text = "".join(e.text or "" for e in case.iter("system-out"))
        for line in text.splitlines():
            m = re.search(r"\b(\d+) skipped\b", line)
            if m and int(m.group(1)) > 0 and re.search(r"\bin [\d.]+s\b", line):
                out.append(f"{name}: {line.strip()}")
    return out


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = ET.parse(sys.argv[1]).getroot()
    cases = sum(1 for _ in root.iter("testcase"))
    if cases == 0:
        print(f"{sys.argv[1]}: no test cases", file=sys.stderr)
        return 1
    skipped = skipped_tests(root)
    for s in skipped:
        print(f"skipped: {s}", file=sys.stderr)
    if skipped:
        print(f"{len(skipped)} of {cases} tests skipped (a fresh clone must run them all)",
              file=sys.stderr)
        return 1
    print(f"{cases} tests, none skipped")
    return 0


if __name__ == "__main__":
    sys.exit(main())
