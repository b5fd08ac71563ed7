#include "experiments/paste/paste_cache.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>

#include "experiments/specimen/packing_cache.hpp"
#include "common/atomic_file.hpp"

namespace gradem::exp {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'G', 'R', 'A', 'D', 'E', 'M', 'P', 'F'};
constexpr std::uint32_t kFamilyFormatVersion = 1;
static_assert(std::is_trivially_copyable_v<PasteReport> && sizeof(PasteReport) % 8 == 0,
              "PasteReport is written as raw 8-byte fields");

std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = 14695981039346656037ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

template <class T>
void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

fs::path family_path(const fs::path& bin) {
    fs::path p = bin;
    return p.replace_extension(".family");
}

std::string serialize_family(const Packing& k, const PasteReport& report, std::uint64_t key) {
    std::string out(kMagic, sizeof kMagic);
    put(out, kFamilyFormatVersion);
    put(out, key);
    put(out, static_cast<std::uint64_t>(k.family.size()));
    out.append(reinterpret_cast<const char*>(k.family.data()), k.family.size());
    put(out, k.paste_density);
    put(out, report);
    put(out, fnv1a(out.data(), out.size()));
    return out;
}

[[noreturn]] void bad(const fs::path& file, const std::string& what) {
    throw PackingCacheError(PackingCacheError::Kind::truncated,
                            file.string() + ": " + what + " (delete it and its .bin and run again)");
}

void load_family(const fs::path& file, std::uint64_t key, Packing& k, PasteReport& report) {
    std::ifstream in(file, std::ios::binary);
    if (!in) bad(file, "missing or unreadable paste family file next to its packing");
    const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t head = sizeof kMagic + 4 + 8 + 8;
    if (s.size() < head + 8 || std::memcmp(s.data(), kMagic, sizeof kMagic) != 0) bad(file, "not a paste family file");
    std::uint32_t version = 0;
    std::uint64_t file_key = 0, n = 0, sum = 0;
    std::memcpy(&version, s.data() + 8, 4);
    std::memcpy(&file_key, s.data() + 12, 8);
    std::memcpy(&n, s.data() + 20, 8);
    if (version != kFamilyFormatVersion) bad(file, "format version " + std::to_string(version) + ", expected " + std::to_string(kFamilyFormatVersion));
    if (file_key != key) bad(file, "key mismatch");
    if (n != k.position.size() || s.size() != head + n + 8 + sizeof(PasteReport) + 8) bad(file, "truncated or wrong grain count");
    std::memcpy(&sum, s.data() + s.size() - 8, 8);
    if (sum != fnv1a(s.data(), s.size() - 8)) bad(file, "checksum mismatch");
    k.family.assign(s.begin() + static_cast<std::ptrdiff_t>(head), s.begin() + static_cast<std::ptrdiff_t>(head + n));
    std::memcpy(&k.paste_density, s.data() + head + n, 8);
    std::memcpy(&report, s.data() + head + n + 8, sizeof(PasteReport));
}

}  // namespace

std::uint64_t paste_packing_key(std::uint64_t sand_key, const PasteSettings& s) {
    std::uint64_t h = fnv1a(&sand_key, sizeof sand_key);
    const MixDesign& m = s.mix;
    const PasteSpec& p = s.paste;
    for (double v : {m.sand_to_cementitious_volume, m.water_cement_ratio, m.cement_specific_gravity,
                     m.sand_specific_gravity, m.cement_bulk_density, m.sand_bulk_density, m.air_content,
                     m.hydration_degree, p.min_diameter, p.max_diameter, p.solid_fraction, p.overlap_tolerance,
                     p.rsa_scale, p.memory_fraction})
        h = fnv1a(&v, sizeof v, h);
    for (std::int64_t v : {std::int64_t{p.rsa_attempts}, std::int64_t{p.growth_stages}, std::int64_t{p.relax_iterations},
                           std::int64_t{kPasteAlgorithmVersion}})
        h = fnv1a(&v, sizeof v, h);
    return h;
}

fs::path paste_cache_path(const lab::GradationCurve& curve, const SpecimenSpec& spec, const fs::path& cache_dir) {
    SpecimenSpec sand_spec = spec;
    sand_spec.paste.reset();
    const std::uint64_t key = paste_packing_key(packing_key(curve, sand_spec), *spec.paste);
    fs::path path = packing_cache_path(cache_dir, key);
    return path.replace_filename("paste-" + path.filename().string().substr(std::string("packing-").size()));
}

Packing load_or_generate_paste(const lab::GradationCurve& curve, const SpecimenSpec& spec, const fs::path& cache_dir,
                               bool* was_cached, PasteReport* report) {
    SpecimenSpec sand_spec = spec;
    sand_spec.paste.reset();
    const std::uint64_t sand_key = packing_key(curve, sand_spec);
    const std::uint64_t key = paste_packing_key(sand_key, *spec.paste);
    const fs::path path = paste_cache_path(curve, spec, cache_dir);
    PasteReport local;
    PasteReport& r = report ? *report : local;
    std::error_code ec;
    if (fs::exists(path, ec)) {
        if (was_cached) *was_cached = true;
        Packing k = load_packing(path, key);
        load_family(family_path(path), key, k, r);
        return k;
    }
    bool sand_cached = false;
    const Packing sand = load_or_generate(curve, sand_spec, cache_dir, &sand_cached);
    if (was_cached) *was_cached = false;
    Packing k = fill_paste(sand, mix_fractions(spec.paste->mix), spec.paste->paste, spec.seed, r);
    if (r.growth_reached < 1.0)
        throw GenesisError("paste fill: the paste particles reached only " + std::to_string(r.growth_reached) +
                           " of their size (the pores are too full): lower paste.solid_fraction or raise "
                           "paste.relax_iterations (nothing cached)");
    fs::create_directories(cache_dir, ec);
    common::write_file_atomically(family_path(path), serialize_family(k, r, key));
    save_packing(path, k, key);
    return k;
}

}  // namespace gradem::exp
