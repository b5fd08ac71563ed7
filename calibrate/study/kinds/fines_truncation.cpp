// The fines_truncation study: what does cutting the fines cost in accuracy? The calibrated
// parameters on specimens whose smallest kept grain is each of study.min_diameters_mm; each cut's
// cost (particles, wall time) against its change from the finest cut (docs/calibration.md
// "Studies").
#include <algorithm>
#include <cmath>

#include "calibrate/study/size_sweep.hpp"
#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_tables.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

void read_keys(StudyKeys& keys) {
    read_swept_sands(keys);
    const auto mins = study_keys::read_list<double>(keys.section, "min_diameters_mm", "a non-empty array of positive numbers [mm]",
                                                    study_keys::positive_number);
    if (mins.size() < 2)
        study_keys::refuse(keys, "min_diameters_mm", "key 'study.min_diameters_mm' needs at least two sizes [mm]");
    keys.config.sweep_mm = mins;
}

std::vector<CalibrationProblem> problems(const CalibratedPoint& point, const StudyConfig& config) {
    return sweep_problems(point, config, SweepKind::min_diameter);
}

// Error of each cut against the finest (smallest d_min) case, and whether it is within the
// 95 % noise of the two means; cost as particles and wall time per run relative to the finest.
void summarise_truncation(StudyResult& result) {
    const auto& cases = result.cases;
    const StudyCase& finest = cases.front();
    StudyTable t{"Cost against error, relative to the finest cut (" + finest.label + ")",
                 {"smallest grain", "sand", "particles x", "wall time x", "modulus error", "peak error", "strain error", "within noise"}, {}};
    json rows = json::array();
    for (const StudyCase& c : cases)
        for (std::size_t s = 0; s < c.sands.size(); ++s) {
            StudyRow row{{c.label, c.sands[s], fmt_num(c.mean_particles(s) / finest.mean_particles(s), 3),
                          fmt_num(c.mean_wall_seconds(s) / finest.mean_wall_seconds(s), 3)}};
            bool within = true;
            json errors;
            for (Quantity q : kQuantities) {
                const Sample a = c.sample(s, q), f = finest.sample(s, q);
                const double err = a.mean / f.mean - 1.0;
                const double noise = 1.96 * std::sqrt(a.std * a.std / std::max(1, a.n) + f.std * f.std / std::max(1, f.n));
                within = within && std::fabs(a.mean - f.mean) <= noise;
                row.cells.push_back(fmt_num(100.0 * err, 3) + " %");
                errors[to_string(q)] = number(err);
            }
            row.cells.push_back(within ? "yes" : "no");
            t.rows.push_back(row);
            rows.push_back({{"x", c.x}, {"sand", c.sands[s]}, {"particles_ratio", number(c.mean_particles(s) / finest.mean_particles(s))},
                            {"wall_ratio", number(c.mean_wall_seconds(s) / finest.mean_wall_seconds(s))},
                            {"relative_error", errors}, {"within_noise", within}});
        }
    result.tables.push_back(t);
    result.data["truncation"] = rows;
    const StudyCase* coarsest_ok = &finest;
    for (const StudyCase& c : cases) {
        bool ok = true;
        for (const json& r : rows)
            if (r["x"] == c.x && !r["within_noise"].get<bool>()) ok = false;
        if (ok) coarsest_ok = &c;
        else break;
    }
    result.verdict.push_back("the coarsest cut whose modulus, peak and strain stay within the 95 % seed noise of the finest: " +
                             coarsest_ok->label + " (" + fmt_num(coarsest_ok->mean_particles(0) / finest.mean_particles(0), 3) +
                             " x the particles of the finest, first sand)");
}

void run(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    run_size_sweep(calibrations.front(), runner, result, SweepKind::min_diameter);
    summarise_truncation(result);
}

}  // namespace

const StudyKindSpec fines_truncation_study = {
    .keys = {"sands", "min_diameters_mm"},
    .read_keys = read_keys,
    .one_calibration = true,
    .problems = problems,
    .run = run,
};

}  // namespace gradem::cal
