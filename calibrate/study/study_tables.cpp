#include "calibrate/study/study_tables.hpp"

#include <cmath>

#include "common/json_number.hpp"
#include "common/number_format.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

}  // namespace

double display_scale(Quantity q) { return q == Quantity::strain ? 1.0 : 1e-6; }

const char* quantity_label(Quantity q) {
    return q == Quantity::modulus ? "chord modulus" : q == Quantity::peak ? "peak stress" : "strain at peak";
}

const char* display_unit(Quantity q) { return q == Quantity::strain ? "-" : "MPa"; }

std::string fmt_num(double v, int digits) { return common::format_significant(v, digits); }

std::string mean_pm(double mean, double std, int digits) {
    if (!std::isfinite(mean)) return "-";
    return fmt_num(mean, digits) + (std::isfinite(std) ? " ± " + fmt_num(std, 2) : "");
}

std::string interval_text(const Interval& i, double scale) {
    if (!std::isfinite(i.low)) return fmt_num(i.estimate * scale) + " [n < 2]";
    return fmt_num(i.estimate * scale) + " [" + fmt_num(i.low * scale) + ", " + fmt_num(i.high * scale) + "]";
}

json interval_json(const Interval& i, double scale) {
    return {{"estimate", number(i.estimate * scale)}, {"low", number(i.low * scale)}, {"high", number(i.high * scale)}};
}

StudyTable case_table(const std::string& title, const std::string& x_name, const std::vector<StudyCase>& cases) {
    StudyTable t{title, {x_name, "sand", "particles", "chord modulus MPa", "peak MPa", "strain at peak", "wall s/run", "failed"}, {}};
    for (const StudyCase& c : cases)
        for (std::size_t s = 0; s < c.sands.size(); ++s) {
            StudyRow row{{c.label, c.sands[s], fmt_num(c.mean_particles(s), 6)}};
            for (Quantity q : kQuantities) {
                const Sample m = c.sample(s, q);
                row.cells.push_back(mean_pm(m.mean * display_scale(q), m.std * display_scale(q)));
            }
            row.cells.push_back(fmt_num(c.mean_wall_seconds(s), 3));
            int failed = 0;
            for (const RunOutcome& r : c.runs[s]) failed += r.ok() ? 0 : 1;
            row.cells.push_back(std::to_string(failed));
            t.rows.push_back(row);
        }
    return t;
}

json case_samples_json(const StudyCase& c) {
    json sands = json::array();
    for (std::size_t s = 0; s < c.sands.size(); ++s) {
        json j = {{"sand", c.sands[s]}, {"particles", c.mean_particles(s)}, {"wall_seconds_per_run", number(c.mean_wall_seconds(s))}};
        for (Quantity q : kQuantities) {
            const Sample m = c.sample(s, q);
            const double k = display_scale(q);
            j[to_string(q)] = {{"mean", number(m.mean * k)}, {"std", number(m.std * k)}, {"n", m.n}, {"unit", display_unit(q)}};
        }
        sands.push_back(j);
    }
    return {{"label", c.label}, {"x", c.x}, {"sands", sands}};
}

RunCostSummary summarise_costs(const std::vector<RunCost>& runs, const std::string& sand) {
    RunCostSummary c;
    double wall = 0.0, particle_steps = 0.0;
    for (const RunCost& r : runs)
        if (r.sand == sand && r.wall_seconds > 0.0) {
            ++c.runs;
            wall += r.wall_seconds;
            particle_steps += static_cast<double>(r.particles) * static_cast<double>(r.steps);
        }
    c.mean_wall_seconds = c.runs ? wall / c.runs : std::nan("");
    c.particle_steps_per_second = c.runs ? particle_steps / wall : std::nan("");
    return c;
}

}  // namespace gradem::cal
