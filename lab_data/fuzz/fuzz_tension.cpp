// libFuzzer target: tension exports (see fuzz_common.hpp, run_fuzz.sh): the autodetected reader,
// the specimen dimensions from the metadata, and the splitting and flexural reductions, once with
// the file's dimensions alone and once with nominal ones for what the file does not state.
#include "lab_data/fuzz/fuzz_common.hpp"
#include "lab_data/tension.hpp"

namespace {

void exercise_tension(std::string_view bytes, gradem::lab::TensileTestKind kind, bool nominal) {
    using namespace gradem::lab;
    try {
        TensileSpec spec;
        spec.test = kind;
        spec.nominal_source = "command line";
        if (nominal) spec.nominal = {0.100, 0.200, 0.040, 0.040, 0.120, {}};
        (void)read_tensile_bytes(bytes, "fuzz-input", spec, ReadOptions{});
    } catch (const InputError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (auto kind : {gradem::lab::TensileTestKind::splitting, gradem::lab::TensileTestKind::flexural})
        for (bool nominal : {false, true}) exercise_tension(bytes, kind, nominal);
    return 0;
}
