#include "lab_data/c144.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace gradem::lab {
namespace {

constexpr double kNo50 = 300e-6, kNo100 = 150e-6;  // m

std::string pct(double f) {
    std::ostringstream os;
    os.precision(3);
    os << std::fixed << f * 100;
    std::string s = os.str();
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s + " %";
}

std::string label(const C144SieveCheck& c) {
    std::ostringstream os;
    os << (c.designation.empty() ? "" : c.designation + " ") << "(" << c.opening_m * 1e3 << " mm)";
    return os.str();
}

}  // namespace

C144Verdict check_c144(const GradationCurve& curve, const C144Limits& limits) {
    C144Verdict v;
    for (const auto& l : limits.sieves) {
        C144SieveCheck c{l.designation, l.opening_m, std::numeric_limits<double>::quiet_NaN(), l.min_passing, l.max_passing};
        if (const auto i = curve.find_sieve(l.opening_m)) {
            c.present = true;
            c.passing = curve.passing[*i];
        } else if (l.opening_m > curve.size_m.back() && curve.passing.back() >= 1.0) {
            c.present = true;  // above the coarsest sieve that already passes everything
            c.passing = 1.0;
        }
        c.ok = c.present && c.passing >= l.min_passing - 1e-12 && c.passing <= l.max_passing + 1e-12;
        if (!c.present) v.violations.push_back("sieve " + label(c) + " is missing from the analysis");
        else if (!c.ok)
            v.violations.push_back("sieve " + label(c) + ": " + pct(c.passing) + " passing, limits " + pct(l.min_passing) + " to " +
                                   pct(l.max_passing));
        v.sieves.push_back(c);
    }
    v.retained_no50_to_no100 = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 1; i < v.sieves.size(); ++i) {
        const auto& coarse = v.sieves[i - 1];
        const auto& fine = v.sieves[i];
        if (!coarse.present || !fine.present) continue;
        const double retained = coarse.passing - fine.passing;
        v.max_retained_consecutive = std::max(v.max_retained_consecutive, retained);
        if (retained > limits.max_retained_between_consecutive + 1e-12)
            v.violations.push_back(pct(retained) + " retained between consecutive sieves " + label(coarse) + " and " + label(fine) +
                                   " (at most " + pct(limits.max_retained_between_consecutive) + ")");
        const bool no50_no100 = std::abs(coarse.opening_m - kNo50) <= 0.03 * kNo50 && std::abs(fine.opening_m - kNo100) <= 0.03 * kNo100;
        if (!no50_no100) continue;
        v.retained_no50_to_no100 = retained;
        if (retained > limits.max_retained_no50_to_no100 + 1e-12)
            v.violations.push_back(pct(retained) + " retained between the No. 50 and No. 100 sieves (at most " +
                                   pct(limits.max_retained_no50_to_no100) + ")");
    }
    v.conforms = v.violations.empty();
    return v;
}

}  // namespace gradem::lab
