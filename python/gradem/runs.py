"""The specimen and the virtual tests of a cube config (gradem specimen, compress, tension).

Each releases the GIL while it runs (other Python threads go on) and stops on Ctrl-C at the
next curve point (KeyboardInterrupt; genesis itself runs to its end). `threads` sets the
OpenMP threads of the run (the results are bitwise the same for any count); `out` writes the
command line's files (load_curve.csv, cracks.csv, macro.json) into a folder as well.
"""

import json
import os
import tempfile

from . import _gradem
from .config import as_impl


class Specimen:
    """A packing: grain centres [m] (N x 3), radii [m], families (0 sand, 1 paste), its report."""

    def __init__(self, d):
        self.positions = d["positions"]
        self.radii = d["radii"]
        self.families = d["families"]
        self.box_lo = d["box_lo"]
        self.box_hi = d["box_hi"]
        self.edge_mm = d["edge_mm"]
        self.density_kg_m3 = d["density_kg_m3"]
        self.cached = d["cached"]
        self.path = d["path"]
        self.description = d["description"]
        self.gradation = d["gradation"]
        self.report = d["report"]
        self.paste = d.get("paste")

    def __len__(self):
        return len(self.radii)

    def __repr__(self):
        return f"Specimen({len(self)} particles, edge {self.edge_mm:.3g} mm, {'cached' if self.cached else 'generated'}: {self.path})"


class TestResult:
    """One virtual test: macro (macro.json as a dict), curve and cracks (numpy columns), provenance."""

    __test__ = False  # not a pytest class

    def __init__(self, d):
        self.macro = d["macro"]
        self.curve = d["curve"]
        self.cracks = d["cracks"]
        self.provenance = d["provenance"]
        self.diverged = d["diverged"]

    @property
    def test(self):
        return self.provenance["test"]

    @property
    def peak_stress_mpa(self):
        """The peak stress (compression) or the tensile strength (direct tension) [MPa]."""
        return self.macro.get("peak_stress_mpa", self.macro.get("tensile_strength_mpa"))

    @property
    def strain_at_peak(self):
        return self.macro["strain_at_peak"]

    @property
    def modulus_mpa(self):
        """The chord modulus [MPa]: ASTM C469 in compression, the tensile chord in tension."""
        return self.macro.get("chord_modulus_mpa", self.macro.get("tensile_modulus_mpa"))

    @property
    def poisson_ratio(self):
        return self.macro.get("poisson_ratio")

    def __repr__(self):
        state = " DIVERGED" if self.diverged else ""
        return (f"TestResult({self.test}: peak {self.peak_stress_mpa:.4g} MPa, modulus {self.modulus_mpa:.4g} MPa, "
                f"strain at peak {self.strain_at_peak:.4g}{state})")


def specimen(config, threads=None):
    """The config's packing, from the packing cache or made by genesis (and cached)."""
    return Specimen(_gradem.specimen(as_impl(config), threads))


def compress(config, threads=None, progress=None, out=None, check_rate=False):
    """The virtual C109 cube test of a config (a CubeConfig or a path), as `gradem compress`.

    progress(point) is called at every curve point with a dict (step, strains, stress_mpa,
    peak_mpa, breaks); an exception it raises stops the test. check_rate runs the test again at
    half the strain rate and puts the change into macro["rate_check"].
    """
    return TestResult(_gradem.compress(as_impl(config), threads, progress, os.fspath(out) if out else "", check_rate))


def tension(config, threads=None, progress=None, out=None, compression=None, check_rate=False):
    """The virtual direct-tension test of a config, as `gradem tension` (files into out/tension).

    compression: the compression test of the same config (a TestResult, or its macro.json), for
    σc/σt in macro["strength_ratio_c_over_t"]; it is checked to be of the same material and specimen.
    """
    impl = as_impl(config)
    out = os.fspath(out) if out else ""
    if isinstance(compression, TestResult):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "macro.json")
            with open(path, "w") as f:
                json.dump(compression.macro, f)
            return TestResult(_gradem.tension(impl, threads, progress, out, path, check_rate))
    return TestResult(_gradem.tension(impl, threads, progress, out, os.fspath(compression) if compression else "", check_rate))
