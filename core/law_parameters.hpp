#pragma once
// The parameter rows of a bond law: each law's header lists its own parameters once, as
// constexpr rows over its parameter struct (Law::kParameters), and core/bond_models.hpp lists the
// laws. From these rows come the core validator (BondParams::invalid_reason), the material table
// (experiments/config/material_table.cpp: config keys, units, macro.json, calibration), the MPI wire
// format (calibrate/execution/run_message.cpp) and the benchmark's JSON rows. Config and IO paths
// only: nothing here runs per bond.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

namespace gradem {

/// Allowed values in config units: lower/upper bounds (infinite = none), each open or closed.
struct Range {
    double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
    bool lower_open = false, upper_open = false;
    [[nodiscard]] bool contains(double v) const;
    [[nodiscard]] std::string rule() const;  ///< "> 0", ">= 0", "in (0, 1]", ...
};

namespace ranges {
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr Range positive{0.0, kInf, true, false};        ///< > 0
inline constexpr Range non_negative{0.0, kInf, false, false};   ///< >= 0
inline constexpr Range unit_open_right{0.0, 1.0, false, true};  ///< in [0, 1)
inline constexpr Range unit_closed{0.0, 1.0, false, false};     ///< in [0, 1]
inline constexpr Range unit_open_left{0.0, 1.0, true, false};   ///< in (0, 1]
inline constexpr Range flag{0.0, 1.0, false, false};            ///< a yes/no as 0/1
}  // namespace ranges

/// What the calibration does with a parameter (docs/calibration.md "Homogeneity"): the
/// homogeneity acts on the stiffness and strength scales; shape parameters are dimensionless.
enum class ParameterRole : std::uint8_t { stiffness_scale, strength_scale, shape };

/// How the calibration may use a parameter.
enum class Calibration : std::uint8_t {
    none,        ///< not a calibration parameter (set in the base cube config only)
    free,        ///< a calibration parameter: fixed or free in [parameters.<key>]
    fixed_only,  ///< integer parameter: may be fixed in [parameters.<key>], never free
};

/// What the platen tests of a specimen bonded by a law cost beyond the bonded specimen at rest,
/// as `gradem calibrate --plan` prices them (calibrate/plan.cpp; docs/calibration.md "The cost
/// before the run"). A law states it as `static constexpr PlatenTestCost kPlatenTestCost`, measured
/// on calibrations of the shipped configs; a law without it is priced at the lab's shape index and
/// at the probe's cost per particle-step.
struct PlatenTestCost {
    /// The stop fraction the end below was measured at (test.stop_fraction's default) [-].
    static constexpr double kMeasuredStopFraction = 0.7;
    /// Platen strain at which a compression test ends (stress down to 0.7 × the peak) over
    /// σ_peak/E of the specimen [-]: 1.45 D for a curve of shape index D that drops soon after
    /// its peak, more for one with a long post-peak tail.
    double compression_end_over_elastic = 0.0;
    /// Platen strain at the peak over σ_peak/E [-]; a test that stops at a fraction f of the peak
    /// is taken to end at peak + (end − peak) (1 − f)/(1 − 0.7).
    double compression_peak_over_elastic = 0.0;
    /// Seconds per particle-step of a compression test up to its peak over the bonded specimen's
    /// at rest [-] (the test's own work, workers sharing the memory system), and after it (broken
    /// bonds, the contacts the cracks make).
    double pre_peak_cost_factor = 1.0;
    double post_peak_cost_factor = 1.0;
    double tension_cost_factor = 1.0;  ///< a direct-tension test's, over its whole run [-]
    /// Platen strain at the direct-tension peak over σ̄_c/Ē, the bonds' mean tensile strength
    /// over their modulus [-]: the low end of what the law's specimens reach, so that the
    /// automatic tension rate, aimed at it, keeps the rule's wave transits before every
    /// specimen's peak (experiments/config/tension_config.hpp). A law without a row: 0.5.
    double tension_peak_over_bond_strain = 0.5;
    /// Platen strain at which a direct-tension test at that rate ends over the expected peak
    /// strain above [-] (the measured peak lies beyond the expected, and the test runs on past it).
    double tension_end_over_expected = 1.6;
};

/// Typed access to one field of a law's parameter struct P, as a double (every row) and as an
/// exact integer (integer and yes/no fields).
template <class P>
struct LawField {
    double (*get)(const P&) = nullptr;
    void (*set)(P&, double) = nullptr;
    std::int64_t (*get_int)(const P&) = nullptr;  ///< integer fields only
    void (*set_int)(P&, std::int64_t) = nullptr;  ///< integer fields only
    bool integer = false;                         ///< an integral field (counts, flags)
    bool flag = false;                            ///< a bool (the config takes true/false)
};

namespace law_field_detail {
template <class M>
struct member_of;
template <class C, class F>
struct member_of<F C::*> {
    using owner = C;
    using field = F;
};
template <auto Member>
using owner_t = typename member_of<decltype(Member)>::owner;
template <auto Member>
using field_t = typename member_of<decltype(Member)>::field;

template <auto Member>
double get(const owner_t<Member>& p) {
    return static_cast<double>(p.*Member);
}
template <auto Member>
void set(owner_t<Member>& p, double v) {
    using F = field_t<Member>;
    if constexpr (std::is_integral_v<F>) p.*Member = static_cast<F>(std::llround(v));
    else p.*Member = v;
}
template <auto Member>
std::int64_t get_int(const owner_t<Member>& p) {
    return static_cast<std::int64_t>(p.*Member);
}
template <auto Member>
void set_int(owner_t<Member>& p, std::int64_t v) {
    using F = field_t<Member>;
    if constexpr (std::is_same_v<F, bool>) p.*Member = v != 0;
    else p.*Member = static_cast<F>(v);
}
}  // namespace law_field_detail

/// The accessors of a member of a law's parameter struct: law_field<&LawParams::member>.
template <auto Member>
inline constexpr LawField<law_field_detail::owner_t<Member>> law_field = [] {
    namespace d = law_field_detail;
    using F = d::field_t<Member>;
    LawField<d::owner_t<Member>> f{d::get<Member>, d::set<Member>};
    if constexpr (std::is_integral_v<F>) {
        f.get_int = d::get_int<Member>;
        f.set_int = d::set_int<Member>;
        f.integer = true;
        f.flag = std::is_same_v<F, bool>;
    }
    return f;
}();

/// One parameter of a bond law: its config key (also its calibration name, its macro.json name
/// in the law's "si" group, and the member it sets), unit, SI conversion, range, description,
/// and what the calibration may do with it. The default value is the struct's member initializer.
template <class P>
struct LawParameter {
    std::string_view key;          ///< [material] config key = calibration parameter name = macro.json key
    std::string_view unit = "-";   ///< config unit
    std::string_view description;  ///< what it is (README, messages)
    LawField<P> field;             ///< the member of P it is
    std::string_view core_field;   ///< how the validator names it ("<Law>Params::<member>")
    double to_si = 1.0;            ///< SI value = config value × to_si
    Range range;                   ///< allowed values, config units
    Calibration calibration = Calibration::none;
    ParameterRole role = ParameterRole::shape;  ///< a law's own parameters are dimensionless: shape
    double lower = 0.0, upper = 0.0;            ///< default calibration bounds, config units
    bool log_scale = false;                     ///< default calibration scale
};

/// The parameters of a law that has none of its own (the parallel bond).
struct NoLawParams {};

}  // namespace gradem
