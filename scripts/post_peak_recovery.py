#!/usr/bin/python3
"""What an earlier stop would have cost: for each platen test recorded in calibration ledgers,
whether its stress, after falling under a fraction f of its running peak, ever rose above that
peak again (a later, higher peak that a test stopped at f would have missed), and where a test
stopped at f would have ended against where it did. With --strain-ratio r, the same for the
strain stop (test.stop_strain_ratio): whether a curve rose above a running peak only after a
point whose strain had passed r x that peak's (where the stop would have ended it), and where
the two stops together would have ended it.

    /usr/bin/python3 scripts/post_peak_recovery.py out/calibration-joint/ledger.sqlite [...] [--fraction 0.9] [--strain-ratio 1.5]

A ledger's `runs.curve` holds "strain stress;..." pairs (the gauge strain the curve is reduced
on; compression and tension alike, stress positive in the test's own sense). The start of a
curve, before the stress first reaches a third of its peak, is not a peak: the platen seating
moves there. Each run key counts once. Exit status 1 if any curve recovered (or would have been
cut before a later maximum), so a script can gate a stop on it.
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


def strain_needed(points):
    """The smallest strain ratio a strain stop needs to see every later, higher maximum [-] (1:
    none came after a dip). A stop is checked at points that set no new maximum, so a later
    maximum is missed by a ratio under the strain of the last point before it over the strain
    of the running peak it exceeded."""
    top = max(s for _, s in points)
    running, at, pending, needed = 0.0, 0.0, 1.0, 1.0
    for strain, stress in points:
        if stress > running:
            if running > top / 3.0 and at > 0.0:
                needed = max(needed, pending)
            running, at, pending = stress, strain, 1.0
        elif at > 0.0:
            pending = max(pending, strain / at)
    return needed


def end_ratio(points, fraction, strain_ratio=None):
    """Platen strain where a test stopped at fraction × its running peak (and, with a strain
    ratio, at that × the running peak's strain) would end, over its last strain."""
    top = max(s for _, s in points)
    running, at = 0.0, 0.0
    for strain, stress in points:
        if stress > running:
            running, at = stress, strain
        elif running > top / 3.0 and (stress < fraction * running or (strain_ratio and strain > strain_ratio * at)):
            return strain / points[-1][0]
    return 1.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("ledgers", nargs="+", help="calibration ledgers (ledger.sqlite)")
    parser.add_argument("--fraction", type=float, default=0.9, help="the stop fraction to check, in (0, 1)")
    parser.add_argument("--strain-ratio", type=float, default=None, help="the strain stop to check, > 1")
    args = parser.parse_args()
    if not 0.0 < args.fraction < 1.0:
        sys.exit(f"--fraction {args.fraction}: expected a number in (0, 1)")
    if args.strain_ratio is not None and not args.strain_ratio > 1.0:
        sys.exit(f"--strain-ratio {args.strain_ratio}: expected a number > 1")
    seen, recovered, ratios, highest, needs = set(), [], [], 0.0, []
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
            needs.append(strain_needed(points))
            if args.strain_ratio and needs[-1] > args.strain_ratio:
                recovered.append(f"{path}: {sand} seed {seed} (run {key}) rose above a peak after {needs[-1]:.3f} x its strain")
            ratios.append(end_ratio(points, args.fraction, args.strain_ratio))
    if not ratios:
        sys.exit("no curves in " + ", ".join(args.ledgers))
    rule = f"{args.fraction} x the peak" + (f" or {args.strain_ratio} x its strain" if args.strain_ratio else "")
    print(f"{len(ratios)} curves; {len(recovered)} rose above a peak a stop at {rule} would have stopped at")
    for line in recovered:
        print("  " + line)
    if highest > 0.0:
        print(f"after falling under {args.fraction} x it, the highest any curve came back to: {highest:.3f} x its peak")
    print(f"seeing every later maximum needs a strain ratio of {max(needs):.3f} (the median curve {statistics.median(needs):.3f}): "
          "the strain of the last point before it over that of the peak it rose above")
    print(f"a stop at {rule} ends at {statistics.median(ratios):.3f} x the recorded end strain "
          f"(median; {min(ratios):.3f}-{max(ratios):.3f})")
    return 1 if recovered else 0


if __name__ == "__main__":
    sys.exit(main())
