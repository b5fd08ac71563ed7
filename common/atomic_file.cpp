#include "common/atomic_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

#include "common/input_error.hpp"

namespace gradem::common {
namespace {

namespace fs = std::filesystem;

/// "<path>.tmp.<pid>": next to the target (same file system, so rename is atomic), and no two
/// processes writing the same result share one.
fs::path temporary_name(const fs::path& path) { return path.string() + ".tmp." + std::to_string(::getpid()); }

/// Writes and flushes `content` into `temp`; false when any byte could not be written.
bool write_whole(const fs::path& temp, const std::string& content) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    return static_cast<bool>(out);
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& content) {
    std::error_code ec;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
    if (ec) throw std::runtime_error(path.string() + ": cannot create folder: " + ec.message());
    const fs::path temp = temporary_name(path);
    if (!write_whole(temp, content)) {
        fs::remove(temp, ec);
        throw std::runtime_error(temp.string() + ": cannot write");
    }
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw std::runtime_error(path.string() + ": cannot move the finished file into place");
    }
}

void write_files_atomically(const std::vector<std::pair<fs::path, std::string>>& files) {
    std::vector<fs::path> temps;
    auto remove_temps = [&] {
        std::error_code ec;
        for (const auto& t : temps) fs::remove(t, ec);
    };
    for (const auto& [path, content] : files) {
        temps.push_back(temporary_name(path));
        if (!write_whole(temps.back(), content)) {
            remove_temps();
            throw InputError(temps.back().string(), 0, "cannot write file");
        }
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        fs::rename(temps[i], files[i].first, ec);
        if (ec) {
            remove_temps();
            throw InputError(files[i].first.string(), 0, "cannot rename the temporary file into place: " + ec.message());
        }
    }
}

}  // namespace gradem::common
