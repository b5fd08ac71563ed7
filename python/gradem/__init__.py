"""gradem from Python: lab data, virtual cube tests, calibrations and their ledgers.

A thin layer over gradem's C++ (the extension gradem._gradem): every number comes from the code
the command line runs. python/README.md lists the API; in short:

    import gradem
    lab = gradem.lab.read("lab_data/datasets/study")            # gradem lab
    cfg = gradem.CubeConfig.load("experiments/configs/calibration_cube.toml")
    cfg.material.tensile_strength_mpa = 12                     # checked as the TOML key is
    packing = gradem.specimen(cfg)                              # gradem specimen
    result = gradem.compress(cfg, threads=2)                    # gradem compress
    summary = gradem.calibrate("problem.toml", max_runs=20)     # gradem calibrate
    model = gradem.Model("problem.toml")                        # parameters -> cube tests
"""

import os as _os

# Idle OpenMP threads sleep after a short spin (core/openmp_policy.hpp): libgomp reads this when
# it is loaded, which is when the extension below is imported. A user's own setting wins.
if "OMP_WAIT_POLICY" not in _os.environ and "GOMP_SPINCOUNT" not in _os.environ:
    _os.environ["GOMP_SPINCOUNT"] = "3000"

from . import _gradem  # noqa: E402
from ._gradem import InputError, LabWarning, RunError, code_version  # noqa: E402
from .config import CubeConfig, material_table  # noqa: E402
from .runs import Specimen, TestResult, compress, specimen, tension  # noqa: E402
from .calibration import Ledger, Model, calibrate, study  # noqa: E402
from . import lab  # noqa: E402

__version__ = _gradem.__version__

__all__ = [
    "__version__", "code_version", "InputError", "RunError", "LabWarning",
    "lab", "CubeConfig", "material_table", "specimen", "compress", "tension", "Specimen", "TestResult",
    "calibrate", "study", "Ledger", "Model",
]
