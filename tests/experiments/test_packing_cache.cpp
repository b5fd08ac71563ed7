// Packing cache: a hand-made packing survives save -> load bit for bit; the key follows every
// genesis input and nothing else; each kind of bad file gets its own error; writes leave no
// temporary file behind; load_or_generate uses the cache without running genesis.
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "experiments/specimen/packing_cache.hpp"
#include "study_curves.hpp"

using namespace gradem;
using namespace gradem::exp;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

// Five grains and every report field set to something other than its default.
Packing hand_packing() {
    Packing k;
    for (int i = 0; i < 5; ++i) {
        k.position.push_back({0.1e-3 * i, 0.2e-3 + 1e-5 * i, 0.3e-3 - 1e-6 * i});
        k.radius.push_back(0.15e-3 + 1.0e-6 * i * i);
    }
    k.density = 2640.0;
    k.box_lo = {-1e-3, -1.5e-3, -2e-3};
    k.box_hi = {1e-3, 1.5e-3, 2e-3 + 1e-9};
    k.grains.diameters = {0.3e-3, 0.31e-3};
    k.grains.removed_fine_fraction = 0.256;
    k.grains.removed_coarse_fraction = 0.004;
    k.grains.sieve_sizes = {0.149e-3, 0.3e-3, 0.4e-3};
    k.grains.target_passing = {0.0, 0.6, 1.0};
    k.grains.achieved_passing = {0.0, 0.58, 1.0};
    k.grains.max_deviation = 0.02;
    k.grains.d50 = 0.28e-3;
    k.grains.solid_volume = 1.234e-9;
    k.steps = 123456;
    k.relax_iterations = 654321;
    k.porosity = 0.41;
    k.edge_over_d50 = 12.5;
    k.mean_coordination = 4.7;
    k.floaters_before = 0.12;
    k.floaters_after = 0.03;
    k.wall_stress = {0.1e6, 0.11e6, 0.095e6};
    k.unbalanced_ratio = 0.04;
    k.radius_growth = 1.0123;
    k.converged = true;
    k.seconds = 3.25;
    return k;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

void require_identical(const Packing& a, const Packing& b) {
    CHECK(same_bits(a.position, b.position));
    CHECK(same_bits(a.radius, b.radius));
    CHECK(same_bits(a.density, b.density));
    CHECK(same_bits(a.box_lo, b.box_lo));
    CHECK(same_bits(a.box_hi, b.box_hi));
    CHECK(same_bits(a.grains.diameters, b.grains.diameters));
    CHECK(same_bits(a.grains.removed_fine_fraction, b.grains.removed_fine_fraction));
    CHECK(same_bits(a.grains.removed_coarse_fraction, b.grains.removed_coarse_fraction));
    CHECK(same_bits(a.grains.sieve_sizes, b.grains.sieve_sizes));
    CHECK(same_bits(a.grains.target_passing, b.grains.target_passing));
    CHECK(same_bits(a.grains.achieved_passing, b.grains.achieved_passing));
    CHECK(same_bits(a.grains.max_deviation, b.grains.max_deviation));
    CHECK(same_bits(a.grains.d50, b.grains.d50));
    CHECK(same_bits(a.grains.solid_volume, b.grains.solid_volume));
    CHECK(a.steps == b.steps);
    CHECK(a.relax_iterations == b.relax_iterations);
    CHECK(same_bits(a.porosity, b.porosity));
    CHECK(same_bits(a.edge_over_d50, b.edge_over_d50));
    CHECK(same_bits(a.mean_coordination, b.mean_coordination));
    CHECK(same_bits(a.floaters_before, b.floaters_before));
    CHECK(same_bits(a.floaters_after, b.floaters_after));
    CHECK(same_bits(a.wall_stress, b.wall_stress));
    CHECK(same_bits(a.unbalanced_ratio, b.unbalanced_ratio));
    CHECK(same_bits(a.radius_growth, b.radius_growth));
    CHECK(a.converged == b.converged);
    CHECK(same_bits(a.seconds, b.seconds));
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Loads `path` expecting a PackingCacheError of `kind` whose message holds `text` and the file.
void require_error(const fs::path& path, std::uint64_t key, PackingCacheError::Kind kind, const std::string& text) {
    try {
        (void)load_packing(path, key);
        FAIL("load_packing accepted " << path);
    } catch (const PackingCacheError& e) {
        INFO(e.what());
        CHECK(e.kind() == kind);
        CHECK(std::string(e.what()).find(text) != std::string::npos);
        CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("a saved packing loads back bit for bit, without a temporary file left", "[packing_cache]") {
    const TempDir dir("cache-roundtrip");
    const Packing k = hand_packing();
    const fs::path path = packing_cache_path(dir.path, 0x0123456789abcdefull);
    CHECK(path.filename() == "packing-0123456789abcdef.bin");
    save_packing(path, k, 0x0123456789abcdefull);
    require_identical(k, load_packing(path, 0x0123456789abcdefull));
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir.path)) {
        ++files;
        CHECK(entry.path() == path);
    }
    CHECK(files == 1);
}

TEST_CASE("the packing key follows every genesis input and nothing else", "[packing_cache]") {
    const lab::GradationCurve curve = test::pre_blended_curve();
    const SpecimenSpec spec;
    const std::uint64_t base = packing_key(curve, spec);
    CHECK(packing_key(curve, spec) == base);
    lab::GradationCurve relabelled = curve;
    relabelled.designation.assign(curve.size_m.size(), "#x");
    CHECK(packing_key(relabelled, spec) == base);  // designations are labels only

    lab::GradationCurve other = curve;
    other.passing[3] += 0.001;
    CHECK(packing_key(other, spec) != base);
    CHECK(packing_key(test::van_buren_curve(), spec) != base);
    other = curve;
    other.size_m[0] *= 1.01;
    CHECK(packing_key(other, spec) != base);

    const std::vector<std::function<void(SpecimenSpec&)>> changes = {
        [](SpecimenSpec& s) { s.size_rule.min_diameter *= 1.1; },
        [](SpecimenSpec& s) { s.size_rule.max_diameter = 2e-3; },
        [](SpecimenSpec& s) { s.size_rule.scale = 1.5; },
        [](SpecimenSpec& s) { s.seed = 2; },
        [](SpecimenSpec& s) { s.genesis.edge *= 1.01; },
        [](SpecimenSpec& s) { s.genesis.target_solid_fraction = 0.55; },
        [](SpecimenSpec& s) { s.genesis.locked_in_stress *= 2; },
        [](SpecimenSpec& s) { s.genesis.stress_tolerance = 0.1; },
        [](SpecimenSpec& s) { s.genesis.reference_modulus *= 2; },
        [](SpecimenSpec& s) { s.genesis.stiffness_ratio = 2.0; },
        [](SpecimenSpec& s) { s.genesis.density = 2650; },
        [](SpecimenSpec& s) { s.genesis.damping = 0.8; },
        [](SpecimenSpec& s) { s.genesis.min_contacts = 4; },
        [](SpecimenSpec& s) { s.genesis.floater_passes = 3; },
        [](SpecimenSpec& s) { s.genesis.floater_growth = 0.02; },
        [](SpecimenSpec& s) { s.genesis.equilibrium_ratio = 0.01; },
        [](SpecimenSpec& s) { s.genesis.max_steps = 1000; },
    };
    for (std::size_t c = 0; c < changes.size(); ++c) {
        SpecimenSpec changed = spec;
        changes[c](changed);
        INFO("change " << c);
        CHECK(packing_key(curve, changed) != base);
    }
}

TEST_CASE("bad cache files each give their own error naming the file", "[packing_cache]") {
    const TempDir dir("cache-errors");
    const std::uint64_t key = 42;
    const std::string good = serialize_packing(hand_packing(), key);
    const fs::path path = dir.path / "packing.bin";
    using Kind = PackingCacheError::Kind;

    SECTION("not a packing") {
        write_bytes(path, "x,y,z\n1,2,3\n" + good.substr(12));
        require_error(path, key, Kind::bad_magic, "not a gradem packing");
        write_bytes(path, "");
        require_error(path, key, Kind::bad_magic, "not a gradem packing");
    }
    SECTION("other format version") {
        std::string bytes = good;
        const std::uint32_t version = kPackingFormatVersion + 1;
        std::memcpy(bytes.data() + 8, &version, sizeof version);
        write_bytes(path, bytes);
        require_error(path, key, Kind::version, "version " + std::to_string(version));
        require_error(path, key, Kind::version, "regenerated");
    }
    SECTION("another key") {
        write_bytes(path, good);
        require_error(path, key + 1, Kind::key_mismatch, "another gradation, size rule, seed or genesis");
    }
    SECTION("truncated") {
        for (std::size_t size : {std::size_t{3}, std::size_t{20}, good.size() / 2, good.size() - 9, good.size() - 1}) {
            INFO("size " << size);
            write_bytes(path, good.substr(0, size));
            require_error(path, key, Kind::truncated, "truncated");
        }
    }
    SECTION("a flipped byte") {
        for (std::size_t at : {std::size_t{40}, good.size() / 2, good.size() - 20, std::size_t{13}}) {  // 13: inside the key
            INFO("byte " << at);
            std::string bytes = good;
            bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
            write_bytes(path, bytes);
            require_error(path, key, Kind::checksum, "checksum mismatch");
        }
    }
    SECTION("missing file") {
        require_error(dir.path / "none.bin", key, Kind::io, "cannot open");
    }
}

TEST_CASE("load_or_generate takes a cached packing without running genesis", "[packing_cache]") {
    const TempDir dir("cache-reuse");
    const lab::GradationCurve curve = test::pre_blended_curve();
    SpecimenSpec spec;
    spec.seed = 7;
    const Packing k = hand_packing();
    save_packing(packing_cache_path(dir.path, packing_key(curve, spec)), k, packing_key(curve, spec));
    bool cached = false;
    require_identical(k, load_or_generate(curve, spec, dir.path, &cached));
    CHECK(cached);

    // A cache file under the right name but with another key inside: an error, not a silent reuse.
    SpecimenSpec other = spec;
    other.seed = 8;
    save_packing(packing_cache_path(dir.path, packing_key(curve, other)), k, packing_key(curve, spec));
    CHECK_THROWS_AS(load_or_generate(curve, other, dir.path), PackingCacheError);
}
