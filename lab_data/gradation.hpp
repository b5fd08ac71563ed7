#pragma once
// Grain-size distribution of a sand: the cumulative curve that specimen genesis samples by
// mass, and the indices that describe it (D-values, Cu, Cc, USCS group, fineness modulus).

#include <optional>
#include <string>
#include <vector>

namespace gradem::lab {

/// Cumulative mass fraction passing versus sieve opening.
/// Invariants (checked by invalid_reason()): sizes strictly ASCENDING (finest sieve first),
/// in metres, > 0; passing fractions in [0, 1] and non-decreasing with size.
/// Between sieves the curve is interpolated linearly in log(size) (the usual semi-log
/// gradation plot). Below the finest sieve the distribution is unknown: the fraction passing
/// the finest sieve (the pan, "fines") lies somewhere below it.
struct GradationCurve {
    std::vector<double> size_m;            ///< sieve openings, ascending [m]
    std::vector<double> passing;           ///< cumulative mass fraction passing each opening [0, 1]
    std::vector<std::string> designation;  ///< "#4", "No. 200", ... (may be empty strings)

    /// Builds a curve from sieve points in any order (sorted here). Throws std::invalid_argument
    /// with invalid_reason() when the points violate the invariants.
    static GradationCurve from_points(std::vector<double> size_m, std::vector<double> passing,
                                      std::vector<std::string> designation = {});

    [[nodiscard]] std::optional<std::string> invalid_reason() const;

    /// Fraction of the mass finer than `size_m`: 0 for size <= 0, the finest sieve's passing
    /// below the finest sieve, the coarsest sieve's passing above the coarsest sieve.
    [[nodiscard]] double passing_fraction(double size_m) const;

    /// Smallest size at which the curve reaches `fraction` (D-value, e.g. 0.10 -> D10), by
    /// log-size interpolation. NaN when `fraction` lies below the finest sieve's passing (inside
    /// the fines) or above the coarsest sieve's passing.
    [[nodiscard]] double size_at_passing(double fraction) const;

    /// Index of the sieve within `relative_tolerance` of `size_m` (e.g. 0.595 mm for 0.600 mm).
    [[nodiscard]] std::optional<std::size_t> find_sieve(double size_m, double relative_tolerance = 0.03) const;
};

struct GradationIndices {
    double d10_m = 0, d30_m = 0, d50_m = 0, d60_m = 0;  ///< NaN where not determinable
    double cu = 0;                   ///< coefficient of uniformity D60/D10
    double cc = 0;                   ///< coefficient of curvature D30²/(D10·D60)
    double gravel_fraction = 0;      ///< retained on 4.75 mm (No. 4)
    double sand_fraction = 0;        ///< passing 4.75 mm, retained on 75 µm
    double fines_fraction = 0;       ///< passing 75 µm (No. 200)
    double fineness_modulus = 0;     ///< ASTM C125: Σ cumulative % retained on the standard sieves / 100
    std::string uscs;                ///< ASTM D2487 group symbol, e.g. "SP"
    std::string uscs_name;           ///< e.g. "poorly graded sand"
    std::vector<std::string> notes;  ///< interpolations and assumptions made
};

/// ASTM D2487 (USCS) for coarse-grained soils from the curve alone: S or G by the larger of the
/// sand and gravel fractions; W when Cu >= 6 (sand) / 4 (gravel) and 1 <= Cc <= 3, else P;
/// 5–12 % fines gives a dual symbol whose second part needs plasticity ("SP-SM or SP-SC");
/// > 12 % fines "SM or SC"; >= 50 % fines is fine-grained and not classified here.
/// Fineness modulus per ASTM C125 over 150 µm, 300 µm, 600 µm, 1.18, 2.36, 4.75, 9.5, 19,
/// 37.5, 75, 150 mm (sieves within 3 % count as the same sieve, e.g. 0.595 / 0.149 mm).
GradationIndices analyse_gradation(const GradationCurve& curve);

}  // namespace gradem::lab
