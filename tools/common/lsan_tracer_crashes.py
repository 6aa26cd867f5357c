"""Prints, as one regular-expression alternation, the failed tests of a CTest JUnit report when
every one of them failed only by LeakSanitizer's tracer crashing at exit (tools/sanitize.sh);
exits 1, printing nothing, when any failure is of another kind or nothing failed.
    lsan_tracer_crashes.py REPORT.xml"""
import re
import sys
import xml.etree.ElementTree as ET

TRACER_CRASH = re.compile(r"Tracer caught signal \d+.*\n.*LeakSanitizer has encountered a fatal error")
# A sanitizer's finding, which no retry may hide.
FINDING = re.compile(r"ERROR: (AddressSanitizer|LeakSanitizer): |runtime error: ")


def failed_tests(report):
    for case in ET.parse(report).getroot().iter("testcase"):
        if case.get("status") == "fail" or case.find("failure") is not None:
            out = case.findtext("system-out") or ""
            yield case.get("name"), out


def main(report):
    names = []
    for name, out in failed_tests(report):
        if not TRACER_CRASH.search(out) or FINDING.search(out):
            return 1
        names.append(re.escape(name))
    if not names:
        return 1
    print("|".join(names))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
