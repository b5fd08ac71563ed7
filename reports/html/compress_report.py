"""report.html of `gradem compress`: the virtual ASTM C109 cube test — stress–strain (platen and
gauge), bonds broken by mode against strain, lateral and volumetric strain, and where and how the
bonds broke — with the reduced quantities (macro.json). Inputs: macro.json, load_curve.csv,
cracks.csv. The cube test uses no lab cube export, so this page has no REPRESENTATIVE banner."""

import math
import os

import numpy as np

from figures import MODE_COLORS, message_panel, new_figure, to_svg
from inputs import field, finite, number, read_csv, read_json, require
from page import Page, fixed, fmt, pct

WRITER = "gradem compress"
CURVE_COLUMNS = ["platen_strain", "gauge_strain", "lateral_strain", "stress_mpa", "stress_top_mpa", "stress_bottom_mpa",
                 "broken_tension", "broken_shear"]


def build(out_dir):
    macro_path = require(out_dir, "macro.json", WRITER)
    macro = read_json(macro_path)
    field(macro, "peak_stress_mpa", macro_path)
    curve = read_columns(require(out_dir, "load_curve.csv", WRITER), CURVE_COLUMNS)
    cracks_path = require(out_dir, "cracks.csv", WRITER)
    crack_rows, _ = read_csv(cracks_path, ["platen_strain", "x_m", "y_m", "z_m", "nx", "ny", "nz", "mode"])
    cracks = [{"strain": number(r, "platen_strain", cracks_path), "x": number(r, "x_m", cracks_path),
               "y": number(r, "y_m", cracks_path), "z": number(r, "z_m", cracks_path), "nz": number(r, "nz", cracks_path),
               "mode": r["mode"]} for r in crack_rows]

    specimen, run = macro.get("specimen") or {}, macro.get("run") or {}
    page = Page(f"gradem cube test report: {os.path.basename(str(macro.get('config', '?')))}",
                f"{specimen.get('particles', '?')} grains of {specimen.get('sand', '?')}, {run.get('bonds', '?')} bonds, "
                f"edge {fmt(specimen.get('edge_mm'), 3)} mm; folder {os.path.abspath(out_dir)}")
    page.cards(headline(macro))
    if macro.get("warnings"):
        page.notes([f"warning: {w}" for w in macro["warnings"]])

    page.section("Load curve")
    page.figure(stress_figure(curve, macro), "Stress–strain of the virtual cube test",
                "Axial stress (mean of both platens) against platen strain (platen displacement / height) and against the "
                "gauge strain of the virtual extensometer (central slabs, as a clip-on gauge); thin: top and bottom platens; "
                "red: the ASTM C469 chord from 50 µε to 40 % of the peak.")
    page.figure(cracks_figure(curve, macro), "Broken bonds by mode against strain",
                "Cumulative number of parallel bonds broken in tension and in shear against platen strain; grey dashed: "
                "axial stress (right axis); vertical line: the peak.")
    page.figure(lateral_figure(curve, macro), "Lateral and volumetric strain",
                "Lateral strain (expansion positive, mean across x and y of the central gauges) and volumetric strain "
                "εv = εa − 2εl (compression positive) against the axial gauge strain; dashed: Poisson's ratio (ASTM C469) slope.")
    page.figure(crack_map_figure(cracks, macro), "Where and how the bonds broke",
                "Left: positions of the broken bonds projected on the x–z plane (loading along z), by mode. Right: angle between "
                "each broken bond's normal and the loading axis (0°: normal along the load, 90°: axial splitting).")
    page.section("Reduced quantities and run")
    page.table(["quantity", "value"], macro_rows(macro), caption="As `gradem lab` reduces a lab curve (lab_data/curve_reduction.hpp): "
               "the same definitions for the simulation and the lab.", text_columns=(0,))
    material = (macro.get("material") or {}).get("display") or {}
    if material:
        page.table(["[material] key", "value"], [[k, fmt(v, 4)] for k, v in material.items()],
                   caption="The material of this run, in the config's keys and units.", text_columns=(0,))
    page.table(["run", "value"], run_rows(macro), text_columns=(0,))
    return page.render()


# ----------------------------------------------------------------------------- inputs

def read_columns(path, columns):
    rows, _ = read_csv(path, columns)
    return {c: np.array([number(r, c, path) for r in rows]) for c in columns}


# ----------------------------------------------------------------------------- headline

def headline(macro):
    broken = macro.get("broken_bonds") or {}
    run = macro.get("run") or {}
    return [("peak stress", f"{fixed(macro.get('peak_stress_mpa'), 2)} MPa", "C109: largest stress sample", ""),
            ("strain at peak", f"{fixed(finite(macro.get('strain_at_peak')) * 1e3, 2)} ‰",
             f"gauge; platen {fixed(finite(macro.get('strain_at_peak_platen')) * 1e3, 2)} ‰", ""),
            ("chord modulus", f"{fixed(finite(macro.get('chord_modulus_mpa')) / 1e3, 2)} GPa", "ASTM C469, gauge strain", ""),
            ("Poisson's ratio", fixed(macro.get("poisson_ratio"), 3), "ASTM C469", ""),
            ("broken bonds", f"{broken.get('total', '?')}", f"{broken.get('tension', '?')} tension, {broken.get('shear', '?')} shear "
             f"of {run.get('bonds', '?')}", ""),
            ("run", str(run.get("stop_reason", "?")), f"{run.get('steps', '?')} steps, {fmt(run.get('wall_seconds'), 3)} s",
             "bad" if run.get("diverged") else "")]


# ----------------------------------------------------------------------------- figures

def stress_figure(c, macro):
    fig, (ax,) = new_figure(1, width=10.0, height=4.4)
    ax.plot(c["platen_strain"] * 1e3, c["stress_mpa"], color="#0072B2", lw=1.9, label="stress vs platen strain")
    ax.plot(c["gauge_strain"] * 1e3, c["stress_mpa"], color="#D55E00", lw=1.9, label="stress vs gauge strain")
    ax.plot(c["platen_strain"] * 1e3, c["stress_top_mpa"], color="#0072B2", lw=0.6, alpha=0.5, label="top / bottom platen")
    ax.plot(c["platen_strain"] * 1e3, c["stress_bottom_mpa"], color="#0072B2", lw=0.6, alpha=0.5, ls=":")
    peak = finite(macro.get("peak_stress_mpa"))
    ax.plot([finite(macro.get("strain_at_peak")) * 1e3], [peak], "o", color="#D55E00", ms=7, mec="black", label="peak (gauge)")
    ax.plot([finite(macro.get("strain_at_peak_platen")) * 1e3], [peak], "o", color="#0072B2", ms=7, mec="black", label="peak (platen)")
    red = macro.get("reduction") or {}
    s1, s2, e2 = finite(red.get("chord_s1_mpa")), finite(red.get("chord_s2_mpa")), finite(red.get("chord_strain2"))
    if all(math.isfinite(v) for v in (s1, s2, e2)):
        ax.plot([0.05, e2 * 1e3], [s1, s2], color="#b3261e", lw=2.6, label=f"C469 chord: {fmt(finite(macro.get('chord_modulus_mpa')) / 1e3, 4)} GPa")
    ax.set_xlabel("axial strain ε [‰]")
    ax.set_ylabel("axial stress σ [MPa]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_title(f"Virtual ASTM C109 cube test: peak {fmt(peak, 4)} MPa")
    ax.legend(loc="lower right")
    return to_svg(fig)


def cracks_figure(c, macro):
    fig, (ax,) = new_figure(1, width=10.0, height=4.0)
    e = c["platen_strain"] * 1e3
    ax.plot(e, c["broken_tension"], color=MODE_COLORS["tension"], lw=2, label="tension")
    ax.plot(e, c["broken_shear"], color=MODE_COLORS["shear"], lw=2, label="shear")
    ax.plot(e, c["broken_tension"] + c["broken_shear"], color="black", lw=1.2, label="total")
    peak_strain = finite(macro.get("strain_at_peak_platen")) * 1e3
    if math.isfinite(peak_strain):
        ax.axvline(peak_strain, color="#555", lw=1, ls="-.")
    ax.set_xlabel("platen strain ε [‰]")
    ax.set_ylabel("broken bonds, cumulative [-]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    twin = ax.twinx()
    twin.plot(e, c["stress_mpa"], color="#8a919c", lw=1.2, ls="--", label="axial stress")
    twin.set_ylabel("axial stress σ [MPa]", color="#5b6475")
    twin.set_ylim(bottom=0)
    twin.grid(False)
    twin.spines["right"].set_visible(True)
    lines = ax.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], loc="upper left")
    total = int(c["broken_tension"][-1] + c["broken_shear"][-1]) if len(e) else 0
    ax.set_title(f"Bonds broken by mode ({total} in all)")
    return to_svg(fig)


def lateral_figure(c, macro):
    fig, (ax,) = new_figure(1, width=10.0, height=4.0)
    ea, el = c["gauge_strain"] * 1e3, c["lateral_strain"] * 1e3
    if not np.any(np.isfinite(el)):
        message_panel(ax, "no lateral strain in load_curve.csv")
        ax.set_title("Lateral strain")
        return to_svg(fig)
    ax.plot(ea, el, color="#009E73", lw=1.9, label="lateral strain εl (expansion +)")
    ax.plot(ea, ea - 2 * el, color="#CC79A7", lw=1.9, label="volumetric strain εv = εa − 2εl (compression +)")
    nu = finite(macro.get("poisson_ratio"))
    if math.isfinite(nu):
        x = np.array([0, np.nanmax(ea) if ea.size else 0])
        ax.plot(x, nu * x, "--", color="#009E73", lw=1, label=f"ν = {fmt(nu, 3)} (C469)")
    peak_strain = finite(macro.get("strain_at_peak")) * 1e3
    if math.isfinite(peak_strain):
        ax.axvline(peak_strain, color="#555", lw=1, ls="-.", label="peak")
    ax.axhline(0, color="#555", lw=0.8)
    ax.set_xlabel("axial gauge strain εa [‰]")
    ax.set_ylabel("strain [‰]")
    ax.set_title("Lateral and volumetric strain against axial strain")
    ax.legend(loc="upper left")
    return to_svg(fig)


def crack_map_figure(cracks, macro):
    fig, (ax, hist) = new_figure(2, width=10.0, height=4.4, gridspec_kw={"width_ratios": [1, 1.25]})
    if not cracks:
        for a in (ax, hist):
            message_panel(a, "no bond broke in this test")
        ax.set_title("Broken bonds (x–z)")
        hist.set_title("Orientation of broken bonds")
        return to_svg(fig)
    for mode in ("tension", "shear"):
        mine = [k for k in cracks if k["mode"] == mode]
        if mine:
            ax.plot([k["x"] * 1e3 for k in mine], [k["z"] * 1e3 for k in mine], "o", ms=2.5, alpha=0.6, color=MODE_COLORS[mode],
                    label=f"{mode} ({len(mine)})")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("z [mm] (loading axis)")
    ax.set_title("Broken bonds projected on x–z")
    ax.legend(loc="upper right", markerscale=2)
    bins = np.linspace(0, 90, 10)
    modes = ("tension", "shear")
    angles = [[math.degrees(math.acos(min(1.0, abs(k["nz"])))) for k in cracks if k["mode"] == m and math.isfinite(k["nz"])]
              for m in modes]
    hist.hist(angles, bins=bins, stacked=True, color=[MODE_COLORS[m] for m in modes], label=list(modes), edgecolor="white")
    hist.set_xlabel("angle between bond normal and loading axis [°]")
    hist.set_ylabel("broken bonds [-]")
    hist.set_xticks(bins)
    hist.set_title("Orientation of broken bonds")
    hist.legend()
    return to_svg(fig)


# ----------------------------------------------------------------------------- tables

def macro_rows(macro):
    red, pop = macro.get("reduction") or {}, macro.get("popovics") or {}
    rows = [["peak stress [MPa]", fmt(macro.get("peak_stress_mpa"), 5)],
            ["strain at peak, gauge [‰]", fmt(finite(macro.get("strain_at_peak")) * 1e3, 4)],
            ["strain at peak, platen [‰]", fmt(finite(macro.get("strain_at_peak_platen")) * 1e3, 4)],
            ["chord modulus, ASTM C469 [MPa]", fmt(macro.get("chord_modulus_mpa"), 5)],
            ["tangent modulus at 50 % of peak [MPa]", fmt(macro.get("tangent_modulus_mpa"), 5)],
            ["Poisson's ratio, ASTM C469 [-]", fmt(macro.get("poisson_ratio"), 3)],
            ["reduction status", f"{red.get('status', '?')} {red.get('message', '')}".strip()]]
    if pop.get("converged"):
        rows.append(["Popovics fit: E, f'c, ε'c, n", f"{fmt(pop.get('elastic_modulus_mpa'), 5)} MPa, {fmt(pop.get('peak_stress_mpa'), 4)} MPa, "
                     f"{fmt(finite(pop.get('strain_at_peak')) * 1e3, 4)} ‰, {fmt(pop.get('n'), 3)}"])
    rc = macro.get("rate_check")
    if rc:
        rows.append(["rate check (half rate)", f"peak {pct(rc.get('peak_change'), 2)}, chord modulus {pct(rc.get('modulus_change'), 2)}"])
        at_rate, at_half = finite(rc.get("platen_imbalance")), finite(rc.get("platen_imbalance_half_rate"))
        if at_rate == at_rate and at_half == at_half:  # an imbalance from inertia halves with the rate
            ratio = f" (× {at_half / at_rate:.2f}; inertia alone would give × 0.5)" if at_rate > 0 else ""
            rows.append(["platen imbalance at the rate, at half of it",
                         f"{pct(at_rate, 2, signed=False)}, {pct(at_half, 2, signed=False)}{ratio}"])
    return rows


def run_rows(macro):
    run, sp = macro.get("run") or {}, macro.get("specimen") or {}
    return [["grains, bonds", f"{sp.get('particles', '?')}, {run.get('bonds', '?')}"],
            ["specimen", f"edge {fmt(sp.get('edge_mm'), 3)} mm = {fmt(sp.get('edge_over_d50'), 3)} × D50, porosity "
             f"{fmt(sp.get('porosity'), 3)}, coordination {fmt(sp.get('mean_coordination'), 3)}, seed {sp.get('seed', '?')}"],
            ["grain sizes [mm]", f"{fmt(sp.get('min_diameter_mm'), 3)} – {fmt(sp.get('max_diameter_mm'), 3)} (× {fmt(sp.get('scale'), 3)})"],
            ["steps, time step", f"{run.get('steps', '?')}, {fmt(run.get('time_step_s'), 3)} s"],
            ["strain rate [1/s]", fmt(run.get("strain_rate_per_s"), 3)],
            ["stop", str(run.get("stop_reason", "?"))],
            ["platen imbalance before the peak", pct(run.get("platen_imbalance"), 2, signed=False)],
            ["wall time, throughput", f"{fmt(run.get('wall_seconds'), 3)} s, {fmt(run.get('particle_steps_per_s'), 3)} particle-steps/s"],
            ["config", str(macro.get("config", ""))]]
