#!/usr/bin/python3
"""Generate the REPRESENTATIVE cube exports of the study dataset (lab_data/datasets/study).

The study ("A Study of the Influence of Particle Gradation in Bonded Assemblies") tested 27
cubes with the pre-blended sand (3 batches of 9) and 12 with the Van Buren sand, but its text
does not publish the Table 4 values or the Figure 4 curves. These files are therefore
REPRESENTATIVE: synthetic, generated here from a stated law, obeying what the study does say
(both sands well above the 12.4 MPa ASTM C270 Type S minimum; the pre-blended mortar clearly
stronger and peaking at a lower strain than the Van Buren mortar; 50-mm cubes; an MTS frame
with an extensometer; loading 900-1800 N/s). They are NOT measurements.

Stress-strain law (extensometer strain eps, compression positive):
  ascending, eps <= eps_c:   sigma = f_c * n*x / (n - 1 + x**n),       x = eps/eps_c  (Popovics 1973)
  descending, eps > eps_c:   sigma = f_c * n*x / (n - 1 + x**(n*k))    (Thorenfeldt et al. 1987 form)
  n is solved per cube so that the ASTM C469 chord modulus of the law (S1 at 50 microstrain,
  S2 at 0.40 f_c) equals the cube's target chord modulus E_ch; the initial tangent modulus is
  E0 = n/(n-1) * f_c/eps_c.

Per-sand means (coefficient of variation), drawn as batch factor x within-batch factor for f_c;
each sand's draws are then rescaled so that their sample means equal the stated means exactly
(the scatter stays random):
  pre-blended  f_c 21.0 MPa (batch 6.0 %, within 5.0 %, total ~8 %), eps_c 0.0030 (7 %),
               E_ch 12 000 MPa (6 %), post-peak k = 1.6
  Van Buren    f_c 17.5 MPa (batch 6.5 %, within 6.0 %, total ~9 %), eps_c 0.0037 (7 %),
               E_ch 10 000 MPa (6 %), post-peak k = 1.5
  Van Buren: 12 cubes = batch VB1 of 9 + batch VB2 of 3 (assumption; the study says 9 per batch).

Load frame (what the crosshead sees), stroke control at a constant rate:
  crosshead u = gap + 1.10*eps*h + F/k_m + d_s*(1 - exp(-F_max/F_s))
  gap U(0.02, 0.05) mm travelled before contact (load ~ 0); machine stiffness k_m = 500 kN/mm;
  irreversible platen seating d_s U(0.04, 0.09) mm with F_s U(1.5, 3.0) kN; end-zone factor 1.10.
  The stroke rate is set so that the mean load rate between 10 % and 50 % of peak is U(1100, 1600)
  N/s. Sampling 6 Hz; the test stops when the load falls below 55 % of peak.
Noise: load N(0, 12 N), extensometer N(0, 1.5e-6), crosshead N(0, 0.8 um). Cube edges 50 +- 0.3 mm,
height 50 +- 0.4 mm (written in the file header).
Export: MTS TestSuite CSV: UTF-8 BOM, CRLF, quoted "Key: value" lines, two blank lines, quoted names
with trailing spaces, a units row (sec, mm, kN, mm/mm), machine coordinates (compression negative).

Deterministic: seed 20160314. Run:  /usr/bin/python3 lab_data/tools/generate_representative_cubes.py
(writes lab_data/datasets/study/cubes/*.csv and generator_truth.csv; stdlib only).
"""

import math
import os
import random
import sys

SEED = 20160314
SAMPLE_HZ = 6.0
MACHINE_STIFFNESS_N_PER_MM = 500e3
END_ZONE_FACTOR = 1.10
CHORD_LOWER_STRAIN = 50e-6
STOP_FRACTION = 0.55
NOISE_LOAD_N = 12.0
NOISE_STRAIN = 1.5e-6
NOISE_CROSSHEAD_MM = 0.8e-3

SANDS = [
    dict(name="pre-blended", batches=[("PB1", 9, "3/14/2016"), ("PB2", 9, "3/15/2016"), ("PB3", 9, "3/16/2016")],
         fc=21.0, fc_cv_batch=0.060, fc_cv_within=0.050, eps_c=0.0030, eps_cv=0.07, e_ch=12000.0, e_cv=0.06, k_post=1.6),
    dict(name="van-buren", batches=[("VB1", 9, "4/11/2016"), ("VB2", 3, "4/12/2016")],
         fc=17.5, fc_cv_batch=0.065, fc_cv_within=0.060, eps_c=0.0037, eps_cv=0.07, e_ch=10000.0, e_cv=0.06, k_post=1.5),
]


def law(eps, fc, eps_c, n, k):
    """Stress [MPa] at strain eps (Popovics ascending, Thorenfeldt-type descending)."""
    if eps <= 0.0:
        return 0.0
    x = eps / eps_c
    power = n if x <= 1.0 else n * k
    return fc * n * x / (n - 1.0 + x ** power)


def bisect(f, lo, hi, iterations=200):
    flo = f(lo)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def chord_modulus(fc, eps_c, n):
    """ASTM C469 chord modulus [MPa] of the ascending law."""
    s2 = 0.40 * fc
    eps2 = bisect(lambda e: law(e, fc, eps_c, n, 1.0) - s2, 1e-9, eps_c)
    s1 = law(CHORD_LOWER_STRAIN, fc, eps_c, n, 1.0)
    return (s2 - s1) / (eps2 - CHORD_LOWER_STRAIN)


def solve_n(fc, eps_c, e_ch):
    """Shape exponent n > 1 whose chord modulus equals e_ch (chord decreases as n grows)."""
    if chord_modulus(fc, eps_c, 60.0) >= e_ch:
        raise ValueError("target chord modulus too low for this peak and strain")
    return bisect(lambda n: chord_modulus(fc, eps_c, n) - e_ch, 1.0001, 60.0)


def crosshead_mm(eps, load_n, fmax_n, p):
    seat = p["seat_mm"] * (1.0 - math.exp(-fmax_n / p["seat_force_n"]))
    return END_ZONE_FACTOR * eps * p["height_mm"] + load_n / MACHINE_STIFFNESS_N_PER_MM + seat


def contact_path(p):
    """Noise-free (eps, load, crosshead-after-contact) on a fine strain grid up to the stop."""
    area = p["width_mm"] * p["depth_mm"]
    path, fmax, eps = [], 0.0, 0.0
    step = p["eps_c"] / 4000.0
    while True:
        load = law(eps, p["fc"], p["eps_c"], p["n"], p["k"]) * area
        fmax = max(fmax, load)
        u = crosshead_mm(eps, load, fmax, p)
        if path and u <= path[-1][2]:
            break  # snap-back would need strain control: the test ends here
        path.append((eps, load, u))
        if eps > p["eps_c"] and load < STOP_FRACTION * p["fc"] * area:
            break
        eps += step
    return path


def interpolate(path, u):
    lo, hi = 0, len(path) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if path[mid][2] <= u:
            lo = mid
        else:
            hi = mid
    a, b = path[lo], path[hi]
    t = 0.0 if b[2] == a[2] else (u - a[2]) / (b[2] - a[2])
    return a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])


def stroke_rate(path, p, target_rate):
    """Stroke rate [mm/s] giving the target mean load rate between 10 % and 50 % of peak."""
    peak = max(row[1] for row in path)
    u10 = next(row[2] for row in path if row[1] >= 0.1 * peak)
    u50 = next(row[2] for row in path if row[1] >= 0.5 * peak)
    return (u50 - u10) / (0.4 * peak / target_rate)


def cube_parameters(rng, sand, batch_factor):
    """Raw draws of one cube; n is solved after the sand's draws are rescaled to its means."""
    return dict(fc=sand["fc"] * batch_factor * rng.gauss(1.0, sand["fc_cv_within"]),
                eps_c=sand["eps_c"] * rng.gauss(1.0, sand["eps_cv"]),
                e_ch=sand["e_ch"] * rng.gauss(1.0, sand["e_cv"]), k=sand["k_post"],
                width_mm=50.0 + rng.uniform(-0.3, 0.3), depth_mm=50.0 + rng.uniform(-0.3, 0.3),
                height_mm=50.0 + rng.uniform(-0.4, 0.4), gap_mm=rng.uniform(0.02, 0.05),
                seat_mm=rng.uniform(0.04, 0.09), seat_force_n=rng.uniform(1500.0, 3000.0),
                load_rate=rng.uniform(1100.0, 1600.0))


def rescale_to_means(cubes, sand):
    """Scales f_c, eps_c and E_ch of a sand's cubes so that their sample means are the stated means."""
    for key in ("fc", "eps_c", "e_ch"):
        factor = sand[key] / (sum(p[key] for _, _, _, p in cubes) / len(cubes))
        for _, _, _, p in cubes:
            p[key] *= factor
    for _, _, _, p in cubes:
        p["n"] = solve_n(p["fc"], p["eps_c"], p["e_ch"])


def samples(rng, p):
    path = contact_path(p)
    v = stroke_rate(path, p, p["load_rate"])
    end_u = p["gap_mm"] + path[-1][2]
    rows, t = [], 0.0
    while v * t <= end_u:
        u = v * t
        eps, load = (0.0, 0.0) if u < p["gap_mm"] else interpolate(path, u - p["gap_mm"])
        rows.append((t, u + rng.gauss(0.0, NOISE_CROSSHEAD_MM), load + rng.gauss(0.0, NOISE_LOAD_N),
                     eps + rng.gauss(0.0, NOISE_STRAIN)))
        t += 1.0 / SAMPLE_HZ
    return rows, v


def write_export(path, name, date, p, rows):
    lines = [
        '"File Path: C:\\MTS TestSuite\\Projects\\Mortar Cubes\\%s.csv"' % name,
        '"Test: ASTM C109 Mortar Cube - Extensometer"',
        '"Test Run: %s"' % name,
        '"Date: %s 10:%02d:%02d AM"' % (date, int(p["width_mm"] * 7) % 60, int(p["depth_mm"] * 11) % 60),
        '"Specimen Width: %.2f mm"' % p["width_mm"],
        '"Specimen Depth: %.2f mm"' % p["depth_mm"],
        '"Specimen Height: %.2f mm"' % p["height_mm"],
        '"Comment: REPRESENTATIVE synthetic export from lab_data/tools/generate_representative_cubes.py '
        '(seed %d); not a laboratory measurement"' % SEED,
        "", "",
        '"Running Time ","Axial Displacement ","Axial Force ","Axial Strain "',
        '"sec","mm","kN","mm/mm"',
    ]
    for t, u, load, eps in rows:  # machine coordinates: compression negative
        lines.append("%.3f,%.5f,%.4f,%.8f" % (t, -u, -load / 1000.0, -eps))
    with open(path, "w", encoding="utf-8-sig", newline="") as f:
        f.write("\r\n".join(lines) + "\r\n")


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "datasets", "study")
    out_dir = os.path.join(root, "cubes")
    os.makedirs(out_dir, exist_ok=True)
    rng = random.Random(SEED)
    truth = ["file,sand,batch,fc_mpa,eps_c,chord_modulus_mpa,n,initial_modulus_mpa,k_post,width_mm,depth_mm,"
             "height_mm,stroke_rate_mm_per_s,target_load_rate_n_per_s"]
    for sand in SANDS:
        cubes = []
        for batch, count, date in sand["batches"]:
            batch_factor = rng.gauss(1.0, sand["fc_cv_batch"])
            for i in range(1, count + 1):
                cubes.append((batch, "%s-C%02d" % (batch, i), date, cube_parameters(rng, sand, batch_factor)))
        rescale_to_means(cubes, sand)
        for batch, name, date, p in cubes:
            rows, v = samples(rng, p)
            write_export(os.path.join(out_dir, name + ".csv"), name, date, p, rows)
            e0 = p["n"] / (p["n"] - 1.0) * p["fc"] / p["eps_c"]
            truth.append("cubes/%s.csv,%s,%s,%.6f,%.8f,%.4f,%.6f,%.4f,%.3f,%.2f,%.2f,%.2f,%.8f,%.2f" % (
                name, sand["name"], batch, p["fc"], p["eps_c"], p["e_ch"], p["n"], e0, p["k"],
                p["width_mm"], p["depth_mm"], p["height_mm"], v, p["load_rate"]))
    with open(os.path.join(root, "generator_truth.csv"), "w", encoding="utf-8", newline="") as f:
        f.write("# REPRESENTATIVE: law parameters of each generated cube (the oracle for tests); not measurements\n")
        f.write("\n".join(truth) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
