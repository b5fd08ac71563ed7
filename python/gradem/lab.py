"""Lab data: what `gradem lab` computes, as the document it writes (lab_results.json) with numpy.

    lab = gradem.lab.read("lab_data/datasets/study")
    for sand in lab["sands"]:
        print(sand["name"], sand["peak_stress_mpa"]["mean"])
    cube = lab["cubes"][0]
    plt.plot(cube["curve"]["strain"], cube["curve"]["stress_mpa"])

The keys are lab_results.json's (lab_data/README.md): per sand the gradation and the
statistics, per cube its reduction, the comparisons between sands. Beside them each cube has
its stress-strain curve as read ("curve": strain, stress_mpa, crosshead_strain, lateral_strain,
time_s, numpy arrays), and each sand's gradation its sieve sizes and passing as numpy arrays.
The readers' warnings (rows skipped, nominal dimensions) come as gradem.LabWarning warnings.
"""

import os

import numpy as np

from . import _gradem


def read(path):
    """The lab statistics of a dataset (folder or dataset.toml), or of a list of export files
    (C109 cubes) or sieve analyses. Bad input raises gradem.InputError naming the file and line."""
    inputs = [os.fspath(path)] if isinstance(path, (str, os.PathLike)) else [os.fspath(p) for p in path]
    doc = _gradem.lab_read(inputs)
    for sand in doc.get("sands", []):
        g = sand.get("gradation")
        if isinstance(g, dict):
            for key in ("sieves_mm", "percent_passing"):
                if key in g:
                    g[key] = np.asarray(g[key], dtype=float)
    return doc
