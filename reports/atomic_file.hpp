#pragma once
// Result files are written whole or not at all: the content goes to a temporary file in the
// same folder, is flushed, and is renamed over the target (atomic on POSIX file systems), so an
// interrupted run never leaves a half-written result behind.
#include <filesystem>
#include <string>

namespace gradem::report {

/// Writes `content` to `path` atomically; creates the parent folder. Throws std::runtime_error
/// naming the path on failure (the temporary file is removed).
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace gradem::report
