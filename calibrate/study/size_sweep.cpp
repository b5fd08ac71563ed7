#include "calibrate/study/size_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_tables.hpp"
#include "common/input_error.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite
using common::InputError;

}  // namespace

void read_swept_sands(StudyKeys& keys) {
    keys.config.sands = study_keys::read_list<std::string>(keys.section, "sands", "an array of sand names", study_keys::text_item);
    keys.config.sands_line = keys.line("sands");
}

// The same parameters on specimens of another edge or another smallest kept grain; every swept
// specimen is checked before anything runs.
std::vector<CalibrationProblem> sweep_problems(const CalibratedPoint& point, const StudyConfig& cfg, SweepKind kind) {
    const char* key = kind == SweepKind::edge ? "study.edges_mm" : "study.min_diameters_mm";
    std::vector<CalibrationProblem> problems;
    for (double x : cfg.sweep_mm) {
        CalibrationProblem p = point.problem;
        exp::SpecimenSpec& spec = p.base.specimen;
        if (kind == SweepKind::edge) spec.genesis.edge = x * 1e-3;
        else spec.size_rule.min_diameter = x * 1e-3;
        const std::string value = std::string(key) + " value " + fmt_num(x) + " mm";
        if (auto why = spec.invalid_reason()) throw InputError(cfg.file.string(), 0, value + " gives an invalid specimen: " + *why);
        if (spec.size_rule.max_diameter > 0.0 && spec.genesis.edge < 3.0 * spec.size_rule.max_diameter)
            throw InputError(cfg.file.string(), 0, value + ": the cube edge " + fmt_num(spec.genesis.edge * 1e3) +
                                                       " mm is under 3 x the largest grain (" +
                                                       fmt_num(spec.size_rule.max_diameter * 1e3) + " mm)");
        if (spec.size_rule.max_diameter > 0.0 && spec.size_rule.min_diameter >= spec.size_rule.max_diameter)
            throw InputError(cfg.file.string(), 0, value + " is not below the largest kept grain (" +
                                                       fmt_num(spec.size_rule.max_diameter * 1e3) + " mm)");
        problems.push_back(std::move(p));
    }
    return problems;
}

void run_size_sweep(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result, SweepKind kind) {
    const StudyConfig& cfg = result.config;
    const std::vector<CalibrationProblem> problems = sweep_problems(point, cfg, kind);
    for (std::size_t k = 0; k < problems.size(); ++k) {
        const double x = cfg.sweep_mm[k];
        const std::string name = (kind == SweepKind::edge ? "edge " : "d_min ") + fmt_num(x) + " mm";
        runner.say("case " + name);
        for (StudyCase& c : runner.run(problems[k], {point.values}, {name}, {x})) result.cases.push_back(std::move(c));
    }
    result.tables.push_back(case_table(kind == SweepKind::edge ? "Macro properties against the cube edge (mean ± seed std)"
                                                               : "Macro properties against the smallest kept grain (mean ± seed std)",
                                       kind == SweepKind::edge ? "edge" : "smallest grain", result.cases));
    json cases = json::array();
    for (const StudyCase& c : result.cases) cases.push_back(case_samples_json(c));
    result.data = {{"x_name", kind == SweepKind::edge ? "edge_mm" : "min_diameter_mm"}, {"cases", cases}};
}

// A property has converged at case k when every later step changes its mean by less than the
// seed standard deviation of the two cases it joins (the noise a user sees at one size), or by
// less than study.tolerance × the mean (a change the user has said does not matter: as the
// cubes grow the seed spread shrinks below any change worth a bigger cube).
void summarise_convergence(StudyResult& result) {
    const auto& cases = result.cases;
    const double tolerance = result.config.tolerance;
    const std::string criterion = tolerance > 0.0 ? "the seed spread or " + fmt_num(100.0 * tolerance) + " %" : "the seed spread";
    StudyTable t{"Convergence with the cube edge", {"sand", "property", "converged from", "last change", "seed std there"}, {}};
    json conv = json::array();
    for (std::size_t s = 0; s < cases.front().sands.size(); ++s)
        for (Quantity q : kQuantities) {
            std::size_t from = cases.size();  // none yet
            double last_change = std::nan(""), last_std = std::nan("");
            for (std::size_t k = cases.size(); k-- > 1;) {
                const Sample a = cases[k - 1].sample(s, q), b = cases[k].sample(s, q);
                const double change = std::fabs(b.mean - a.mean);
                const double seed_std = std::max(a.std, b.std);
                const double noise = std::max(seed_std, tolerance * std::fabs(b.mean));
                if (k == cases.size() - 1) last_change = change / std::fabs(b.mean), last_std = seed_std / std::fabs(b.mean);
                if (!(change < noise)) break;
                from = k - 1;
            }
            const bool converged = from < cases.size();
            const std::string at = converged ? cases[from].label : "not within the sweep";
            t.rows.push_back({{cases.front().sands[s], quantity_label(q), at, fmt_num(100.0 * last_change, 3) + " %",
                               fmt_num(100.0 * last_std, 3) + " %"}});
            conv.push_back({{"sand", cases.front().sands[s]}, {"quantity", to_string(q)}, {"converged", converged},
                            {"from_x", converged ? json(cases[from].x) : json(nullptr)}, {"last_relative_change", number(last_change)},
                            {"relative_seed_std", number(last_std)}, {"tolerance", tolerance}});
            if (q != Quantity::strain)
                result.verdict.push_back(cases.front().sands[s] + ", " + quantity_label(q) + ": " +
                                         (converged ? "changes less than " + criterion + " from " + at + " on"
                                                    : "still changes more than " + criterion + " at the largest edge"));
        }
    result.tables.push_back(t);
    result.data["convergence"] = conv;
}

}  // namespace gradem::cal
