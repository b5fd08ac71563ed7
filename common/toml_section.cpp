#include "common/toml_section.hpp"

#include <algorithm>

#include "common/text_file.hpp"

namespace gradem::common::toml_io {

toml::table parse_toml_file(const fs::path& file, Context& ctx) {
    ctx.file = file.string();
    ctx.dir = fs::absolute(file).parent_path();
    const std::string text = decode_text(read_file_bytes(file)).utf8;
    try {
        return toml::parse(text, ctx.file);
    } catch (const toml::parse_error& e) {
        throw InputError(ctx.file, static_cast<int>(e.source().begin.line), std::string(e.description()));
    }
}

void check_tables(const Context& ctx, const toml::table& root, const std::vector<std::string>& known_tables) {
    for (auto&& [key, n] : root) {
        const std::string k(key.str());
        if (std::find(known_tables.begin(), known_tables.end(), k) != known_tables.end()) continue;
        std::string known;
        for (const auto& t : known_tables) known += (known.empty() ? "" : ", ") + t;
        throw InputError(ctx.file, line_of(n), (n.is_table() ? "unknown table '[" + k + "]'" : "unknown key '" + k + "'") +
                                                   " (known tables: " + known + ")");
    }
}

}  // namespace gradem::common::toml_io
