#include "calibrate/execution/run_message.hpp"

#include <cstring>
#include <type_traits>

namespace gradem::cal::wire {
namespace {

constexpr std::uint32_t kMagic = 0x4D445247;  // "GRDM" little-endian
constexpr std::uint32_t kByteOrder = 0x01020304;

// Every shared field of the material is written below, one by one; a bond law's own fields are
// written from its parameter rows (Law::kParameters). A new shared field changes these sizes:
// serialise it in put_material/get_material (and in material_key), then update the sizes.
static_assert(sizeof(ContactParams) == 3 * 8, "ContactParams changed: serialise the new field in run_message.cpp");
static_assert(sizeof(BondParams) == 9 * 8 /* doubles */ + 8 /* seed */ + 8 /* model, padded */ + sizeof(BondLawParams) +
                                       8 /* replaces_contact, padded */,
              "BondParams changed: serialise the new field in run_message.cpp");
static_assert(sizeof(exp::MaterialParams) == 24 + sizeof(BondParams) + 4 * 8 + 3 * 8 /* families */,
              "MaterialParams changed: serialise the new field in run_message.cpp");

class Writer {
public:
    explicit Writer(Kind kind) {
        u32(kMagic);
        u32(kProtocolVersion);
        u32(kByteOrder);
        u8(static_cast<std::uint8_t>(kind));
    }
    template <class T>
    void raw(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        out_.append(b, sizeof(T));
    }
    void u8(std::uint8_t v) { raw(v); }
    void u32(std::uint32_t v) { raw(v); }
    void u64(std::uint64_t v) { raw(v); }
    void i64(std::int64_t v) { raw(v); }
    void f64(double v) { raw(v); }
    void str(const std::string& s) {
        u64(s.size());
        out_ += s;
    }
    void f64s(const std::vector<double>& v) {
        u64(v.size());
        for (double x : v) f64(x);
    }
    std::string take() { return std::move(out_); }

private:
    std::string out_;
};

class Reader {
public:
    Reader(const std::string& bytes, Kind expected) : in_(bytes) {
        const Kind k = kind_of(bytes);
        pos_ = 13;
        if (k != expected)
            throw WireError(std::string("expected a '") + to_string(expected) + "' message, got '" + to_string(k) + "'");
    }
    template <class T>
    T raw() {
        if (in_.size() - pos_ < sizeof(T)) throw WireError("truncated message (" + std::to_string(in_.size()) + " bytes)");
        T v;
        std::memcpy(&v, in_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    std::uint8_t u8() { return raw<std::uint8_t>(); }
    std::uint32_t u32() { return raw<std::uint32_t>(); }
    std::uint64_t u64() { return raw<std::uint64_t>(); }
    std::int64_t i64() { return raw<std::int64_t>(); }
    double f64() { return raw<double>(); }
    std::uint64_t count(std::size_t item_bytes) {
        const std::uint64_t n = u64();
        if (item_bytes && n > (in_.size() - pos_) / item_bytes) throw WireError("truncated message (count " + std::to_string(n) + ")");
        return n;
    }
    std::string str() {
        const std::uint64_t n = count(1);
        std::string s = in_.substr(pos_, n);
        pos_ += n;
        return s;
    }
    std::vector<double> f64s() {
        std::vector<double> v(count(8));
        for (double& x : v) x = f64();
        return v;
    }
    void end() const {
        if (pos_ != in_.size()) throw WireError(std::to_string(in_.size() - pos_) + " unexpected bytes at the end of a message");
    }

private:
    const std::string& in_;
    std::size_t pos_ = 0;
};

void put_material(Writer& w, const exp::MaterialParams& m) {
    const ContactParams& c = m.contact;
    const BondParams& b = m.bond;
    for (double x : {c.effective_modulus, c.stiffness_ratio, c.friction, b.effective_modulus, b.stiffness_ratio,
                     b.radius_multiplier, b.moment_factor, b.tensile_strength_mean, b.tensile_strength_std, b.cohesion_mean,
                     b.cohesion_std, b.friction_angle_deg})
        w.f64(x);
    w.u64(b.seed);
    w.u8(static_cast<std::uint8_t>(b.model));
    // every law's own fields, in BondModel then row order: integer rows as integers, the others
    // as the bits of their double
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            if (row.field.integer) w.i64(row.field.get_int(b.law<Law>()));
            else w.f64(row.field.get(b.law<Law>()));
        }
    });
    w.u8(b.replaces_contact ? 1 : 0);
    for (double x : {m.bond_gap_fraction, m.bond_gap_absolute, m.platen_friction, m.damping}) w.f64(x);
    w.f64(m.families.itz_strength_factor);
    w.f64(m.families.itz_modulus_factor);
    w.u8(m.families.sand_sand_bonded ? 1 : 0);
}

exp::MaterialParams get_material(Reader& r) {
    exp::MaterialParams m;
    ContactParams& c = m.contact;
    BondParams& b = m.bond;
    for (double* x : {&c.effective_modulus, &c.stiffness_ratio, &c.friction, &b.effective_modulus, &b.stiffness_ratio,
                      &b.radius_multiplier, &b.moment_factor, &b.tensile_strength_mean, &b.tensile_strength_std,
                      &b.cohesion_mean, &b.cohesion_std, &b.friction_angle_deg})
        *x = r.f64();
    b.seed = r.u64();
    const std::uint8_t model = r.u8();
    if (model >= kBondLawCount) throw WireError("unknown bond model " + std::to_string(model));
    b.model = static_cast<BondModel>(model);
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            if (row.field.integer) row.field.set_int(b.law<Law>(), r.i64());
            else row.field.set(b.law<Law>(), r.f64());
        }
    });
    b.replaces_contact = r.u8() != 0;
    for (double* x : {&m.bond_gap_fraction, &m.bond_gap_absolute, &m.platen_friction, &m.damping}) *x = r.f64();
    m.families.itz_strength_factor = r.f64();
    m.families.itz_modulus_factor = r.f64();
    m.families.sand_sand_bonded = r.u8() != 0;
    return m;
}

}  // namespace

Kind kind_of(const std::string& bytes) {
    if (bytes.size() < 13) throw WireError("message of " + std::to_string(bytes.size()) + " bytes is shorter than a header");
    std::uint32_t head[3];
    std::memcpy(head, bytes.data(), sizeof head);
    if (head[0] != kMagic) throw WireError("not a gradem message (bad magic)");
    if (head[2] != kByteOrder) throw WireError("message from a rank of another byte order");
    if (head[1] != kProtocolVersion)
        throw WireError("message of protocol version " + std::to_string(head[1]) + ", this build speaks " +
                        std::to_string(kProtocolVersion) + " (mismatched gradem builds across ranks)");
    const auto k = static_cast<std::uint8_t>(bytes[12]);
    if (k < 1 || k > 6) throw WireError("unknown message kind " + std::to_string(k));
    return static_cast<Kind>(k);
}

std::string encode(const Hello& m) {
    Writer w(Kind::hello);
    w.str(m.code_version);
    w.str(m.host);
    w.str(m.model_fingerprint);
    w.i64(m.pid);
    w.i64(m.threads);
    w.str(m.error);
    return w.take();
}

Hello decode_hello(const std::string& bytes) {
    Reader r(bytes, Kind::hello);
    Hello m;
    m.code_version = r.str();
    m.host = r.str();
    m.model_fingerprint = r.str();
    m.pid = r.i64();
    m.threads = r.i64();
    m.error = r.str();
    r.end();
    return m;
}

std::string encode(const Prepare& m) {
    Writer w(Kind::prepare);
    w.u64(m.seeds.size());
    for (std::uint64_t s : m.seeds) w.u64(s);
    return w.take();
}

Prepare decode_prepare(const std::string& bytes) {
    Reader r(bytes, Kind::prepare);
    Prepare m;
    m.seeds.resize(r.count(8));
    for (std::uint64_t& s : m.seeds) s = r.u64();
    r.end();
    return m;
}

std::string encode(const Prepared& m) {
    Writer w(Kind::prepared);
    w.f64(m.seconds);
    w.str(m.error);
    return w.take();
}

Prepared decode_prepared(const std::string& bytes) {
    Reader r(bytes, Kind::prepared);
    Prepared m;
    m.seconds = r.f64();
    m.error = r.str();
    r.end();
    return m;
}

std::string encode(const Run& m) {
    Writer w(Kind::run);
    w.u64(m.job);
    w.str(m.code_version);
    w.str(m.model_hash);
    w.f64(m.timeout_s);
    w.u64(m.request.sand);
    w.u64(m.request.seed);
    put_material(w, m.request.material);
    w.u8(m.request.test == CubeTest::tension ? 1 : 0);
    return w.take();
}

Run decode_run(const std::string& bytes) {
    Reader r(bytes, Kind::run);
    Run m;
    m.job = r.u64();
    m.code_version = r.str();
    m.model_hash = r.str();
    m.timeout_s = r.f64();
    m.request.sand = r.u64();
    m.request.seed = r.u64();
    m.request.material = get_material(r);
    m.request.test = r.u8() != 0 ? CubeTest::tension : CubeTest::compression;
    r.end();
    return m;
}

std::string encode(const Result& m) {
    const RunOutcome& o = m.outcome;
    Writer w(Kind::result);
    w.u64(m.job);
    w.u8(static_cast<std::uint8_t>(o.status));
    w.str(o.reason);
    for (double x : {o.modulus_pa, o.peak_pa, o.strain_at_peak, o.poisson}) w.f64(x);
    for (std::int64_t n : {o.particles, o.bonds, o.steps}) w.i64(n);
    w.f64(o.wall_seconds);
    w.f64s(o.curve_strain);
    w.f64s(o.curve_stress_pa);
    return w.take();
}

Result decode_result(const std::string& bytes) {
    Reader r(bytes, Kind::result);
    Result m;
    RunOutcome& o = m.outcome;
    m.job = r.u64();
    const std::uint8_t status = r.u8();
    if (status > static_cast<std::uint8_t>(RunStatus::failed)) throw WireError("unknown run status " + std::to_string(status));
    o.status = static_cast<RunStatus>(status);
    o.reason = r.str();
    for (double* x : {&o.modulus_pa, &o.peak_pa, &o.strain_at_peak, &o.poisson}) *x = r.f64();
    for (std::int64_t* n : {&o.particles, &o.bonds, &o.steps}) *n = r.i64();
    o.wall_seconds = r.f64();
    o.curve_strain = r.f64s();
    o.curve_stress_pa = r.f64s();
    if (o.curve_strain.size() != o.curve_stress_pa.size()) throw WireError("curve columns of different lengths");
    r.end();
    return m;
}

std::string encode(const Stop& m) {
    Writer w(Kind::stop);
    w.str(m.reason);
    return w.take();
}

Stop decode_stop(const std::string& bytes) {
    Reader r(bytes, Kind::stop);
    Stop m;
    m.reason = r.str();
    r.end();
    return m;
}

}  // namespace gradem::cal::wire
