// libFuzzer target: the plain csv reader (see fuzz_common.hpp, run_fuzz.sh).
#include "lab_data/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    gradem::lab::fuzz::exercise_export(data, size, gradem::lab::ExportFormat::plain_csv);
    return 0;
}
