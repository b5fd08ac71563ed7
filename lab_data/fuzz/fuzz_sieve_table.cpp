// libFuzzer target: the sieve-analysis reader in every layout it takes (header detection,
// designations, several sands, Pan and Total rows), the single-sand selection, the ASTM C144
// limits reader (fast-cpp-csv-parser layer), the gradation indices and the C144 check on
// whatever parses.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/input_error.hpp"
#include "lab_data/c144.hpp"
#include "lab_data/fuzz/fuzz_common.hpp"
#include "lab_data/sieve_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace gradem::lab;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    (void)looks_like_sieve_csv(bytes);
    try {
        C144Limits limits;
        limits.sieves = {{"No. 30", 0.6e-3, 0.4, 0.75, 0}, {"No. 50", 0.3e-3, 0.1, 0.35, 0}, {"No. 100", 0.15e-3, 0.02, 0.15, 0}};
        const std::vector<SieveAnalysis> all = parse_sieve_csv_all(bytes, "fuzz-input");
        for (const SieveAnalysis& s : all) {
            (void)analyse_gradation(s.curve);
            (void)check_c144(s.curve, limits);
        }
        (void)parse_sieve_csv(bytes, "fuzz-input", all.back().sand);  // selection by name
    } catch (const InputError&) {
    }
    try {
        (void)parse_c144_limits(bytes, "fuzz-input");
    } catch (const InputError&) {
    }
    return 0;
}
