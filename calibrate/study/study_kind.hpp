#pragma once
// THE list of study kinds. A kind is one file, calibrate/study/kinds/<kind>.cpp, defining
// `const StudyKindSpec <kind>_study` (its own [study] keys, the specimens its cases run, and
// its runs and analysis), plus one row KIND(<kind>) in GRADEM_STUDY_KINDS below; its report
// figures are one Python module, reports/html/study_<kind>.py (docs/extending.md "A study
// kind"). The StudyKind enum, its names, the config reader's key checks, the dispatch of
// run_study and the MPI job's case list derive from these rows; what each kind answers is in
// docs/calibration.md "Studies" and experiments/README.md.
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/named_enum.hpp"

// clang-format off
#define GRADEM_STUDY_KINDS(KIND) \
    KIND(gradation_effect)       \
    KIND(resolution)             \
    KIND(fines_truncation)       \
    KIND(sensitivity)            \
    KIND(model_form)
// clang-format on

namespace gradem::common::toml_io {
class Section;
struct Context;
}  // namespace gradem::common::toml_io

namespace gradem::cal {

#define GRADEM_STUDY_KIND_ENUMERATOR(name) name,
/// One enumerator per row of GRADEM_STUDY_KINDS, in order.
enum class StudyKind { GRADEM_STUDY_KINDS(GRADEM_STUDY_KIND_ENUMERATOR) };
#undef GRADEM_STUDY_KIND_ENUMERATOR

#define GRADEM_STUDY_KIND_ROW(name) EnumName<StudyKind>{StudyKind::name, #name},
/// The `[study] kind` names (common/named_enum.hpp).
constexpr auto enum_name_table(StudyKind) {
    return std::to_array({GRADEM_STUDY_KINDS(GRADEM_STUDY_KIND_ROW)});
}
#undef GRADEM_STUDY_KIND_ROW

struct StudyConfig;
struct CalibratedPoint;
struct CalibrationProblem;
struct StudyResult;
class StudyRunner;

/// The [study] table while a study file is read: the kind reads its own keys from it.
struct StudyKeys {
    common::toml_io::Section& section;
    common::toml_io::Context& context;
    StudyConfig& config;
    /// The line of key `study.<key>` (0 when it was not given).
    [[nodiscard]] int line(const char* key) const;
};

/// What a study kind is (one per file in calibrate/study/kinds/).
struct StudyKindSpec {
    /// The [study] keys that belong to this kind besides kind, calibration(s) and seeds; a
    /// study of another kind refuses them, naming the kinds they belong to.
    std::vector<std::string> keys;
    /// Reads and checks those keys into the config (InputError naming the file, line and key).
    void (*read_keys)(StudyKeys& keys);
    /// true: the kind studies one calibration (study.calibration) on the study's packing seeds;
    /// false: several (study.calibrations), each on its own seeds.
    bool one_calibration = true;
    /// The specimens its compression cases run, before as_study_problem (the MPI job's case
    /// models); nullptr: none (its runs, if any, run on threads of rank 0).
    std::vector<CalibrationProblem> (*problems)(const CalibratedPoint& point, const StudyConfig& config);
    /// Runs its cases through `runner` and fills result.tables, result.data and result.verdict.
    void (*run)(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result);
    /// What its runs are, for study.md's "DEM runs" line ("" for cube tests on the study's seeds).
    const char* runs_note = "";
};

#define GRADEM_STUDY_KIND_SPEC(name) extern const StudyKindSpec name##_study;
GRADEM_STUDY_KINDS(GRADEM_STUDY_KIND_SPEC)
#undef GRADEM_STUDY_KIND_SPEC

/// The kind's spec.
inline const StudyKindSpec& study_kind(StudyKind kind) {
#define GRADEM_STUDY_KIND_CASE(name) \
    case StudyKind::name: return name##_study;
    switch (kind) { GRADEM_STUDY_KINDS(GRADEM_STUDY_KIND_CASE) }
#undef GRADEM_STUDY_KIND_CASE
    throw std::invalid_argument("study_kind: not a registered StudyKind");
}

}  // namespace gradem::cal
