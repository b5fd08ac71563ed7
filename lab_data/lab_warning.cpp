#include "lab_data/lab_warning.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "common/number_format.hpp"

namespace gradem::lab {
namespace {

std::string joined(const std::vector<std::string>& items, const char* separator) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
    return out;
}

std::string millimetres(double metres) { return common::format_significant(metres * 1e3, 6); }

// "50 x 50 x 50 mm (width x depth x height) from F [specimen] width_mm, depth_mm, height_mm",
// or "height 50 mm from ..." for one dimension: the dimensions of one origin.
std::string nominal_group(const std::vector<const NominalDimension*>& group) {
    std::vector<std::string> values, names, keys;
    for (const NominalDimension* d : group) {
        values.push_back(millimetres(d->value_m));
        names.push_back(d->name);
        if (!d->key.empty()) keys.push_back(d->key);
    }
    std::string text = group.size() == 1 ? names.front() + " " + values.front() + " mm"
                                         : joined(values, " x ") + " mm (" + joined(names, " x ") + ")";
    text += " from " + group.front()->origin;
    if (!keys.empty()) text += " " + joined(keys, ", ");
    return text;
}

std::string geometry_message(const LabWarning& w) {
    std::vector<std::string> names;
    for (const auto& d : w.dimensions) names.push_back(d.name);
    std::string text = w.nothing_from_file ? "no specimen dimensions in the file" : "specimen " + joined(names, ", ") + " not in the file";
    // Consecutive dimensions of one origin are told together.
    std::vector<std::string> groups;
    for (std::size_t i = 0; i < w.dimensions.size();) {
        std::vector<const NominalDimension*> group{&w.dimensions[i]};
        while (++i < w.dimensions.size() && w.dimensions[i].origin == group.front()->origin) group.push_back(&w.dimensions[i]);
        groups.push_back(nominal_group(group));
    }
    return text + "; nominal " + joined(groups, "; ");
}

}  // namespace

std::string describe_lines(const std::vector<int>& lines) {
    std::vector<std::string> runs;
    std::size_t i = 0;
    for (; i < lines.size() && runs.size() < kShownLineRanges;) {
        std::size_t j = i;
        while (j + 1 < lines.size() && lines[j + 1] == lines[j] + 1) ++j;
        runs.push_back(j == i ? std::to_string(lines[i]) : std::to_string(lines[i]) + "-" + std::to_string(lines[j]));
        i = j + 1;
    }
    if (i < lines.size()) runs.emplace_back("...");
    return (lines.size() == 1 ? "line " : "lines ") + joined(runs, ", ");
}

std::string LabWarning::message() const {
    if (kind == Kind::nominal_geometry) return geometry_message(*this);
    return std::to_string(count()) + (count() == 1 ? " row" : " rows") + " skipped (" + describe_lines(lines) + ": " + reason + ")";
}

std::string LabWarning::line() const { return "warning: " + file + ": " + message(); }

LabWarning rows_skipped(const std::string& file, std::vector<int> lines, const std::string& reason) {
    std::sort(lines.begin(), lines.end());
    LabWarning w;
    w.kind = LabWarning::Kind::rows_skipped;
    w.file = file;
    w.lines = std::move(lines);
    w.reason = reason;
    return w;
}

LabWarning nominal_geometry(const std::string& file, std::vector<NominalDimension> dimensions, bool nothing_from_file) {
    LabWarning w;
    w.kind = LabWarning::Kind::nominal_geometry;
    w.file = file;
    w.dimensions = std::move(dimensions);
    w.nothing_from_file = nothing_from_file;
    return w;
}

void WarningSink::start(Printer printer) {
    const std::lock_guard<std::mutex> lock(mutex_);
    printer_ = std::move(printer);
    seen_.clear();
}

void WarningSink::add(const LabWarning& warning) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!seen_.insert(warning.line()).second || !printer_) return;
    printer_(warning);
}

void WarningSink::print_to_stderr(const LabWarning& warning) {
    std::fprintf(stderr, "%s\n", warning.line().c_str());
}

WarningSink& warning_sink() {
    static WarningSink sink;
    return sink;
}

void report(const LabWarning& warning, std::vector<LabWarning>& records, std::vector<std::string>& notes) {
    if (warning.kind == LabWarning::Kind::rows_skipped && warning.lines.empty()) return;
    if (warning.kind == LabWarning::Kind::nominal_geometry && warning.dimensions.empty()) return;
    warning_sink().add(warning);
    records.push_back(warning);
    notes.push_back(warning.message());
}

}  // namespace gradem::lab
