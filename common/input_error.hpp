#pragma once
// Errors at the input boundary: every problem with a user's file (lab export,
// sieve table, config, study) is an InputError whose message starts with "file:line: " (or
// "file: " when no line applies), so the user can jump straight to the offending cell or key.

#include <stdexcept>
#include <string>

namespace gradem::common {

class InputError : public std::runtime_error {
public:
    /// line <= 0 means "no particular line" and is left out of the message.
    InputError(const std::string& file, int line, const std::string& what)
        : std::runtime_error(format(file, line, what)), file_(file), line_(line) {}

    [[nodiscard]] const std::string& file() const noexcept { return file_; }
    [[nodiscard]] int line() const noexcept { return line_; }

    static std::string format(const std::string& file, int line, const std::string& what) {
        return line > 0 ? file + ":" + std::to_string(line) + ": " + what : file + ": " + what;
    }

private:
    std::string file_;
    int line_ = 0;
};

/// "column 'Axial Force': " — the prefix used for every cell-level message.
inline std::string column_prefix(const std::string& column) { return "column '" + column + "': "; }

}  // namespace gradem::common

// lab_data's readers name these unqualified (lab::InputError is the same type, not a copy).
namespace gradem::lab {
using common::column_prefix;
using common::InputError;
}  // namespace gradem::lab
