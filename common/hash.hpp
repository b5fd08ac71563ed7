#pragma once
// FNV-1a 64 (Fowler–Noll–Vo, 64-bit offset basis and prime): the hash of cache keys, ledger
// keys and fingerprints. Not cryptographic; chosen because it is tiny, byte-order free over a
// byte stream and stable across compilers and releases (a stored key must never change).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace gradem::common {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;
inline constexpr std::uint64_t kFnv1aPrime = 1099511628211ull;

/// Continues the hash `h` over `size` bytes at `data` (start with kFnv1aOffset).
inline std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = kFnv1aOffset) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= kFnv1aPrime;
    }
    return h;
}

/// A 64-bit value as 16 lower-case hex digits.
std::string hex16(std::uint64_t v);

/// The offset basis of the text keys (ledger run keys, problem and model fingerprints): the
/// standard basis with its last digit lost (1469598103934665603, not 14695981039346656037), as
/// the first ledger wrote it. Kept so that every stored ledger key stays valid; the hash is as
/// well spread with it.
inline constexpr std::uint64_t kTextKeyOffset = 1469598103934665603ull;

/// FNV-1a 64 of a text (from kTextKeyOffset), as 16 hex digits: ledger keys, fingerprints.
inline std::string fnv1a_hex(std::string_view text) { return hex16(fnv1a(text.data(), text.size(), kTextKeyOffset)); }

}  // namespace gradem::common
