"""A calibration's run ledger as a table: one row per cube test, its parameters as columns.

    PYTHONPATH=build/python python3 examples/python/ledger_table.py out/calibration-joint/ledger.sqlite [CSV]

With pandas installed, pandas.DataFrame(ledger.table()) is the same table as a DataFrame.
"""
import csv
import sys

import gradem

ledger = gradem.Ledger(sys.argv[1])
print(f"{ledger.meta['problem'].splitlines()[0] if ledger.meta.get('problem') else ledger.path}: {len(ledger)} runs")
table = ledger.table()
parameters = sorted(set(table) - {"sequence", "sand", "seed", "status", "modulus_pa", "peak_pa", "strain_at_peak",
                                  "poisson", "particles", "bonds", "steps", "wall_seconds", "rank", "host"})
columns = ["sequence", "sand", "seed", "status"] + parameters + ["modulus_pa", "peak_pa", "strain_at_peak", "wall_seconds"]
print("  ".join(f"{c:>14s}" for c in columns))
for k in range(len(ledger)):
    print("  ".join(f"{table[c][k]:>14.6g}" if table[c].dtype.kind == "f" else f"{table[c][k]!s:>14s}" for c in columns))
if len(sys.argv) > 2:
    with open(sys.argv[2], "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        w.writerows(zip(*(table[c] for c in columns)))
    print(f"written: {sys.argv[2]}")
