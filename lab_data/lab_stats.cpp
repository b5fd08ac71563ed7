#include "lab_data/lab_stats.hpp"

#include <cmath>

#include "common/input_error.hpp"
#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

namespace fs = std::filesystem;

std::string display_path(const fs::path& p, const fs::path& base) {
    if (base.empty()) return p.string();
    std::error_code ec;
    const fs::path rel = fs::relative(p, base, ec);
    return ec || rel.empty() ? p.string() : rel.generic_string();
}

SandStatistics statistics_of(const std::vector<CubeResult>& cubes, const std::vector<std::size_t>& members) {
    std::vector<double> peak, strain, chord, tangent, crosshead;
    for (auto i : members) {
        const auto& r = cubes[i].reduction;
        peak.push_back(r.peak_stress_pa);
        strain.push_back(r.strain_at_peak);
        chord.push_back(r.chord_modulus_pa);
        tangent.push_back(r.tangent_modulus_pa);
        crosshead.push_back(r.strain_at_peak_crosshead);
    }
    return {summarize(peak), summarize(strain), summarize(chord), summarize(tangent), summarize(crosshead)};
}

// Splitting, flexural and (pooled over both) direct-tension statistics of a sand's specimens.
TensileStatistics tensile_statistics_of(const std::vector<TensileResult>& tests, const std::vector<std::size_t>& members) {
    std::vector<double> splitting, flexural, direct;
    for (auto i : members) {
        const TensileResult& t = tests[i];
        (t.test == TensileTestKind::splitting ? splitting : flexural).push_back(t.strength_pa);
        direct.push_back(t.direct_equivalent_pa);
    }
    return {summarize(splitting), summarize(flexural), summarize(direct)};
}

// C109 range checks per batch; flags the cubes concerned.
void range_checks(SandResult& sand, std::vector<CubeResult>& cubes, std::size_t group_size) {
    for (const auto& batch : sand.batches) {
        std::vector<std::size_t> members;
        for (auto i : sand.cubes)
            if (cubes[i].batch == batch) members.push_back(i);
        std::vector<double> strength;
        for (auto i : members) strength.push_back(cubes[i].reduction.peak_stress_pa);
        for (const RangeCheck& g : c109_range_checks(strength, group_size)) {
            BatchRangeCheck b{batch, {}, {}, g};
            for (auto k : g.members) {
                CubeResult& cube = cubes[members[k]];
                b.files.push_back(cube.file);
                if (static_cast<long>(k) == g.discarded) {
                    cube.flags.push_back("c109_range_discarded");
                    b.discarded_file = cube.file;
                }
                if (g.retest_required && static_cast<long>(k) != g.discarded) cube.flags.push_back("c109_retest_required");
            }
            sand.range_checks.push_back(std::move(b));
        }
    }
}

// The sieve table's warnings among the gradation's notes (the JSON's "notes" of a gradation).
void add_notes(GradationIndices& gradation, const std::vector<LabWarning>& warnings) {
    for (const LabWarning& w : warnings) gradation.notes.push_back(w.message());
}

void gradation_of(SandResult& sand, const fs::path& sieve, const C144Limits* limits) {
    if (sieve.empty()) return;
    sand.sieve = read_sieve_csv(sieve);
    sand.gradation = analyse_gradation(sand.sieve->curve);
    add_notes(*sand.gradation, sand.sieve->warnings);
    if (limits) sand.c144 = check_c144(sand.sieve->curve, *limits);
}

void compare_sands(LabStats& lab) {
    struct Quantity { const char* name; double CurveReduction::*field; };
    static const Quantity kQuantities[] = {{"peak_stress_mpa", &CurveReduction::peak_stress_pa},
                                           {"strain_at_peak", &CurveReduction::strain_at_peak},
                                           {"chord_modulus_mpa", &CurveReduction::chord_modulus_pa},
                                           {"tangent_modulus_mpa", &CurveReduction::tangent_modulus_pa}};
    for (std::size_t a = 0; a < lab.sands.size(); ++a)
        for (std::size_t b = a + 1; b < lab.sands.size(); ++b) {
            const SandResult &sa = lab.sands[a], &sb = lab.sands[b];
            if (!sa.cubes.empty() && !sb.cubes.empty())
                for (const auto& q : kQuantities) {
                    std::vector<double> xa, xb;
                    for (auto i : sa.cubes) xa.push_back(lab.cubes[i].reduction.*q.field);
                    for (auto i : sb.cubes) xb.push_back(lab.cubes[i].reduction.*q.field);
                    lab.comparisons.push_back({q.name, sa.name, sb.name, welch_t_test(xa, xb)});
                }
            if (!sa.tensile.empty() && !sb.tensile.empty()) {  // the direct tensile strength calibration fits
                std::vector<double> xa, xb;
                for (auto i : sa.tensile) xa.push_back(lab.tensile_tests[i].direct_equivalent_pa);
                for (auto i : sb.tensile) xb.push_back(lab.tensile_tests[i].direct_equivalent_pa);
                lab.comparisons.push_back({"tensile_strength_mpa", sa.name, sb.name, welch_t_test(xa, xb)});
            }
        }
}

}  // namespace

CubeResult reduce_cube_file(const fs::path& path, const std::string& display_name, const DatasetConfig& config) {
    const LoadFrameTest test = read_load_frame_test(path, config.read);
    CubeResult cube;
    cube.file = display_name;
    cube.format = test.format;
    cube.geometry = test.geometry;
    cube.columns = test.columns;
    cube.representative = test.representative || config.representative;
    cube.notes = test.notes;
    cube.warnings = test.warnings;
    report(cube_geometry_warning(test), cube.warnings, cube.notes);
    cube.curve = to_stress_strain(test);
    cube.reduction = reduce_curve(cube.curve, config.reduction);
    const auto& r = cube.reduction;
    if (r.status != ReductionStatus::ok) {
        const int line = r.problem_index < test.line.size() ? test.line[r.problem_index] : 0;
        throw InputError(path.string(), line, r.message);
    }
    cube.load_rate_n_per_s = r.stress_rate_pa_per_s * test.geometry.loaded_area_m2();
    if (std::isfinite(cube.load_rate_n_per_s) && (cube.load_rate_n_per_s < kC109MinLoadRate || cube.load_rate_n_per_s > kC109MaxLoadRate))
        cube.flags.push_back("load_rate_outside_c109");
    if (test.strain.empty()) cube.flags.push_back("no_extensometer");
    if (config.reduction.fit_popovics && !r.popovics.converged) cube.flags.push_back("popovics_fit_not_converged");
    return cube;
}

LabStats analyse_lab_dataset(const fs::path& folder_or_toml) { return analyse_lab_dataset(load_dataset_config(folder_or_toml)); }

LabStats analyse_lab_dataset(const DatasetConfig& config) {
    LabStats lab;
    lab.dataset = config.name;
    lab.source = config.file.string();
    lab.representative = config.representative;
    lab.note = config.note;
    lab.reduction = config.reduction;
    std::optional<C144Limits> limits;
    if (!config.c144_limits.empty()) limits = read_c144_limits(config.c144_limits);
    for (const SandSpec& spec : config.sands) {
        SandResult sand;
        sand.name = spec.name;
        sand.specific_gravity = spec.specific_gravity;
        gradation_of(sand, spec.sieve, limits ? &*limits : nullptr);
        for (const BatchSpec& batch : spec.batches) {
            sand.batches.push_back(batch.name);
            for (const fs::path& f : batch.files) {
                CubeResult cube = reduce_cube_file(f, display_path(f, config.folder), config);
                cube.sand = spec.name;
                cube.batch = batch.name;
                sand.cubes.push_back(lab.cubes.size());
                lab.cubes.push_back(std::move(cube));
            }
        }
        for (const TensionBatchSpec& batch : spec.tension) {
            sand.tension_batches.push_back(batch.name);
            for (const fs::path& f : batch.files) {
                TensileResult t = read_tensile_file(f, display_path(f, config.folder), batch.spec, config.read);
                t.sand = spec.name;
                t.batch = batch.name;
                t.representative = t.representative || config.representative;
                sand.tensile.push_back(lab.tensile_tests.size());
                lab.tensile_tests.push_back(std::move(t));
            }
        }
        range_checks(sand, lab.cubes, config.c109_group_size);
        sand.stats = statistics_of(lab.cubes, sand.cubes);
        sand.tensile_stats = tensile_statistics_of(lab.tensile_tests, sand.tensile);
        lab.sands.push_back(std::move(sand));
    }
    for (const auto& c : lab.cubes) lab.representative = lab.representative || c.representative;
    for (const auto& t : lab.tensile_tests) lab.representative = lab.representative || t.representative;
    compare_sands(lab);
    return lab;
}

namespace {

// The results of loose files (no dataset): one group named "files", filled by `add`.
template <typename AddFiles>
LabStats analyse_loose_files(const DatasetConfig& config, AddFiles add) {
    LabStats lab;
    lab.dataset = config.name;
    lab.source = "files";
    lab.note = config.note;
    lab.reduction = config.reduction;
    SandResult group;
    group.name = "files";
    add(lab, group);
    lab.sands.push_back(std::move(group));
    if (lab.representative && lab.note.empty())
        lab.note = "at least one file says it holds REPRESENTATIVE (synthetic) data, not measurements";
    return lab;
}

}  // namespace

LabStats analyse_lab_files(const std::vector<fs::path>& files, const DatasetConfig& config) {
    return analyse_loose_files(config, [&](LabStats& lab, SandResult& group) {
        for (const auto& f : files) {
            CubeResult cube = reduce_cube_file(f, f.string(), config);
            cube.sand = group.name;
            group.cubes.push_back(lab.cubes.size());
            lab.representative = lab.representative || cube.representative;
            lab.cubes.push_back(std::move(cube));
        }
        group.stats = statistics_of(lab.cubes, group.cubes);
    });
}

LabStats analyse_tension_files(const std::vector<fs::path>& files, const TensileSpec& spec, const DatasetConfig& config) {
    return analyse_loose_files(config, [&](LabStats& lab, SandResult& group) {
        for (const auto& f : files) {
            TensileResult t = read_tensile_file(f, f.string(), spec, config.read);
            t.sand = group.name;
            group.tensile.push_back(lab.tensile_tests.size());
            lab.representative = lab.representative || t.representative;
            lab.tensile_tests.push_back(std::move(t));
        }
        group.tensile_stats = tensile_statistics_of(lab.tensile_tests, group.tensile);
    });
}

namespace {

// The analysis's sand (its column headers or "# sand:" line), else the file stem.
std::string sand_name_of(const SieveAnalysis& sieve, const fs::path& file) {
    return sieve.sand.empty() ? file.stem().string() : sieve.sand;
}

}  // namespace

LabStats analyse_sieve_files(const std::vector<fs::path>& files, const fs::path& c144_limits) {
    LabStats lab;
    lab.dataset = "sieve analyses";
    lab.source = "sieve files";
    std::optional<C144Limits> limits;
    if (!c144_limits.empty()) limits = read_c144_limits(c144_limits);
    for (const fs::path& f : files)
        for (SieveAnalysis& analysis : read_sieve_csv_all(f)) {
            SandResult sand;
            sand.name = sand_name_of(analysis, f);
            sand.gradation = analyse_gradation(analysis.curve);
            add_notes(*sand.gradation, analysis.warnings);
            if (limits) sand.c144 = check_c144(analysis.curve, *limits);
            sand.sieve = std::move(analysis);
            lab.sands.push_back(std::move(sand));
        }
    return lab;
}

}  // namespace gradem::lab
