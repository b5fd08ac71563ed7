// common/: input errors, text decoding, atomic writes (whole or absent), number formats,
// NaN-safe JSON, FNV-1a against its published test vectors and the stored ledger-key basis.
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "common/atomic_file.hpp"
#include "common/clock_text.hpp"
#include "common/hash.hpp"
#include "common/input_error.hpp"
#include "common/json_number.hpp"
#include "common/number_format.hpp"
#include "common/text_file.hpp"

using namespace gradem;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Files in `dir` whose name contains ".tmp." (left-over temporary files).
int temporaries_in(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().filename().string().find(".tmp.") != std::string::npos;
    return n;
}

}  // namespace

TEST_CASE("InputError names the file and the line, or only the file without a line", "[common]") {
    const common::InputError with_line("cfg.toml", 7, "key 'a' = 3 violates > 5");
    CHECK(std::string(with_line.what()) == "cfg.toml:7: key 'a' = 3 violates > 5");
    CHECK(with_line.file() == "cfg.toml");
    CHECK(with_line.line() == 7);
    CHECK(std::string(common::InputError("data.csv", 0, "cannot open file").what()) == "data.csv: cannot open file");
    CHECK(common::column_prefix("Axial Force") == "column 'Axial Force': ");
    // lab_data's name for it is the same type: a handler of one catches the other.
    CHECK_THROWS_AS(throw lab::InputError("x", 1, "y"), common::InputError);
}

TEST_CASE("decode_text: BOMs, UTF-16 and Windows-1252 all become the same UTF-8", "[common]") {
    const std::string euro_utf8 = "\xE2\x82\xAC 5";
    CHECK(common::decode_text(euro_utf8).utf8 == euro_utf8);
    CHECK(common::decode_text("\xEF\xBB\xBF" + euro_utf8).encoding == "utf-8 (BOM)");
    CHECK(common::decode_text("\xEF\xBB\xBF" + euro_utf8).utf8 == euro_utf8);
    CHECK(common::decode_text(std::string("\xFF\xFE\xAC\x20\x20\x00\x35\x00", 8)).utf8 == euro_utf8);  // UTF-16LE
    CHECK(common::decode_text(std::string("\xFE\xFF\x20\xAC\x00\x20\x00\x35", 8)).utf8 == euro_utf8);  // UTF-16BE
    const common::DecodedText cp1252 = common::decode_text("\x80 5");  // 0x80 is the euro sign in Windows-1252
    CHECK(cp1252.encoding == "windows-1252");
    CHECK(cp1252.utf8 == euro_utf8);
}

TEST_CASE("read_file_bytes: a folder or a missing file is an InputError naming it", "[common]") {
    test::TempDir dir("common-read");
    CHECK_THROWS_WITH(common::read_file_bytes(dir.path), Contains(dir.path.string()) && Contains("is a directory"));
    CHECK_THROWS_AS(common::read_file_bytes(dir.path / "absent.csv"), common::InputError);
    std::ofstream(dir.path / "a.bin", std::ios::binary) << std::string("a\0b\r\n", 5);
    CHECK(common::read_file_bytes(dir.path / "a.bin") == std::string("a\0b\r\n", 5));  // bytes as they are
}

TEST_CASE("write_file_atomically: whole or absent, parent folders made, no temporary left", "[common]") {
    test::TempDir dir("common-atomic");
    const fs::path target = dir.path / "deep" / "er" / "result.csv";
    common::write_file_atomically(target, "a,b\n1,2\n");
    CHECK(slurp(target) == "a,b\n1,2\n");
    common::write_file_atomically(target, "replaced");  // an existing result is replaced whole
    CHECK(slurp(target) == "replaced");
    CHECK(temporaries_in(dir.path) == 0);

    // The target is a folder: rename fails, the error names it, the old content is untouched.
    fs::create_directories(dir.path / "busy" / "inside");
    CHECK_THROWS_WITH(common::write_file_atomically(dir.path / "busy", "x"), Contains((dir.path / "busy").string()));
    CHECK(fs::is_directory(dir.path / "busy" / "inside"));
    CHECK(temporaries_in(dir.path) == 0);
}

TEST_CASE("write_files_atomically: a failure on one file leaves none of the set", "[common]") {
    test::TempDir dir("common-atomic-set");
    common::write_files_atomically({{dir.path / "a.json", "{}\n"}, {dir.path / "b.csv", "x\n"}});
    CHECK(slurp(dir.path / "a.json") == "{}\n");
    CHECK(slurp(dir.path / "b.csv") == "x\n");

    // The second file's folder does not exist: its temporary cannot be written, so the first
    // file is not renamed into place either.
    const fs::path first = dir.path / "c.json", second = dir.path / "missing" / "d.csv";
    try {
        common::write_files_atomically({{first, "1"}, {second, "2"}});
        FAIL("wrote into a missing folder");
    } catch (const common::InputError& e) {
        CHECK_THAT(e.what(), Contains("d.csv") && Contains("cannot write file"));
    }
    CHECK_FALSE(fs::exists(first));
    CHECK(temporaries_in(dir.path) == 0);
}

TEST_CASE("number formats: significant digits, fixed decimals, a marker for missing values", "[common]") {
    CHECK(common::format_significant(1234.5678, 4) == "1235");
    CHECK(common::format_significant(0.000123456, 3) == "0.000123");
    CHECK(common::format_significant(2.5e7, 2) == "2.5e+07");
    CHECK(common::format_fixed(2.345, 1) == "2.3");
    CHECK(common::format_fixed(-0.5, 0) == "-0");
    const double nan = std::nan("");
    CHECK(common::format_significant(nan, 4) == "-");
    CHECK(common::format_fixed(std::numeric_limits<double>::infinity(), 2) == "-");
    CHECK(common::format_significant(nan, 8, "").empty());  // an empty CSV cell
    CHECK(common::clock_text(245) == "4m05s");
    CHECK(common::clock_text(4320) == "1h12m");
    CHECK(common::clock_text(nan) == "?");
}

TEST_CASE("json_number: non-finite values become null, finite ones keep every bit", "[common]") {
    CHECK(common::json_number(std::nan("")).is_null());
    CHECK(common::json_number(-std::numeric_limits<double>::infinity()).is_null());
    const double v = 0.1 + 0.2;  // not exactly representable as written
    const nlohmann::json round_trip = nlohmann::json::parse(common::json_number(v).dump());
    CHECK(round_trip.get<double>() == v);
    const nlohmann::ordered_json ordered = common::json_number<nlohmann::ordered_json>(std::nan(""));
    CHECK(ordered.is_null());
}

TEST_CASE("FNV-1a 64: the published test vectors, text keys keep the ledger's offset basis", "[common]") {
    auto hash = [](const std::string& s) { return common::fnv1a(s.data(), s.size()); };
    CHECK(hash("") == 0xcbf29ce484222325ull);  // the offset basis itself
    CHECK(hash("a") == 0xaf63dc4c8601ec8cull);
    CHECK(hash("foobar") == 0x85944171f73967e8ull);
    // Hashing in pieces continues the same stream.
    CHECK(common::fnv1a("bar", 3, common::fnv1a("foo", 3)) == hash("foobar"));
    CHECK(common::hex16(0xabcull) == "0000000000000abc");
    // Ledger keys and fingerprints stored by earlier runs: the text-key basis must not change.
    CHECK(common::fnv1a_hex("") == common::hex16(common::kTextKeyOffset));
    CHECK(common::fnv1a_hex("gradem") == "9d01929bfbf5d0d9");
    CHECK(common::fnv1a_hex("gradem") != common::fnv1a_hex("gradeM"));
}

TEST_CASE("number_or_nan: a number read back, NaN for absent, null or text", "[common]") {
    const nlohmann::json j = {{"a", 1.5}, {"n", 3}, {"missing", nullptr}, {"text", "1.0"}};
    CHECK(common::number_or_nan(j, "a") == 1.5);
    CHECK(common::number_or_nan(j, "n") == 3.0);
    CHECK(std::isnan(common::number_or_nan(j, "missing")));
    CHECK(std::isnan(common::number_or_nan(j, "text")));
    CHECK(std::isnan(common::number_or_nan(j, "absent")));
    // Written and read back: NaN survives the trip as null.
    const nlohmann::json written = {{"x", common::json_number(std::nan(""))}};
    CHECK(std::isnan(common::number_or_nan(nlohmann::json::parse(written.dump()), "x")));
}
