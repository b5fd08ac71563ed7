// common/toml_section: typed reads of one TOML table with unit conversion and defaults, and
// every kind of bad input (parse error, unknown table or key, wrong type, integer out of
// range) rejected naming the file, line and key.
#include "../input_files.hpp"
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "common/toml_section.hpp"

using namespace gradem::common;
using namespace gradem::common::toml_io;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using gradem::test::write_file;

/// `read` on the parsed `text` must throw an InputError at `line` containing every part.
template <typename Read>
void require_rejected(const fs::path& file, const std::string& text, Read read, int line, std::initializer_list<std::string> parts) {
    write_file(file, text);
    gradem::test::require_input_error(
        [&] {
            Context ctx;
            read(ctx, parse_toml_file(file, ctx));
        },
        file, line, parts);
}

}  // namespace

TEST_CASE("Section: values converted to SI, defaults kept and recorded, paths relative to the file", "[common]") {
    gradem::test::TempDir dir("common-toml");
    const fs::path file = write_file(dir.path / "c.toml", "[a]\nlength_mm = 2.5\ncount = 3\nflag = true\nname = \"x\"\nfile = \"d/e.csv\"\n");
    Context ctx;
    const toml::table root = parse_toml_file(file, ctx);
    Section a(ctx, root, "a");
    double length = 0.0, width = 0.004;
    int count = 0;
    bool flag = false;
    std::string name;
    fs::path path;
    a.real("length_mm", length, 1e-3);
    a.real("width_mm", width, 1e-3);  // absent: the default (4 mm) stays
    a.integer("count", count, 1);
    a.boolean("flag", flag);
    a.text("name", name);
    a.path("file", path);
    a.finish();
    CHECK(length == 2.5e-3);
    CHECK(width == 0.004);
    CHECK(count == 3);
    CHECK(flag);
    CHECK(name == "x");
    CHECK(path == (fs::absolute(dir.path) / "d" / "e.csv").lexically_normal());
    CHECK(ctx.keys.at("a.length_mm").line == 2);
    CHECK(ctx.keys.at("a.length_mm").converted);
    CHECK(ctx.keys.at("a.width_mm").text == "4.0 (default)");  // shown in the file's unit
}

TEST_CASE("Section: bad input names the file, the line and the key", "[common]") {
    gradem::test::TempDir dir("common-toml-bad");
    const fs::path file = dir.path / "bad.toml";
    auto read_a = [](Context& ctx, const toml::table& root) {
        Section a(ctx, root, "a");
        double x = 0.0;
        std::uint8_t n = 0;
        a.real("x", x);
        a.integer("n", n, 1);
        a.finish();
    };
    require_rejected(file, "[a]\nx = \"one\"\n", read_a, 2, {"key 'a.x' = \"one\"", "expected a number"});
    require_rejected(file, "[a]\nx = 1\nn = 0\n", read_a, 3, {"key 'a.n' = 0", "violates in [1, 255]"});
    require_rejected(file, "[a]\nx = 1\nn = 300\n", read_a, 3, {"violates in [1, 255]"});
    require_rejected(file, "[a]\nx = 1\n\ny = 2\n", read_a, 4, {"unknown key 'a.y'", "known: n, x"});
    require_rejected(file, "a = 3\n", read_a, 1, {"'a' must be a table ([a])"});
    require_rejected(file, "[a]\nx = = 1\n", read_a, 2, {});  // a parse error keeps its line
    auto tables = [](Context& ctx, const toml::table& root) { check_tables(ctx, root, {"a", "b"}); };
    require_rejected(file, "[a]\n[c]\nk = 1\n", tables, 2, {"unknown table '[c]'", "known tables: a, b"});
}

TEST_CASE("parse_toml_file reads a UTF-16 file like a UTF-8 one", "[common]") {
    gradem::test::TempDir dir("common-toml-utf16");
    const std::string text = "[a]\nname = \"caf\xC3\xA9\"\n";
    std::string utf16 = "\xFF\xFE";
    for (unsigned char c : std::string("[a]\nname = \"caf")) utf16 += std::string{static_cast<char>(c), '\0'};
    utf16 += std::string("\xE9\x00\"\x00\n\x00", 6);
    Context ctx8, ctx16;
    const toml::table a = parse_toml_file(write_file(dir.path / "u8.toml", text), ctx8);
    const toml::table b = parse_toml_file(write_file(dir.path / "u16.toml", utf16), ctx16);
    CHECK(a["a"]["name"].value<std::string>() == b["a"]["name"].value<std::string>());
    CHECK(b["a"]["name"].value<std::string>() == "caf\xC3\xA9");
}
