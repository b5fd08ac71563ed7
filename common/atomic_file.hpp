#pragma once
// Result files are written whole or not at all: the content goes to a temporary file in the
// same folder, is flushed, and is renamed over the target (atomic on POSIX file systems), so an
// interrupted run never leaves a half-written result behind.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace gradem::common {

/// Writes `content` to `path` atomically; creates the parent folder. Throws std::runtime_error
/// naming the path on failure (the temporary file is removed).
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

/// Writes a set of files that belong together (path, content): every one to its temporary file
/// first, then all are renamed, so a failure while writing leaves none of them behind. The
/// folders must exist. Throws InputError naming the file on failure (temporary files removed).
void write_files_atomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

}  // namespace gradem::common
