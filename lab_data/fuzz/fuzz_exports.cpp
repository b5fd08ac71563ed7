// libFuzzer target: every export reader (see fuzz_common.hpp, run_fuzz.sh). The first byte
// picks the format among "auto" and every row of GRADEM_EXPORT_FORMATS, so a new format is
// fuzzed without a target of its own; the rest of the input is the file.
#include <string>
#include <vector>

#include "lab_data/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace gradem;
    static const std::vector<std::string> names = enum_names<lab::ExportFormat>();
    if (size == 0) return 0;
    const lab::ExportFormat format = *parse_enum<lab::ExportFormat>(names[data[0] % names.size()]);
    lab::fuzz::exercise_export(data + 1, size - 1, format);
    return 0;
}
