#pragma once
// ASTM C144 conformance of a sand's gradation: percent passing within the limits sieve by
// sieve, at most 50 % retained between two consecutive listed sieves, at most 25 % between
// the No. 50 and No. 100 sieves (C144 §4 [check clause numbers against the edition in use]).
// C144 §4.4 allows non-conforming sand when the mortar meets ASTM C270; the verdict is
// reported, not enforced.

#include <string>
#include <vector>

#include "lab_data/gradation.hpp"
#include "lab_data/sieve_table.hpp"

namespace gradem::lab {

struct C144SieveCheck {
    std::string designation;
    double opening_m = 0;
    double passing = 0;  ///< of the sand at this sieve (NaN when the analysis lacks it)
    double min_passing = 0, max_passing = 1;
    bool present = false;  ///< the analysis has a sieve within 3 % of this opening
    bool ok = false;
};

struct C144Verdict {
    bool conforms = false;
    std::vector<C144SieveCheck> sieves;   ///< coarsest first
    std::vector<std::string> violations;  ///< one sentence each
    double max_retained_consecutive = 0;  ///< largest fraction retained between consecutive listed sieves
    double retained_no50_to_no100 = 0;    ///< fraction retained between 300 µm and 150 µm (NaN if absent)
};

C144Verdict check_c144(const GradationCurve& curve, const C144Limits& limits);

}  // namespace gradem::lab
