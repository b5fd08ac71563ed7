#!/usr/bin/python3
"""Generate the tension-test fixtures of the lab-data tests (tests/lab_data/fixtures/tension/).

The study has no tensile tests, so these GENERATED exports exist only to test the readers and
reductions of splitting-tension (ASTM C496) and flexural (ASTM C348) exports against hand values:
each file's peak load is stated below, exactly, and the rest of its curve is a plain shape.

Curve: load rises linearly from 0 to the peak P over 40 samples (0.5 s apart), then drops to
20 % of P in 3 samples (the specimen breaks), crosshead displacement proportional to time.

Layouts (both read by lab_data/export_readers):
  MTS TestSuite CSV   UTF-8 BOM, CRLF, quoted "Key: value" lines, quoted names with trailing
                      spaces, units row (sec, mm, kN), machine coordinates (load negative).
  Instron Bluehill    "Category : Name,value,unit" lines, names row, "(sec),(mm),(lbf)" units
                      row, quoted numbers with thousands separators, load positive.

Files (P = peak load; hand values: T = 2P/(pi l d), Sf = 3PL/(2bd^2)):
  Sand A  A-S1  splitting  MTS kN        P = 100.0 kN, states d 100 mm, l 200 mm  -> T 3.18310 MPa
          A-S2  splitting  MTS kN        P =  95.0 kN, states d 100 mm, l 200 mm  -> T 3.02394 MPa
          A-S3  splitting  MTS kN        P = 105.0 kN, states nothing (dataset: 100 x 200 mm) -> T 3.34225 MPa
          A-F1  flexural   Bluehill lbf  P = 3000 N, states nothing (ASTM C348: 40 x 40, span 120 mm) -> Sf 8.4375 MPa
          A-F2  flexural   Bluehill lbf  P = 2800 N                                  -> Sf 7.8750 MPa
          A-F3  flexural   Bluehill lbf  P = 3200 N                                  -> Sf 9.0000 MPa
  Sand B  B-S1  splitting  Bluehill kN   P = 25.0 kN, states d 50 mm (dataset: l 100 mm) -> T 3.18310 MPa
          B-S2  splitting  Bluehill kN   P = 24.0 kN                                -> T 3.05577 MPa
          B-S3  splitting  Bluehill kN   P = 26.0 kN                                -> T 3.31042 MPa
          B-F1  flexural   MTS kN        P = 2.50 kN, states b 40, d 40, span 120 mm -> Sf 7.03125 MPa
          B-F2  flexural   MTS kN        P = 2.60 kN                                -> Sf 7.31250 MPa
          B-F3  flexural   MTS kN        P = 2.40 kN                                -> Sf 6.75000 MPa

Deterministic, stdlib only. Run:  /usr/bin/python3 lab_data/tools/generate_tension_fixtures.py
(writes tests/lab_data/fixtures/tension/*.csv).
"""

import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "..", "tests", "lab_data", "fixtures", "tension")
LBF = 4.4482216152605  # N per lbf
NOTE = "GENERATED fixture from lab_data/tools/generate_tension_fixtures.py - not a laboratory measurement"


def curve(peak_n):
    """(time s, crosshead mm, load N): linear rise to the peak over 40 samples, then the break."""
    rows = []
    for i in range(41):
        rows.append((0.5 * i, 0.005 * i, peak_n * i / 40))
    for k, f in enumerate((0.7, 0.4, 0.2), start=1):
        rows.append((0.5 * (40 + k), 0.005 * (40 + k), peak_n * f))
    return rows


def write_mts(name, test, peak_n, dims):
    lines = ['\ufeff"File Path: C:\\MTS TestSuite\\Projects\\Mortar Tension\\%s.csv"' % name,
             '"Test: %s"' % test, '"Test Run: %s"' % name, '"Date: 3/21/2016 9:02:11 AM"']
    lines += ['"%s: %s mm"' % (k, v) for k, v in dims]
    lines += ['"Comment: %s"' % NOTE, "", ""]
    lines += ['"Running Time ","Axial Displacement ","Axial Force "', '"sec","mm","kN"']
    for t, u, f in curve(peak_n):
        lines.append("%.1f,%.4f,%.5f" % (t, -u, -f / 1e3))  # machine coordinates: compression negative
    with open(os.path.join(OUT, name + ".csv"), "w", encoding="utf-8", newline="") as out:
        out.write("\r\n".join(lines) + "\r\n")


def write_bluehill(name, peak_n, dims, unit):
    lines = ['Text Inputs : Specimen label,"%s"' % name, "General : Start Date,03/21/2016 9:40 AM",
             'Text Inputs : Comment,"%s"' % NOTE]
    lines += ["Dimensions : %s,%s,mm" % (k, v) for k, v in dims]
    lines += ["", "Time,Extension,Load", "(sec),(mm),(%s)" % unit]
    for t, u, f in curve(peak_n):
        value = f / LBF if unit == "lbf" else f / 1e3
        lines.append('%.5f,%.5f,"%s"' % (t, u, format(value, ",.5f")))
    with open(os.path.join(OUT, name + ".csv"), "w", encoding="utf-8", newline="\n") as out:
        out.write("\n".join(lines) + "\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    cylinder = [("Specimen Diameter", "100.0"), ("Specimen Length", "200.0")]
    write_mts("A-S1", "ASTM C496 Splitting Tension", 100.0e3, cylinder)
    write_mts("A-S2", "ASTM C496 Splitting Tension", 95.0e3, cylinder)
    write_mts("A-S3", "ASTM C496 Splitting Tension", 105.0e3, [])
    for name, p in (("A-F1", 3000.0), ("A-F2", 2800.0), ("A-F3", 3200.0)):
        write_bluehill(name, p, [], "lbf")
    for name, p in (("B-S1", 25.0e3), ("B-S2", 24.0e3), ("B-S3", 26.0e3)):
        write_bluehill(name, p, [("Diameter", "50.00")], "kN")
    prism = [("Specimen Width", "40.0"), ("Specimen Depth", "40.0"), ("Specimen Length", "160.0"), ("Support Span", "120.0")]
    for name, p in (("B-F1", 2500.0), ("B-F2", 2600.0), ("B-F3", 2400.0)):
        write_mts(name, "ASTM C348 Flexure", p, prism)


if __name__ == "__main__":
    main()
