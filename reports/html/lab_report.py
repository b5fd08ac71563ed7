"""report.html of `gradem lab`: gradation against the ASTM C144 band, the cubes' stress–strain
curves per sand, the spread of the reduced quantities, the tension specimens' strengths per sand
(when there are any), and the tables of lab_results.json.
Inputs: lab_results.json (required) and curves.csv (the curves; a figure says so if absent)."""

import math
import os

import numpy as np
from matplotlib.ticker import FixedFormatter, FixedLocator, NullLocator

from figures import message_panel, new_figure, sand_color, to_svg
from inputs import field, finite, read_csv, read_json, number, require
from page import Page, fixed, fmt, pct

WRITER = "gradem lab ... --out DIR"


def build(out_dir):
    path = require(out_dir, "lab_results.json", WRITER)
    lab = read_json(path)
    sands = field(lab, "sands", path, list)
    cubes = field(lab, "cubes", path, list)
    tensile = lab.get("tensile_tests") or []  # absent in results written before tension tests
    for k, s in enumerate(sands):
        field(s, "name", f"{path} (sands[{k}])", str)
    curves = read_curves(out_dir)

    counts = ", ".join(([f"{len(cubes)} cubes"] if cubes or not tensile else []) +
                       ([f"{len(tensile)} tension specimens"] if tensile else []))
    page = Page(f"gradem lab report: {lab.get('dataset') or 'lab data'}",
                f"{counts}, {len(sands)} sand(s); source {lab.get('source', '?')}; folder {os.path.abspath(out_dir)}")
    if lab.get("representative_data"):
        page.banner(lab.get("note") or "at least one input file says its data are representative (synthetic).")
    page.cards(headline(sands))

    page.section("Gradation", "Percent passing each sieve (the sieve analyses) against the ASTM C144 limits for natural sand.")
    page.figure(gradation_figure(sands), "Gradation curves and the ASTM C144 band",
                "Percent passing vs sieve opening (log scale); the grey band spans the C144 limits at the sieves that have them, "
                "red rings mark sieves outside them.")
    if any(s.get("gradation") for s in sands):
        page.table(*gradation_table(sands), caption="Gradation indices from the sieve analyses (D-values interpolated on the "
               "log-size curve; Cu = D60/D10, Cc = D30²/(D10·D60); USCS per ASTM D2487).",
                   text_columns=(0, 8, 9))
    for s in sands:
        violations = (s.get("gradation") or {}).get("c144_violations") or []
        if violations:
            page.notes([f"{s['name']}: C144 — {v}" for v in violations])

    comparisons = lab.get("comparisons") or []
    if cubes or not tensile:  # tension specimens alone: no cube sections
        page.section("Cube compression curves", "Each cube's stress–strain curve as read from its load-frame export.")
        page.figure(curves_figure(sands, cubes, curves), "Lab stress–strain curves per sand",
                    "Axial stress vs extensometer strain of every cube (thin lines, one colour per batch); dashed black: the "
                    "Popovics (1973) curve through the sand's mean chord modulus, peak stress and strain at peak.")

        page.section("Strength and stiffness", "The quantities calibration uses, cube by cube, with their means and spread.")
        page.figure(spread_figure(sands, cubes, lab.get("comparisons") or []), "Peak stress, chord modulus and strain at peak by sand",
                    "Dots: cubes (open: the cube ASTM C109's permissible range says to discard; it is still counted); bar and "
                    "whiskers: mean ± 1 sample standard deviation; p: Welch two-sided test between the first two sands.")
        page.table(*statistics_table(sands), caption="Per-sand statistics: sample standard deviation (n − 1), all cubes included.",
                   text_columns=(0, 1))
        if comparisons:
            page.table(*comparisons_table(comparisons), caption="Welch t-tests between the sands (mean difference a − b).",
                       text_columns=(0, 1, 2))
        range_rows, bad = c109_table(sands)
        if range_rows:
            page.table(["sand", "batch", "cubes", "mean [MPa]", "range [% of mean]", "permissible [%]", "verdict"], range_rows,
                       caption="ASTM C109 permissible range of cubes of one batch (highlighted: exceeded).", text_columns=(0, 1, 2, 6),
                       bad_rows=bad)
        page.section("All cubes")
        page.table(*cubes_table(cubes), caption="One row per cube (flags: what the reduction noticed; highlighted: flagged).",
                   text_columns=(0, 1, 2, 9), bad_rows=[i for i, c in enumerate(cubes) if c.get("flags")])
    if tensile:
        page.section("Tensile strength", "Splitting (ASTM C496) and flexural (ASTM C348) strengths of the tension specimens, and "
                     "the direct tensile strength they stand for (fib Model Code 2010 5.1.5.1), which calibration fits.")
        page.figure(tensile_figure(sands, tensile), "Tensile strength of the specimens, per sand",
                    "Dots: specimens (left: splitting T = 2P/(πld); middle: flexural Sf = 3PL/(2bd²); right: direct equivalent "
                    "α·strength, α_sp = 1.0, α_fl = 0.06h^0.7/(1 + 0.06h^0.7), both kinds pooled); box: quartiles and median; "
                    "black square and whiskers: mean ± 1 sample standard deviation.")
        page.table(*tensile_table(tensile), caption="One row per tension specimen (geometry from the export, the dataset or "
                   "ASTM C348; highlighted: flagged).", text_columns=(0, 1, 2, 3, 5, 9),
                   bad_rows=[i for i, t in enumerate(tensile) if t.get("flags")])
        conversions = [f"{s['name']}: {stat(s, 'tensile_strength_mpa').get('conversion')}" for s in sands
                       if stat(s, "tensile_strength_mpa").get("conversion")]
        if conversions:
            page.notes(conversions)
    if not cubes and tensile:
        page.table(*statistics_table(sands), caption="Per-sand statistics: sample standard deviation (n − 1).",
                   text_columns=(0, 1))
        if comparisons:
            page.table(*comparisons_table(comparisons), caption="Welch t-tests between the sands (mean difference a − b).",
                       text_columns=(0, 1, 2))
    definitions = lab.get("definitions") or {}
    if definitions:
        page.section("Definitions")
        page.notes([f"{k}: {v}" for k, v in definitions.items()])
    return page.render()


# ----------------------------------------------------------------------------- inputs

def read_curves(out_dir):
    """{file: (strain array, stress_mpa array)} from curves.csv, or None when there is none."""
    path = os.path.join(out_dir, "curves.csv")
    if not os.path.isfile(path):
        return None
    rows, _ = read_csv(path, ["file", "sand", "batch", "strain", "stress_mpa"])
    curves = {}
    for r in rows:
        strain, stress = curves.setdefault(r["file"], ([], []))
        strain.append(number(r, "strain", path))
        stress.append(number(r, "stress_mpa", path))
    return {f: (np.array(e), np.array(s)) for f, (e, s) in curves.items()}


def stat(s, key):
    return s.get(key) or {}


def popovics(e_mpa, peak_mpa, strain_peak, strains):
    """Popovics (1973): σ = σp·n·x/(n − 1 + xⁿ), x = ε/εp, n = E/(E − σp/εp); None if E ≤ σp/εp."""
    secant = peak_mpa / strain_peak
    if not (e_mpa > secant > 0):
        return None
    n = e_mpa / (e_mpa - secant)
    x = strains / strain_peak
    return peak_mpa * n * x / (n - 1.0 + x ** n)


# ----------------------------------------------------------------------------- headline

def headline(sands):
    items = []
    for s in sands:
        tensile = stat(s, "tensile_strength_mpa")
        if tensile:
            items.append((f"{s['name']}: direct tensile strength", f"{fixed(tensile.get('mean'), 2)}{spread(tensile.get('std'), 2)} MPa",
                          f"n = {tensile.get('n', '?')}, CV {pct(tensile.get('cv'), signed=False)} (fib MC2010)", ""))
            if not s.get("n"):
                continue  # no cubes: no compression cards
        peak, chord, eps = stat(s, "peak_stress_mpa"), stat(s, "chord_modulus_mpa"), stat(s, "strain_at_peak")
        items.append((f"{s['name']}: peak stress", f"{fixed(peak.get('mean'), 1)}{spread(peak.get('std'), 1)} MPa",
                      f"n = {s.get('n', '?')}, CV {pct(peak.get('cv'), signed=False)}", ""))
        items.append((f"{s['name']}: chord modulus",
                      f"{fixed(finite(chord.get('mean')) / 1e3, 2)}{spread(finite(chord.get('std')) / 1e3, 2)} GPa",
                      f"strain at peak {fixed(finite(eps.get('mean')) * 1e3, 2)}{spread(finite(eps.get('std')) * 1e3, 2)} ‰", ""))
        g = s.get("gradation")
        if g:
            ok = g.get("c144_conforms")
            failing = [c["sieve"] for c in g.get("c144_checks") or [] if not c.get("ok")]
            items.append((f"{s['name']}: ASTM C144", "conforms" if ok else "does not conform",
                          ("outside at " + ", ".join(failing)) if failing else f"{g.get('uscs', '')} {g.get('uscs_name', '')}",
                          "good" if ok else "bad"))
    return items


def spread(std, decimals):
    """' ± std', or nothing when there is no standard deviation (a single cube)."""
    return f" ± {fixed(std, decimals)}" if math.isfinite(finite(std)) else ""


# ----------------------------------------------------------------------------- figures

def gradation_figure(sands):
    fig, (ax,) = new_figure(1, width=10.0, height=4.6)
    graded = [(k, s) for k, s in enumerate(sands) if s.get("gradation")]
    if not graded:
        message_panel(ax, "no sieve analysis in these lab results (export files only)")
        ax.set_title("Gradation")
        return to_svg(fig)
    ax.set_xscale("log")  # first: setting the scale resets the tick locators chosen below
    band = {}
    for _, s in graded:
        for c in s["gradation"].get("c144_checks") or []:
            band[round(float(c["opening_mm"]), 4)] = (finite(c["min_pct"]), finite(c["max_pct"]), c.get("sieve", ""))
    if band:
        openings = sorted(band)
        lo = [band[o][0] for o in openings]
        hi = [band[o][1] for o in openings]
        ax.fill_between(openings, lo, hi, color="#c9ced6", alpha=0.6, lw=0, label="ASTM C144 limits")
        ax.plot(openings, lo, color="#8a919c", lw=0.8)
        ax.plot(openings, hi, color="#8a919c", lw=0.8)
        top = ax.secondary_xaxis("top")
        top.xaxis.set_major_locator(FixedLocator(openings))
        top.xaxis.set_major_formatter(FixedFormatter([band[o][2].replace("No. ", "#") for o in openings]))
        top.xaxis.set_minor_locator(NullLocator())
        top.tick_params(length=3, labelsize=8.5)
        top.set_xlabel("ASTM sieve", fontsize=9)
        ax.xaxis.set_major_locator(FixedLocator(openings))
        ax.xaxis.set_major_formatter(FixedFormatter([fmt(o, 3) for o in openings]))
        ax.xaxis.set_minor_locator(NullLocator())
    for k, s in graded:
        g = s["gradation"]
        size, passing = np.array(g["sieves_mm"], float), np.array(g["percent_passing"], float)
        keep = size > 0
        ax.plot(size[keep], passing[keep], "-o", color=sand_color(k), ms=4.5, lw=1.8,
                label=f"{s['name']} (Cu {fmt(g.get('cu'), 3)}, FM {fmt(g.get('fineness_modulus'), 3)})")
        bad = [c for c in g.get("c144_checks") or [] if not c.get("ok")]
        ax.plot([c["opening_mm"] for c in bad], [c["percent_passing"] for c in bad], "o", ms=10, mfc="none", mec="#b3261e",
                mew=1.6, label="outside C144" if k == graded[0][0] else None)
    ax.set_xlabel("sieve opening [mm] (log scale)")
    ax.set_ylabel("percent passing [%]")
    ax.set_ylim(-2, 102)
    ax.set_title("Gradation of the sands with the ASTM C144 band")
    ax.legend(loc="upper left")
    return to_svg(fig)


def curves_figure(sands, cubes, curves):
    fig, axes = new_figure(max(1, len(sands)), width=10.0, height=4.4, sharey=True)
    if curves is None:
        for ax in axes:
            message_panel(ax, "no curves.csv in this folder\n(written by gradem lab; re-run it to get the curves)")
        axes[0].set_title("Lab stress–strain curves")
        return to_svg(fig)
    for k, (ax, s) in enumerate(zip(axes, sands)):
        mine = [c for c in cubes if c.get("sand") == s["name"]]
        batches = sorted({c.get("batch", "") for c in mine})
        shades = batch_shades(sand_color(k), len(batches))
        e_max = 0.0
        for c in mine:
            if c.get("file") not in curves:
                continue
            strain, stress = curves[c["file"]]
            b = batches.index(c.get("batch", ""))
            ax.plot(strain * 1e3, stress, color=shades[b], lw=0.8, alpha=0.85,
                    label=c.get("batch") if c is next(x for x in mine if x.get("batch") == c.get("batch")) else None)
            e_max = max(e_max, float(np.nanmax(strain)) if strain.size else 0.0)
        peak, chord, eps = (finite(stat(s, q).get("mean")) for q in ("peak_stress_mpa", "chord_modulus_mpa", "strain_at_peak"))
        if all(math.isfinite(v) for v in (peak, chord, eps)):
            x = np.linspace(0, max(e_max, 1.5 * eps), 200)
            y = popovics(chord, peak, eps, x)
            if y is not None:
                ax.plot(x * 1e3, y, "--", color="black", lw=1.8, label="Popovics through the means")
            ax.plot([eps * 1e3], [peak], "kD", ms=5)
        ax.set_title(f"{s['name']} ({len(mine)} cubes)")
        ax.set_xlabel("axial strain ε [‰] (extensometer)")
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.legend(loc="lower right", fontsize=8)
    axes[0].set_ylabel("axial stress σ [MPa]")
    return to_svg(fig)


def batch_shades(color, n):
    """n shades of one colour, darker to lighter."""
    import matplotlib.colors as mc
    base = np.array(mc.to_rgb(color))
    return [tuple(base * (1 - t) + np.array([1, 1, 1]) * t) for t in np.linspace(0.0, 0.45, max(n, 1))]


def spread_figure(sands, cubes, comparisons):
    quantities = [("peak_stress_mpa", "peak stress [MPa]", 1.0, "Peak stress (C109)"),
                  ("chord_modulus_mpa", "chord modulus [GPa]", 1e-3, "Chord modulus (C469)"),
                  ("strain_at_peak", "strain at peak [‰]", 1e3, "Strain at peak")]
    fig, axes = new_figure(3, width=10.0, height=3.9)
    rng = np.random.default_rng(7)  # fixed jitter: the same page for the same data
    for ax, (key, label, scale, title) in zip(axes, quantities):
        for k, s in enumerate(sands):
            values = [(finite(c.get(key)) * scale, "c109_range_discarded" in (c.get("flags") or []))
                      for c in cubes if c.get("sand") == s["name"]]
            x = k + rng.uniform(-0.18, 0.18, len(values))
            color = sand_color(k)
            for xi, (v, flagged) in zip(x, values):
                ax.plot(xi, v, "o", ms=4.5, mfc="white" if flagged else color, mec=color, alpha=0.9)
            st = stat(s, key)
            m, sd = finite(st.get("mean")) * scale, finite(st.get("std")) * scale
            # One cube has no standard deviation (NaN): the mean alone.
            ax.errorbar([k + 0.36], [m], yerr=[sd] if math.isfinite(sd) else None, fmt="s", color="black", ms=6, capsize=5, lw=1.6)
        ax.set_xticks(range(len(sands)))
        ax.set_xticklabels([s["name"] for s in sands])
        ax.set_xlim(-0.6, len(sands) - 0.3)
        ax.set_ylabel(label)
        ax.set_title(title)
        ax.grid(axis="x", visible=False)
        test = next((c for c in comparisons if c.get("quantity") == key), None)
        if test is not None:
            p = finite(test.get("p_value"))
            ax.text(0.5, 0.98, "Welch p < 0.0001" if p < 1e-4 else f"Welch p = {fmt(p, 2)}", transform=ax.transAxes,
                    ha="center", va="top", fontsize=9, color="#333")
            ax.margins(y=0.18)
    return to_svg(fig)


TENSILE_STRIPS = [("splitting", "splitting\n(C496)", "o"), ("flexural", "flexural\n(C348)", "s"),
                  (None, "direct\nequivalent", "D")]


def tensile_figure(sands, tensile):
    """One panel per sand with tension specimens: strips of splitting, flexural and direct-equivalent strengths."""
    tested = [(k, s) for k, s in enumerate(sands) if any(t.get("sand") == s["name"] for t in tensile)]
    fig, axes = new_figure(max(1, len(tested)), width=10.0, height=4.2, sharey=True)
    rng = np.random.default_rng(11)  # fixed jitter: the same page for the same data
    for ax, (k, s) in zip(axes, tested):
        mine = [t for t in tensile if t.get("sand") == s["name"]]
        color = sand_color(k)
        for x, (kind, _, marker) in enumerate(TENSILE_STRIPS):
            key = "direct_equivalent_mpa" if kind is None else "strength_mpa"
            values = [finite(t.get(key)) for t in mine if kind is None or t.get("test") == kind]
            values = [v for v in values if math.isfinite(v)]
            if not values:
                continue
            ax.boxplot([values], positions=[x], widths=0.45, showfliers=False, patch_artist=True,
                       boxprops={"facecolor": "#eef1f5", "edgecolor": "#8a919c"}, medianprops={"color": "#5b6475"},
                       whiskerprops={"color": "#8a919c"}, capprops={"color": "#8a919c"})
            ax.plot(x + rng.uniform(-0.12, 0.12, len(values)), values, marker, ms=5, color=color, alpha=0.9, ls="none")
            m = float(np.mean(values))
            sd = float(np.std(values, ddof=1)) if len(values) > 1 else float("nan")
            ax.errorbar([x + 0.32], [m], yerr=[sd] if math.isfinite(sd) else None, fmt="s", color="black", ms=5, capsize=4, lw=1.4)
        ax.set_xticks(range(len(TENSILE_STRIPS)))
        ax.set_xticklabels([label for _, label, _ in TENSILE_STRIPS])
        ax.set_xlim(-0.6, len(TENSILE_STRIPS) - 0.3)
        ax.set_ylim(bottom=0)
        ax.grid(axis="x", visible=False)
        ax.set_title(f"{s['name']} ({len(mine)} specimens)")
    if not tested:
        message_panel(axes[0], "no tension specimens in these lab results")
    axes[0].set_ylabel("tensile strength [MPa]")
    return to_svg(fig)


# ----------------------------------------------------------------------------- tables

def tensile_table(tensile):
    headers = ["file", "sand", "batch", "test", "peak load [kN]", "geometry [mm]", "strength [MPa]", "α", "direct [MPa]", "flags"]
    rows = []
    for t in tensile:
        if t.get("test") == "splitting":
            geometry = f"d {fmt(t.get('diameter_mm'), 4)}, l {fmt(t.get('length_mm'), 4)}"
        else:
            geometry = f"{fmt(t.get('width_mm'), 4)} × {fmt(t.get('depth_mm'), 4)}, span {fmt(t.get('span_mm'), 4)}"
        rows.append([t.get("file", ""), t.get("sand", ""), t.get("batch", ""), t.get("test", ""),
                     fmt(finite(t.get("peak_load_n")) / 1e3, 4), f"{geometry} ({t.get('geometry_source', '')})",
                     fmt(t.get("strength_mpa"), 4), fmt(t.get("conversion_factor"), 4), fmt(t.get("direct_equivalent_mpa"), 4),
                     "; ".join(t.get("flags") or [])])
    return headers, rows


def gradation_table(sands):
    headers = ["sand", "D10 [mm]", "D30 [mm]", "D50 [mm]", "D60 [mm]", "Cu", "Cc", "fineness modulus", "USCS", "C144"]
    rows = []
    for s in sands:
        g = s.get("gradation")
        if not g:
            continue
        rows.append([s["name"], fmt(g.get("d10_mm"), 3), fmt(g.get("d30_mm"), 3), fmt(g.get("d50_mm"), 3), fmt(g.get("d60_mm"), 3),
                     fmt(g.get("cu"), 3), fmt(g.get("cc"), 3), fmt(g.get("fineness_modulus"), 3),
                     f"{g.get('uscs', '')} ({g.get('uscs_name', '')})", "conforms" if g.get("c144_conforms") else "does not conform"])
    return headers, rows


def statistics_table(sands):
    quantities = [("peak_stress_mpa", "peak stress [MPa]", 1.0, 3), ("chord_modulus_mpa", "chord modulus [MPa]", 1.0, 4),
                  ("tangent_modulus_mpa", "tangent modulus [MPa]", 1.0, 4), ("strain_at_peak", "strain at peak [‰]", 1e3, 3),
                  ("strain_at_peak_crosshead", "crosshead strain at peak [‰]", 1e3, 3),
                  ("splitting_tensile_strength_mpa", "splitting tensile strength [MPa]", 1.0, 3),
                  ("flexural_strength_mpa", "flexural strength [MPa]", 1.0, 3),
                  ("tensile_strength_mpa", "direct tensile strength [MPa]", 1.0, 3)]
    headers = ["sand", "quantity", "n", "mean", "std", "CV", "min", "max"]
    rows = []
    for s in sands:
        for key, label, scale, digits in quantities:
            st = stat(s, key)
            if not st or not st.get("n"):
                continue
            rows.append([s["name"], label, st.get("n", ""), fmt(finite(st.get("mean")) * scale, digits),
                         fmt(finite(st.get("std")) * scale, 3), pct(st.get("cv"), signed=False), fmt(finite(st.get("min")) * scale, digits),
                         fmt(finite(st.get("max")) * scale, digits)])
    return headers, rows


def comparisons_table(comparisons):
    headers = ["quantity", "sand a", "sand b", "n a", "n b", "mean difference", "Welch t", "dof", "p", "Hedges g"]
    names = {"peak_stress_mpa": "peak stress [MPa]", "strain_at_peak": "strain at peak [-]",
             "chord_modulus_mpa": "chord modulus [MPa]", "tangent_modulus_mpa": "tangent modulus [MPa]",
             "tensile_strength_mpa": "direct tensile strength [MPa]"}
    rows = [[names.get(c.get("quantity"), c.get("quantity")), c.get("sand_a"), c.get("sand_b"), c.get("n_a"), c.get("n_b"), fmt(c.get("mean_difference"), 4),
             fmt(c.get("welch_t"), 3), fmt(c.get("dof"), 3), "< 0.0001" if finite(c.get("p_value")) < 1e-4 else fmt(c.get("p_value"), 2),
             fmt(c.get("hedges_g"), 3)] for c in comparisons]
    return headers, rows


def c109_table(sands):
    rows, bad = [], []
    for s in sands:
        for r in s.get("c109_range_checks") or []:
            if not r.get("ok"):
                bad.append(len(rows))
            verdict = "within" if r.get("ok") else f"exceeded: discard {os.path.basename(r.get('discarded') or '?')}"
            if r.get("retest_required"):
                verdict += "; retest required"
            rows.append([s["name"], r.get("batch", ""), ", ".join(os.path.basename(f) for f in r.get("files") or []),
                         fmt(r.get("mean_mpa"), 4), fmt(r.get("range_pct"), 3), fmt(r.get("permissible_pct"), 3), verdict])
    return rows, bad


def cubes_table(cubes):
    headers = ["file", "sand", "batch", "peak [MPa]", "strain at peak [‰]", "chord modulus [MPa]", "tangent modulus [MPa]",
               "load rate [N/s]", "Popovics n", "flags"]
    rows = [[c.get("file", ""), c.get("sand", ""), c.get("batch", ""), fmt(c.get("peak_stress_mpa"), 4),
             fmt(finite(c.get("strain_at_peak")) * 1e3, 3), fmt(c.get("chord_modulus_mpa"), 5), fmt(c.get("tangent_modulus_mpa"), 5),
             fmt(c.get("load_rate_n_per_s"), 4), fmt((c.get("popovics") or {}).get("n"), 3), "; ".join(c.get("flags") or [])]
            for c in cubes]
    return headers, rows
