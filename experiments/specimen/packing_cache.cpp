#include "experiments/specimen/packing_cache.hpp"
#include "experiments/paste/paste_cache.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "common/atomic_file.hpp"
#include "common/hash.hpp"

namespace gradem::exp {

static_assert(std::endian::native == std::endian::little, "packing cache files are little-endian");

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'G', 'R', 'A', 'D', 'E', 'M', 'P', 'K'};
using common::fnv1a;
using common::hex16;

// Hashes the raw bits of trivially copyable values (doubles by bit pattern, not by value).
struct Hasher {
    std::uint64_t h = common::kFnv1aOffset;
    template <typename T>
    void add(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        h = fnv1a(&v, sizeof(T), h);
    }
    void add(const std::vector<double>& v) {
        add(static_cast<std::uint64_t>(v.size()));
        if (!v.empty()) h = fnv1a(v.data(), v.size() * sizeof(double), h);
    }
};

// Appends values to the file image.
struct Writer {
    std::string bytes;
    template <typename T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    void put(const Vec3& v) { put(v.x), put(v.y), put(v.z); }
    void put_raw(const void* data, std::size_t size) {
        if (size > 0) bytes.append(static_cast<const char*>(data), size);
    }
    void put(const std::vector<double>& v) {
        put(static_cast<std::uint64_t>(v.size()));
        put_raw(v.data(), v.size() * sizeof(double));
    }
};

// Reads values back, bounds-checked: running out of bytes is a truncated file.
struct Reader {
    const std::string& bytes;
    std::size_t end;  // the trailing checksum is not payload
    std::string file;
    std::size_t at = 0;

    [[noreturn]] void truncated() const {
        throw PackingCacheError(PackingCacheError::Kind::truncated,
                                file + ": truncated packing cache file (" + std::to_string(bytes.size()) +
                                    " bytes, ends inside the field at byte " + std::to_string(at) +
                                    "): delete it and run again");
    }
    [[nodiscard]] std::size_t remaining() const { return at < end ? end - at : 0; }
    void need(std::uint64_t size) const {
        if (size > remaining()) truncated();
    }
    template <typename T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>);
        need(sizeof(T));
        T v;
        std::memcpy(&v, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return v;
    }
    Vec3 vec3() {
        const double x = get<double>(), y = get<double>(), z = get<double>();
        return {x, y, z};
    }
    /// n values of `per` doubles each (checked before allocating).
    std::vector<double> doubles(std::uint64_t n, std::uint64_t per = 1) {
        if (n > remaining() / (per * sizeof(double))) truncated();
        std::vector<double> v(n * per);
        if (!v.empty()) std::memcpy(v.data(), bytes.data() + at, v.size() * sizeof(double));
        at += v.size() * sizeof(double);
        return v;
    }
    std::vector<double> vector() { return doubles(get<std::uint64_t>()); }
};

void put_report(Writer& w, const Packing& k) {
    const GrainSample& g = k.grains;
    w.put(g.diameters), w.put(g.removed_fine_fraction), w.put(g.removed_coarse_fraction);
    w.put(g.sieve_sizes), w.put(g.target_passing), w.put(g.achieved_passing);
    w.put(g.max_deviation), w.put(g.d50), w.put(g.solid_volume);
    w.put(k.steps), w.put(k.relax_iterations), w.put(k.porosity), w.put(k.edge_over_d50), w.put(k.mean_coordination);
    w.put(k.floaters_before), w.put(k.floaters_after), w.put(k.wall_stress);
    w.put(k.unbalanced_ratio), w.put(k.radius_growth);
    w.put(static_cast<std::uint8_t>(k.converged ? 1 : 0)), w.put(k.seconds);
}

void get_report(Reader& r, Packing& k) {
    GrainSample& g = k.grains;
    g.diameters = r.vector();
    g.removed_fine_fraction = r.get<double>(), g.removed_coarse_fraction = r.get<double>();
    g.sieve_sizes = r.vector(), g.target_passing = r.vector(), g.achieved_passing = r.vector();
    g.max_deviation = r.get<double>(), g.d50 = r.get<double>(), g.solid_volume = r.get<double>();
    k.steps = r.get<std::int64_t>(), k.relax_iterations = r.get<std::int64_t>(), k.porosity = r.get<double>(), k.edge_over_d50 = r.get<double>();
    k.mean_coordination = r.get<double>(), k.floaters_before = r.get<double>(), k.floaters_after = r.get<double>();
    k.wall_stress = r.vec3();
    k.unbalanced_ratio = r.get<double>(), k.radius_growth = r.get<double>();
    k.converged = r.get<std::uint8_t>() != 0;
    k.seconds = r.get<double>();
}

std::string read_all(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw PackingCacheError(PackingCacheError::Kind::io, path.string() + ": cannot open the packing cache file");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw PackingCacheError(PackingCacheError::Kind::io, path.string() + ": read error");
    return bytes;
}

struct Header {
    std::uint64_t key = 0, count = 0;
};

// Magic and version first (a foreign file or an old format says so); the checksum is verified
// over everything before the key is compared, so a flipped byte never poses as another key.
Header read_header(Reader& r) {
    const std::size_t have = std::min(r.bytes.size(), sizeof kMagic);
    if (std::memcmp(r.bytes.data(), kMagic, have) != 0 || r.bytes.empty())
        throw PackingCacheError(PackingCacheError::Kind::bad_magic,
                                r.file + ": not a gradem packing cache file (no \"GRADEMPK\" magic at its start)");
    if (have < sizeof kMagic) r.truncated();
    r.at = sizeof kMagic;
    const auto version = r.get<std::uint32_t>();
    if (version != kPackingFormatVersion)
        throw PackingCacheError(PackingCacheError::Kind::version,
                                r.file + ": packing cache format version " + std::to_string(version) + ", this gradem reads version " +
                                    std::to_string(kPackingFormatVersion) + ": the packing must be regenerated (delete the file)");
    Header h;
    h.key = r.get<std::uint64_t>();
    h.count = r.get<std::uint64_t>();
    return h;
}

void check_key(const std::string& file, std::uint64_t key, std::uint64_t expected_key) {
    if (key == expected_key) return;
    throw PackingCacheError(PackingCacheError::Kind::key_mismatch,
                            file + ": packing cache key " + hex16(key) + " differs from the expected " + hex16(expected_key) +
                                ": the cache belongs to another gradation, size rule, seed or genesis settings");
}

}  // namespace

std::uint64_t packing_key(const lab::GradationCurve& curve, const SpecimenSpec& spec) {
    Hasher h;
    h.add(kPackingFormatVersion), h.add(kGenesisAlgorithmVersion);
    h.add(curve.size_m), h.add(curve.passing);
    h.add(spec.size_rule.min_diameter), h.add(spec.size_rule.max_diameter), h.add(spec.size_rule.scale);
    h.add(spec.seed);
    const GenesisSpec& g = spec.genesis;
    h.add(g.edge), h.add(g.target_solid_fraction), h.add(g.locked_in_stress), h.add(g.stress_tolerance);
    h.add(g.reference_modulus), h.add(g.stiffness_ratio), h.add(g.density), h.add(g.damping);
    h.add(g.min_contacts), h.add(g.floater_passes), h.add(g.floater_growth), h.add(g.equilibrium_ratio);
    h.add(g.max_steps);
    return h.h;
}

fs::path packing_cache_path(const fs::path& dir, std::uint64_t key) { return dir / ("packing-" + hex16(key) + ".bin"); }

std::string serialize_packing(const Packing& k, std::uint64_t key) {
    if (k.position.size() != k.radius.size())
        throw std::invalid_argument("serialize_packing: " + std::to_string(k.position.size()) + " positions but " +
                                    std::to_string(k.radius.size()) + " radii");
    Writer w;
    w.put_raw(kMagic, sizeof kMagic);
    w.put(kPackingFormatVersion), w.put(key), w.put(static_cast<std::uint64_t>(k.radius.size()));
    for (const Vec3& p : k.position) w.put(p);
    w.put_raw(k.radius.data(), k.radius.size() * sizeof(double));
    w.put(k.density), w.put(k.box_lo), w.put(k.box_hi);
    put_report(w, k);
    w.put(fnv1a(w.bytes.data(), w.bytes.size()));
    return std::move(w.bytes);
}

void save_packing(const fs::path& path, const Packing& packing, std::uint64_t key) {
    common::write_file_atomically(path, serialize_packing(packing, key));
}

Packing load_packing(const fs::path& path, std::uint64_t expected_key) {
    const std::string bytes = read_all(path);
    const std::size_t payload_end = bytes.size() >= sizeof(std::uint64_t) ? bytes.size() - sizeof(std::uint64_t) : 0;
    Reader r{bytes, payload_end, path.string()};
    const Header h = read_header(r);

    Packing k;
    const std::vector<double> xyz = r.doubles(h.count, 3);
    k.position.resize(h.count);
    for (std::size_t i = 0; i < h.count; ++i) k.position[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    k.radius = r.doubles(h.count);
    k.density = r.get<double>(), k.box_lo = r.vec3(), k.box_hi = r.vec3();
    get_report(r, k);
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + payload_end, sizeof stored);
    if (r.at != payload_end || stored != fnv1a(bytes.data(), payload_end))
        throw PackingCacheError(PackingCacheError::Kind::checksum,
                                r.file + ": checksum mismatch (the file is corrupt): delete it and run again");
    check_key(r.file, h.key, expected_key);
    return k;
}

Packing load_or_generate(const lab::GradationCurve& curve, const SpecimenSpec& spec, const fs::path& cache_dir,
                         bool* was_cached) {
    if (spec.paste) return load_or_generate_paste(curve, spec, cache_dir, was_cached);  // explicit paste
    const std::uint64_t key = packing_key(curve, spec);
    const fs::path path = packing_cache_path(cache_dir, key);
    std::error_code ec;
    const bool cached = fs::exists(path, ec);
    if (was_cached) *was_cached = cached;
    if (cached) return load_packing(path, key);
    Packing packing = generate_packing(curve, spec);
    if (!packing.converged) throw GenesisError(convergence_failure(packing, spec) + " (nothing cached)");
    save_packing(path, packing, key);
    return packing;
}

}  // namespace gradem::exp
