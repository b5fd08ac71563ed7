#pragma once
// What the study kinds share to fill a result's tables (study.md) and data (study.json, the
// figures): the target quantities in display units (stresses and moduli in MPa, strains as
// ratios), numbers with significant digits, intervals as text and JSON, and the per-case table
// and JSON of the macro properties.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calibrate/execution/ledger.hpp"
#include "calibrate/study/study.hpp"

namespace gradem::cal {

/// Multiplier from SI to the shown unit: 1e-6 (Pa -> MPa), 1 for the strain.
double display_scale(Quantity q);
/// "chord modulus", "peak stress", "strain at peak".
const char* quantity_label(Quantity q);
/// "MPa", or "-" for the strain.
const char* display_unit(Quantity q);

/// "12.3 ± 0.4" with `digits` significant digits; "-" for NaN.
std::string mean_pm(double mean, double std, int digits = 4);
std::string fmt_num(double v, int digits = 4);

/// "estimate [low, high]" scaled to display units ("estimate [n < 2]" without bounds).
std::string interval_text(const Interval& i, double scale);
nlohmann::json interval_json(const Interval& i, double scale);

/// Per case and sand: particles, each quantity's mean ± seed std, wall time per run, failures.
StudyTable case_table(const std::string& title, const std::string& x_name, const std::vector<StudyCase>& cases);
/// A case's label, swept value and per-sand means, stds and counts (display units).
nlohmann::json case_samples_json(const StudyCase& c);

/// Cost per cube test of a calibration, per sand, from its ledger's successful runs.
struct RunCostSummary {
    int runs = 0;
    double mean_wall_seconds = 0.0;          ///< [s] per run
    double particle_steps_per_second = 0.0;  ///< Σ particles·steps / Σ wall seconds [1/s]
};
RunCostSummary summarise_costs(const std::vector<RunCost>& runs, const std::string& sand);

}  // namespace gradem::cal
