#pragma once
// Sample statistics for replicate specimens, Welch's unequal-variance t-test with effect sizes,
// and the ASTM C109 permissible-range check for cubes of one batch.

#include <cstddef>
#include <string>
#include <vector>

namespace gradem::lab {

struct SampleSummary {
    std::size_t n = 0;
    double mean = 0;
    double std = 0;  ///< sample standard deviation (n − 1 in the denominator); NaN for n < 2
    double cv = 0;   ///< std / mean
    double min = 0, max = 0;
};

/// Summary of the finite values (NaN entries are skipped and not counted).
SampleSummary summarize(const std::vector<double>& values);

/// I_x(a, b), the regularized incomplete beta function (continued fraction, Lentz's method).
double regularized_incomplete_beta(double a, double b, double x);

/// Two-sided p-value of Student's t distribution: P(|T| >= |t|) = I_{ν/(ν+t²)}(ν/2, 1/2).
double student_t_two_sided_p(double t, double dof);

struct WelchTest {
    std::size_t n1 = 0, n2 = 0;
    double mean_difference = 0;  ///< mean(a) − mean(b)
    double std_error = 0;        ///< sqrt(s1²/n1 + s2²/n2), of the difference
    double t = 0;                ///< (m1 − m2) / std_error
    double dof = 0;              ///< Welch–Satterthwaite degrees of freedom
    double p_value = 0;          ///< two-sided
    double cohens_d = 0;         ///< difference / pooled standard deviation
    double hedges_g = 0;         ///< d × (1 − 3/(4(n1 + n2) − 9)), small-sample corrected
};

/// Needs at least 2 finite values in each sample with some spread; otherwise t, p, d are NaN.
WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b);
/// The same from the samples' summaries (n, mean, std), e.g. lab statistics without the values.
WelchTest welch_t_test_of_summaries(const SampleSummary& a, const SampleSummary& b);

/// ASTM C109/C109M (faulty specimens and retests) [check clause numbers]: the maximum
/// permissible range between specimens from the same batch tested at the same age is 8.7 %
/// of the average for three cubes and 7.6 % for two. Returns NaN for other group sizes.
double c109_permissible_range(std::size_t cubes);

/// One group of (up to) three cubes of a batch, taken in test order.
struct RangeCheck {
    std::vector<std::size_t> members;   ///< indices into the batch's strengths
    double mean = 0;
    double range_fraction = 0;          ///< (max − min) / mean of all members
    double permissible_fraction = 0;
    bool ok = true;                     ///< range within the permissible range
    long discarded = -1;                ///< member discarded (most different from the mean), or −1
    bool retest_required = false;       ///< the remaining two still exceed 7.6 %
};

/// Splits a batch into consecutive groups of `group_size` (3: as C109 intends; a last group of
/// two is checked against 7.6 %, a single leftover cube is not checked). If a group of three
/// exceeds 8.7 %, the cube most different from the average is discarded and the other two
/// are checked against 7.6 %, as C109 prescribes.
std::vector<RangeCheck> c109_range_checks(const std::vector<double>& strengths, std::size_t group_size = 3);

}  // namespace gradem::lab
