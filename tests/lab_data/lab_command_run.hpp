#pragma once
// `gradem lab` run in-process for the tests: its exit status and what it printed, and a fresh
// scratch folder per test.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/lab_command.hpp"

namespace gradem::test {

struct LabRun {
    int status = 0;
    std::string out, err;
};

/// run_lab_command(args) with std::cout and std::cerr captured.
inline LabRun run_lab(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    auto* old_out = std::cout.rdbuf(out.rdbuf());
    auto* old_err = std::cerr.rdbuf(err.rdbuf());
    LabRun r;
    r.status = app::run_lab_command(args);
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    r.out = out.str();
    r.err = err.str();
    return r;
}

/// An empty, not yet created folder in the temp directory, unique to this process and `name`.
inline std::filesystem::path lab_scratch(const std::string& prefix, const std::string& name) {
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() / (prefix + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    return p;
}

}  // namespace gradem::test
