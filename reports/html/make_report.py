"""gradem's HTML report generator: makes report.html of a gradem command's output folder.

    /usr/bin/python3 make_report.py KIND OUT_DIR [TEMP_FILE]

KIND is a report kind (reports/html_report.hpp, GRADEM_REPORT_KINDS): its page is made by the
module KIND_report.py beside this file (build(out_dir) -> the page's text); OUT_DIR holds that
command's CSV/JSON outputs. The page is
written to TEMP_FILE (the caller renames it into place: reports/html_report.cpp) or, without
TEMP_FILE, to OUT_DIR/report.html through a temporary file and a rename. The `gradem` binary
carries these files (embedded at build time) and runs them this way at the end of each command.

Exit status: 0 written; 2 an output file is missing or not as expected (the message names the
file, line and what was expected); 3 matplotlib or numpy is missing; 1 usage.
"""

import importlib
import os
import sys

EXIT_BAD_INPUT = 2
EXIT_NO_MATPLOTLIB = 3
HERE = os.path.dirname(os.path.abspath(__file__))


def kinds():
    """The report kinds: every KIND_report.py beside this file."""
    return sorted(f[:-len("_report.py")] for f in os.listdir(HERE) if f.endswith("_report.py"))


def main(argv):
    if len(argv) not in (3, 4) or argv[1] not in kinds():
        print(f"usage: make_report.py {{{'|'.join(kinds())}}} OUT_DIR [TEMP_FILE]", file=sys.stderr)
        return 1
    kind, out_dir = argv[1], argv[2]
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError as e:
        print(f"python3 cannot import {e.name} ({sys.executable})", file=sys.stderr)
        return EXIT_NO_MATPLOTLIB
    sys.path.insert(0, HERE)
    from inputs import InputError
    try:
        text = importlib.import_module(f"{kind}_report").build(out_dir)
    except InputError as e:
        print(f"{e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    target = argv[3] if len(argv) == 4 else os.path.join(out_dir, "report.html")
    temp = target if len(argv) == 4 else f"{target}.tmp.{os.getpid()}"
    with open(temp, "w", encoding="utf-8") as f:
        f.write(text)
    if temp != target:
        os.replace(temp, target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
