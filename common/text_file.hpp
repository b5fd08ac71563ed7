#pragma once
// Reading a user's text file whatever its encoding: every config and lab file goes through
// here, so a UTF-16 or Windows-1252 file reads the same everywhere.
#include <filesystem>
#include <string>
#include <string_view>

namespace gradem::common {

/// Bytes of a file decoded to UTF-8, with the encoding that was detected.
struct DecodedText {
    std::string utf8;
    std::string encoding;  ///< "utf-8", "utf-8 (BOM)", "utf-16le (BOM)", "utf-16be (BOM)", "windows-1252"
};

/// UTF-8 BOM is stripped; UTF-16 with BOM is transcoded; bytes that are not valid UTF-8 are read
/// as Windows-1252 (a superset of Latin-1, what MTS 793 writes with sCode=A).
DecodedText decode_text(std::string_view bytes);

/// Reads a whole file; throws InputError(file, 0, ...) when it cannot be opened.
std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace gradem::common
