// study.json (everything, for figures and scripts), study.md (the tables and the verdict for
// people) and runs.csv (one row per run) of a `gradem study`, each written atomically.
#include "reports/study_report.hpp"

#include <cmath>
#include <sstream>

#include "calibrate/execution/ledger.hpp"
#include "calibrate/study/study.hpp"
#include "common/atomic_file.hpp"
#include "common/clock_text.hpp"
#include "common/json_number.hpp"

namespace gradem::report {
namespace {

using namespace cal;  // the study's result types

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

/// The packing seed of a case's k-th run of a sand (the case's own, else the study's).
std::uint64_t seed_of(const StudyResult& r, const StudyCase& c, std::size_t k) {
    const std::vector<std::uint64_t>& seeds = c.seeds.empty() ? r.config.seeds : c.seeds;
    return k < seeds.size() ? seeds[k] : 0;
}

json runs_json(const StudyResult& r) {
    json cases = json::array();
    for (const StudyCase& c : r.cases) {
        json sands = json::array();
        for (std::size_t s = 0; s < c.sands.size(); ++s) {
            json runs = json::array();
            for (std::size_t k = 0; k < c.runs[s].size(); ++k) {
                const RunOutcome& o = c.runs[s][k];
                runs.push_back({{"seed", seed_of(r, c, k)}, {"status", to_string(o.status)},
                                {"reason", o.reason}, {"modulus_mpa", number(o.modulus_pa * 1e-6)}, {"peak_mpa", number(o.peak_pa * 1e-6)},
                                {"strain_at_peak", number(o.strain_at_peak)}, {"particles", o.particles}, {"bonds", o.bonds},
                                {"steps", o.steps}, {"wall_seconds", o.wall_seconds}});
            }
            sands.push_back({{"sand", c.sands[s]}, {"runs", runs}});
        }
        cases.push_back({{"label", c.label}, {"x", c.x}, {"sands", sands}});
    }
    return cases;
}

json tables_json(const StudyResult& r) {
    json out = json::array();
    for (const StudyTable& t : r.tables) {
        json rows = json::array();
        for (const StudyRow& row : t.rows) rows.push_back(row.cells);
        out.push_back({{"title", t.title}, {"header", t.header}, {"rows", rows}});
    }
    return out;
}

std::string markdown(const StudyResult& r) {
    std::ostringstream md;
    md << "# gradem study: " << to_string(r.config.kind) << " (" << r.config.file.filename().string() << ")\n\n";
    if (r.representative) md << "> **The lab data are REPRESENTATIVE, not measurements.**\n\n";
    md << "- calibration: ";
    for (std::size_t k = 0; k < r.calibration_summaries.size(); ++k) md << (k ? ", " : "") << r.calibration_summaries[k];
    const StudyKindSpec& kind = study_kind(r.config.kind);
    if (kind.one_calibration) md << "\n- packing seeds per sand: " << r.config.seeds.size();
    md << "\n- DEM runs" << kind.runs_note
       << ": " << r.runs_executed << " run now, "
       << r.runs_from_ledger << " from the ledger, " << r.runs_failed << " failed; wall time " << common::clock_text(r.wall_seconds)
       << "\n\n## Answer\n\n";
    for (const std::string& v : r.verdict) md << "- " << v << "\n";
    for (const StudyTable& t : r.tables) {
        md << "\n## " << t.title << "\n\n|";
        for (const auto& h : t.header) md << " " << h << " |";
        md << "\n|";
        for (std::size_t k = 0; k < t.header.size(); ++k) md << "---|";
        md << "\n";
        for (const StudyRow& row : t.rows) {
            md << "|";
            for (const auto& c : row.cells) md << " " << c << " |";
            md << "\n";
        }
    }
    return md.str();
}

std::string runs_csv(const StudyResult& r) {
    std::ostringstream csv;
    csv.precision(10);
    csv << "case,x,sand,seed,status,modulus_mpa,peak_mpa,strain_at_peak,particles,bonds,steps,wall_seconds\n";
    for (const StudyCase& c : r.cases)
        for (std::size_t s = 0; s < c.sands.size(); ++s)
            for (std::size_t k = 0; k < c.runs[s].size(); ++k) {
                const RunOutcome& o = c.runs[s][k];
                csv << '"' << c.label << "\"," << c.x << ",\"" << c.sands[s] << "\"," << seed_of(r, c, k)
                    << "," << to_string(o.status) << "," << o.modulus_pa * 1e-6 << "," << o.peak_pa * 1e-6 << "," << o.strain_at_peak
                    << "," << o.particles << "," << o.bonds << "," << o.steps << "," << o.wall_seconds << "\n";
            }
    return csv.str();
}

}  // namespace

void write_study_outputs(const cal::StudyResult& r) {
    const json j = {{"schema", "gradem-study/1"},
                    {"kind", to_string(r.config.kind)},
                    {"study_file", r.config.file.string()},
                    {"calibrations", r.calibration_summaries},
                    {"representative_lab_data", r.representative},
                    {"seeds", r.config.seeds},
                    {"runs", {{"executed_now", r.runs_executed}, {"from_ledger", r.runs_from_ledger}, {"failed", r.runs_failed}}},
                    {"wall_seconds", r.wall_seconds},
                    {"ledger", r.config.ledger.string()},
                    {"code_version", code_version()},
                    {"verdict", r.verdict},
                    {"data", r.data},
                    {"tables", tables_json(r)},
                    {"cases", runs_json(r)}};
    common::write_file_atomically(r.config.out_dir / "study.json", j.dump(2) + "\n");
    common::write_file_atomically(r.config.out_dir / "study.md", markdown(r));
    common::write_file_atomically(r.config.out_dir / "runs.csv", runs_csv(r));
}

}  // namespace gradem::report
