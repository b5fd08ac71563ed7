#!/usr/bin/python3
"""Runs one command and checks its exact exit status and what it printed on which stream.

    expect_exit.py --exit N [--stdout RE]... [--stderr RE]... [--not-stdout RE]... [--not-stderr RE]...
                   [--empty-stdout] [--empty-stderr] [--stdout-json] [--fresh-cwd DIR] [--copy FILE]... [--no-new-files DIR]...
                   [--absent PATH]... -- COMMAND [ARG...]

--stdout/--stderr: a Python regex that must be found in that stream (re.search, multi-line;
one that starts with "-" is given as --stdout=RE); --not-*: one that must not be; --empty-*: the
stream must be empty; --stdout-json: stdout must be one JSON document and nothing else. --fresh-cwd: run in DIR,
emptied first (then --copy puts FILEs there). --no-new-files: no file under DIR (relative to the
working folder) may appear during the run. --absent: PATH must not exist after the run.
Exit status 0 when every check holds, 1 otherwise (with what differed).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys


def files_under(root):
    found = set()
    for folder, _, names in os.walk(root):
        for name in names:
            found.add(os.path.relpath(os.path.join(folder, name), root))
    return found


def main():
    argv = sys.argv[1:]
    if "--" not in argv:
        sys.exit("expect_exit.py: the command goes after --")
    cut = argv.index("--")
    parser = argparse.ArgumentParser(prog="expect_exit.py")
    parser.add_argument("--exit", type=int, required=True)
    for stream in ("stdout", "stderr"):
        parser.add_argument("--" + stream, action="append", default=[])
        parser.add_argument("--not-" + stream, action="append", default=[])
        parser.add_argument("--empty-" + stream, action="store_true")
    parser.add_argument("--stdout-json", action="store_true")
    parser.add_argument("--fresh-cwd")
    parser.add_argument("--copy", action="append", default=[])
    parser.add_argument("--no-new-files", action="append", default=[])
    parser.add_argument("--absent", action="append", default=[])
    parser.add_argument("--timeout", type=float, default=600.0)
    args = parser.parse_args(argv[:cut])
    command = argv[cut + 1:]
    if not command:
        sys.exit("expect_exit.py: no command after --")

    cwd = None
    if args.fresh_cwd:
        cwd = args.fresh_cwd
        shutil.rmtree(cwd, ignore_errors=True)
        os.makedirs(cwd)
        for f in args.copy:
            shutil.copy(f, cwd)
    here = cwd or os.getcwd()
    before = {d: files_under(os.path.join(here, d)) for d in args.no_new_files}

    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
    run = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, errors="replace",
                         timeout=args.timeout)
    out = {"stdout": run.stdout, "stderr": run.stderr}

    problems = []
    if run.returncode != args.exit:
        problems.append("exit status %d, expected %d" % (run.returncode, args.exit))
    for stream in ("stdout", "stderr"):
        for pattern in getattr(args, stream):
            if not re.search(pattern, out[stream], re.MULTILINE):
                problems.append("%s does not match %r" % (stream, pattern))
        for pattern in getattr(args, "not_" + stream):
            if re.search(pattern, out[stream], re.MULTILINE):
                problems.append("%s matches %r, which it must not" % (stream, pattern))
        if getattr(args, "empty_" + stream) and out[stream]:
            problems.append("%s is not empty" % stream)
    if args.stdout_json:
        try:
            json.loads(run.stdout)
        except ValueError as e:
            problems.append("stdout is not one JSON document: %s" % e)
    for d, old in before.items():
        new = sorted(files_under(os.path.join(here, d)) - old)
        if new:
            problems.append("new files under %s: %s" % (d, ", ".join(new[:10])))
    for path in args.absent:
        if os.path.exists(os.path.join(here, path)):
            problems.append("%s exists, it must not" % path)

    if problems:
        print("command: %s%s" % (" ".join(command), " (in %s)" % cwd if cwd else ""))
        for p in problems:
            print("FAILED: " + p)
        for stream in ("stdout", "stderr"):
            text = out[stream]
            print("---- %s (%d characters, the last 3000) ----\n%s" % (stream, len(text), text[-3000:]))
        return 1
    print("ok: %s -> exit %d" % (" ".join(command), run.returncode))
    return 0


if __name__ == "__main__":
    sys.exit(main())
