#pragma once
// Input files of the tests that read configs: writing one, and checking that a bad one is
// refused with an InputError naming the file, the line and what was expected.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "common/input_error.hpp"

namespace gradem::test {

/// Writes `text` to `path` (folders made); returns the path.
inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

/// `read()` must throw a common::InputError at `line` whose message names `file` and contains
/// every one of `parts`.
template <typename Read>
void require_input_error(Read&& read, const std::filesystem::path& file, int line, std::initializer_list<std::string> parts) {
    try {
        read();
        FAIL("accepted " << file);
    } catch (const common::InputError& e) {
        INFO(e.what());
        CHECK(e.line() == line);
        CHECK_THAT(e.what(), Catch::Matchers::Contains(file.string()));
        for (const auto& p : parts) CHECK_THAT(e.what(), Catch::Matchers::Contains(p));
    }
}

}  // namespace gradem::test
