#include "reports/atomic_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace gradem::report {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
    if (ec) throw std::runtime_error(path.string() + ": cannot create folder: " + ec.message());
    const fs::path temp = path.string() + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out << content;
        out.flush();
        if (!out) {
            fs::remove(temp, ec);
            throw std::runtime_error(temp.string() + ": cannot write");
        }
    }
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw std::runtime_error(path.string() + ": cannot move the finished file into place");
    }
}

}  // namespace gradem::report
