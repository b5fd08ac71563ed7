#pragma once
// Reading a JSON result file another command wrote (lab_results.json, macro.json,
// summary.json): one reader, so every such file that is missing or not JSON is refused alike,
// naming the file.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/input_error.hpp"

namespace gradem::common {

/// The document in `file`; InputError "cannot read <what>" when it cannot be opened, "not valid
/// JSON (<what>): ..." when it does not parse. `what` names the file's role ("the lab results").
/// Json: nlohmann::json, or nlohmann::ordered_json to keep the file's key order.
template <typename Json = nlohmann::json>
Json read_json_file(const std::filesystem::path& file, const std::string& what) {
    std::ifstream in(file);
    if (!in) throw InputError(file.string(), 0, "cannot read " + what);
    try {
        return Json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(file.string(), 0, "not valid JSON (" + what + "): " + e.what());
    }
}

}  // namespace gradem::common
