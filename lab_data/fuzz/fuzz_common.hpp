#pragma once
// Shared body of the reader fuzz targets: read the bytes as one export format, interpret the
// columns, reduce the curve. InputError is the expected outcome for most inputs; anything else
// (a crash, another exception, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/input_error.hpp"
#include "lab_data/curve_reduction.hpp"
#include "lab_data/lab_warning.hpp"
#include "lab_data/load_frame_test.hpp"

namespace gradem::lab::fuzz {

/// The readers' warnings (rows skipped, nominal dimensions) are dropped, not printed per input.
inline const bool kWarningsDropped = (warning_sink().start({}), true);

inline void exercise_export(const std::uint8_t* data, std::size_t size, ExportFormat format) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        ReadOptions options;
        options.format = format;
        const LoadFrameTest test = read_load_frame_bytes(bytes, "fuzz-input", options);
        ReductionOptions reduction;
        reduction.fit_popovics = false;
        (void)reduce_curve(to_stress_strain(test), reduction);
    } catch (const InputError&) {
    }
}

}  // namespace gradem::lab::fuzz
