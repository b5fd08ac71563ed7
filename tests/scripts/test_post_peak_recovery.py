#!/usr/bin/python3
"""scripts/post_peak_recovery.py on a ledger with known curves: a curve that falls to 0.88 x its
peak and then rises to 1.02 x it is a recovery for a stop at 0.9 and not for one at 0.85 (it never
fell under 0.85 x the peak); its last point before that later maximum lies at 1.25 x the first
peak's strain, so a strain stop at 1.2 x misses it and one at 1.3 x does not; where each stop
would end; bad input refused.

    test_post_peak_recovery.py <path of scripts/post_peak_recovery.py>
"""
import sqlite3
import subprocess
import sys
import tempfile
from pathlib import Path


def curve(points):
    return ";".join(f"{e!r} {s!r}" for e, s in points)


# strain, stress [Pa]: seating (a dip under 0.9 x the first points that is no peak), a rise to
# 10 MPa at 2e-3, a fall to 8.8 MPa, a second, higher peak of 10.2 MPa, the fall to the stop.
RECOVERS = [(0.0, 0.0), (1e-4, 1e6), (2e-4, 0.5e6), (1e-3, 6e6), (2e-3, 10e6), (2.5e-3, 8.8e6), (3e-3, 10.2e6),
            (3.5e-3, 9.0e6), (4e-3, 8.4e6)]
# a plain curve: peak 10 MPa at 2e-3, under 0.9 x it at 3e-3, the recorded end (0.85 x) at 4e-3
PLAIN = [(0.0, 0.0), (1e-3, 6e6), (2e-3, 10e6), (2.5e-3, 9.5e6), (3e-3, 8.9e6), (4e-3, 8.4e6)]


def ledger(path, rows):
    db = sqlite3.connect(path)
    db.execute("CREATE TABLE runs(run_key TEXT PRIMARY KEY, sand TEXT, seed INTEGER, status TEXT, strain_at_peak REAL, curve TEXT)")
    db.executemany("INSERT INTO runs VALUES (?, ?, ?, 'ok', ?, ?)", rows)
    db.commit()
    db.close()


def run(script, *args):
    return subprocess.run([sys.executable, "-B", script, *map(str, args)], capture_output=True, text=True)


def expect(condition, message, result=None):
    if not condition:
        detail = f"\n--- stdout\n{result.stdout}--- stderr\n{result.stderr}" if result else ""
        sys.exit("FAILED: " + message + detail)


def main():
    script = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        both, plain = Path(tmp) / "both.sqlite", Path(tmp) / "plain.sqlite"
        ledger(both, [("a", "pre-blended", 1, 3e-3, curve(RECOVERS)), ("b", "Van Buren", 2, 2e-3, curve(PLAIN))])
        ledger(plain, [("b", "Van Buren", 2, 2e-3, curve(PLAIN))])

        r = run(script, both, "--fraction", "0.9")
        expect(r.returncode == 1, "a curve that rose to 1.02 x its peak after 0.88 x it: exit 1 at 0.9", r)
        expect("2 curves; 1 rose above" in r.stdout and "pre-blended seed 1 (run a) rose to 1.0200 x" in r.stdout,
               "the recovering curve named with its rise", r)
        r = run(script, both, "--fraction", "0.85")
        expect(r.returncode == 0 and "0 rose above" in r.stdout, "no curve fell under 0.85 x its peak before the end", r)
        # the plain curve stopped at 0.9 ends at 3e-3 of its 4e-3; a ledger listed twice counts once
        r = run(script, plain, plain, "--fraction", "0.9")
        expect(r.returncode == 0 and r.stdout.startswith("1 curves;"), "each run key once", r)
        expect("ends at 0.750 x the recorded end strain" in r.stdout, "the end of a stop at 0.9: 3e-3 / 4e-3", r)
        expect("came back to: 0.840 x its peak" in r.stdout, "the highest stress after the fall: 8.4 MPa", r)

        r = run(script, both, "--fraction", "0.85", "--strain-ratio", "1.2")
        expect(r.returncode == 1 and "pre-blended seed 1 (run a) rose above a peak after 1.250 x its strain" in r.stdout,
               "the later maximum at 3e-3 after the peak at 2e-3 and a point at 2.5e-3: missed by a strain stop at 1.2", r)
        r = run(script, both, "--fraction", "0.85", "--strain-ratio", "1.3")
        expect(r.returncode == 0 and "needs a strain ratio of 1.250" in r.stdout, "caught by one at 1.3", r)
        # the plain curve with a strain stop at 1.2: past 2.4e-3 at its point at 2.5e-3, before 0.9 x the peak
        r = run(script, plain, "--fraction", "0.9", "--strain-ratio", "1.2")
        expect(r.returncode == 0 and "ends at 0.625 x the recorded end strain" in r.stdout, "the end of the strain stop: 2.5e-3 / 4e-3", r)
        r = run(script, plain, "--strain-ratio", "1.0")
        expect(r.returncode != 0 and "--strain-ratio 1.0: expected a number > 1" in r.stderr, "a strain ratio of 1 refused", r)

        r = run(script, plain, "--fraction", "1.2")
        expect(r.returncode != 0 and "--fraction 1.2: expected a number in (0, 1)" in r.stderr, "a bad fraction refused", r)
        bad = Path(tmp) / "not_a_ledger.sqlite"
        bad.write_text("not sqlite")
        r = run(script, bad)
        expect(r.returncode != 0 and f"{bad}: not a calibration ledger" in r.stderr, "a file that is no ledger refused by name", r)
    print("post_peak_recovery.py: every check passed")


if __name__ == "__main__":
    main()
