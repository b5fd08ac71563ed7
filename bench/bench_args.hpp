#pragma once
// The command-line reading the bench programs share (gradem-bench, gradem-model-sweep): walk
// argv option by option, take an option's value from the next argument, and read comma lists
// of numbers, each failure an std::invalid_argument naming the option and the text.
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gradem::bench {

/// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
inline std::vector<std::string> split_list(const std::string& text, char separator = ',') {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, separator);)
        if (!item.empty()) out.push_back(item);
    return out;
}

/// The whole of `text` as a number (strtod: "1e5", "0.25"); `what` names it in the error.
inline double parse_number(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw std::invalid_argument(what + ": '" + text + "' is not a number");
    return v;
}

/// A comma list of numbers, each cast to T ("20000,2e5" -> {20000, 200000}).
template <class T>
std::vector<T> parse_number_list(const std::string& text, const std::string& what) {
    std::vector<T> out;
    for (const std::string& item : split_list(text)) out.push_back(static_cast<T>(parse_number(item, what)));
    if (out.empty()) throw std::invalid_argument(what + ": expected a comma-separated list of numbers, got '" + text + "'");
    return out;
}

/// Walks argv[1..]: `for (ArgReader args(argc, argv); args.next();)`, then arg() is the current
/// argument and value() consumes the next one as its value.
class ArgReader {
public:
    ArgReader(int argc, char** argv) : argc_(argc), argv_(argv) {}
    bool next() { return ++k_ < argc_ && (current_ = argv_[k_], true); }
    [[nodiscard]] const std::string& arg() const { return current_; }
    std::string value() {
        if (k_ + 1 >= argc_) throw std::invalid_argument(current_ + " needs a value");
        return argv_[++k_];
    }

private:
    int argc_;
    char** argv_;
    int k_ = 0;
    std::string current_;
};

}  // namespace gradem::bench
