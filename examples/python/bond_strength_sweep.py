"""Peak stress and stress-strain curves of a cube config over the mean bond tensile strength.

    PYTHONPATH=build/python python3 examples/python/bond_strength_sweep.py CONFIG.toml OUT.png [MPa ...]
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import gradem  # noqa: E402

config, figure = sys.argv[1], sys.argv[2]
strengths = [float(s) for s in sys.argv[3:]] or [6.0, 9.0, 12.0]  # [MPa]
cfg = gradem.CubeConfig.load(config)
fig, (curves, peaks) = plt.subplots(1, 2, figsize=(9, 3.5))
for s in strengths:
    cfg.material.tensile_strength_mpa = s  # checked as the TOML key is
    r = gradem.compress(cfg)
    curves.plot(r.curve["gauge_strain"], r.curve["stress_mpa"], label=f"{s:g} MPa")
    peaks.plot(s, r.peak_stress_mpa, "ko")
    print(f"tensile strength {s:g} MPa: peak {r.peak_stress_mpa:.3f} MPa, modulus {r.modulus_mpa:.0f} MPa")
curves.set(xlabel="gauge strain [-]", ylabel="stress [MPa]")
curves.legend(title="bond tensile strength")
peaks.set(xlabel="bond tensile strength [MPa]", ylabel="peak stress [MPa]")
fig.tight_layout()
fig.savefig(figure, dpi=120)
