#!/usr/bin/python3
"""What an earlier stop would have cost: for each platen test recorded in calibration ledgers,
whether its stress, after falling under a fraction f of its running peak, ever rose above that
peak again (a later, higher peak that a test stopped at f would have missed), and where a test
stopped at f would have ended against where it did.

    /usr/bin/python3 scripts/post_peak_recovery.py out/calibration-joint/ledger.sqlite [...] [--fraction 0.9]

A ledger's `runs.curve` holds "platen_strain stress;..." pairs (compression and tension alike,
stress positive in the test's own sense). The start of a curve, before the stress first reaches
a third of its peak, is not a peak: the platen seating moves there. Each run key counts once.
Exit status 1 if any curve recovered, so a script can gate a stop fraction on it.
"""
import argparse
import sqlite3
import statistics
import sys


def parse_curve(text):
    points = []
    for pair in text.split(";"):
        fields = pair.split()
        if len(fields) == 2:
            points.append((float(fields[0]), float(fields[1])))
    return points


def recovery(points, fraction):
    """The largest stress after the curve first fell under fraction × its running peak, over
    that peak [-] (above 1: it rose to a higher peak; 0: it never fell so far)."""
    top = max(s for _, s in points)
    running, dipped, highest = 0.0, False, 0.0
    for _, stress in points:
        if dipped:
            highest = max(highest, stress / running)
        if stress > running and not dipped:
            running = stress
        elif running > top / 3.0 and stress < fraction * running:
            dipped = True
    return highest


def end_ratio(points, fraction):
    """Platen strain where a test stopped at fraction × its peak would end, over its last strain."""
    peak = max(range(len(points)), key=lambda i: points[i][1])
    limit = fraction * points[peak][1]
    end = next((e for e, s in points[peak:] if s < limit), points[-1][0])
    return end / points[-1][0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("ledgers", nargs="+", help="calibration ledgers (ledger.sqlite)")
    parser.add_argument("--fraction", type=float, default=0.9, help="the stop fraction to check, in (0, 1)")
    args = parser.parse_args()
    if not 0.0 < args.fraction < 1.0:
        sys.exit(f"--fraction {args.fraction}: expected a number in (0, 1)")
    seen, recovered, ratios, highest = set(), [], [], 0.0
    for path in args.ledgers:
        try:
            rows = sqlite3.connect(f"file:{path}?mode=ro", uri=True).execute(
                "select run_key, sand, seed, strain_at_peak, curve from runs where status = 'ok'").fetchall()
        except sqlite3.Error as e:
            sys.exit(f"{path}: not a calibration ledger ({e})")
        for key, sand, seed, strain_at_peak, curve in rows:
            points = parse_curve(curve or "")
            if key in seen or len(points) < 2 or max(s for _, s in points) <= 0.0:
                continue
            seen.add(key)
            rise = recovery(points, args.fraction)
            highest = max(highest, rise)
            if rise > 1.0:
                recovered.append(f"{path}: {sand} seed {seed} (run {key}) rose to {rise:.4f} x its earlier peak")
            ratios.append(end_ratio(points, args.fraction))
    if not ratios:
        sys.exit("no curves in " + ", ".join(args.ledgers))
    print(f"{len(ratios)} curves; {len(recovered)} rose above their peak after falling under {args.fraction} x it")
    for line in recovered:
        print("  " + line)
    if highest > 0.0:
        print(f"after falling under it, the highest any curve came back to: {highest:.3f} x its peak")
    print(f"a stop at {args.fraction} x the peak ends at {statistics.median(ratios):.3f} x the recorded end strain "
          f"(median; {min(ratios):.3f}-{max(ratios):.3f})")
    return 1 if recovered else 0


if __name__ == "__main__":
    sys.exit(main())
