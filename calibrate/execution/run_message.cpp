#include "calibrate/execution/run_message.hpp"

#include <cstring>
#include <string_view>
#include <type_traits>

namespace gradem::cal::wire {
namespace {

constexpr std::uint32_t kMagic = 0x4D445247;  // "GRDM" little-endian
constexpr std::uint32_t kByteOrder = 0x01020304;

// Every shared field of the material is listed below, one by one; a bond law's own fields are
// written from its parameter rows (Law::kParameters). A new shared field changes these sizes:
// add it to the material's fields() (and to material_key), then update the sizes.
static_assert(sizeof(ContactParams) == 3 * 8, "ContactParams changed: serialise the new field in run_message.cpp");
static_assert(sizeof(BondParams) == 9 * 8 /* doubles */ + 8 /* seed */ + 8 /* model, padded */ + sizeof(BondLawParams) +
                                       8 /* replaces_contact, padded */,
              "BondParams changed: serialise the new field in run_message.cpp");
static_assert(sizeof(exp::MaterialParams) == 24 + sizeof(BondParams) + 4 * 8 + 3 * 8 /* families */,
              "MaterialParams changed: serialise the new field in run_message.cpp");

// Each message's fields are listed once, in `fields(io, message)`: the Writer writes them and
// the Reader reads them in that order, so encoder and decoder cannot drift apart. Strings and
// vectors are a u64 count then the items; enums and bools one byte (a read enum must be one of
// its table's values, common/named_enum.hpp).
class Writer {
public:
    explicit Writer(Kind kind) {
        raw(kMagic);
        raw(kProtocolVersion);
        raw(kByteOrder);
        raw(static_cast<std::uint8_t>(kind));
    }
    void operator()(std::uint64_t v) { raw(v); }
    void operator()(std::int64_t v) { raw(v); }
    void operator()(double v) { raw(v); }
    void operator()(bool v) { raw(static_cast<std::uint8_t>(v ? 1 : 0)); }
    template <class E>
        requires std::is_enum_v<E>
    void operator()(E v) {
        raw(static_cast<std::uint8_t>(v));
    }
    void operator()(const std::string& s) {
        raw(static_cast<std::uint64_t>(s.size()));
        out_ += s;
    }
    template <class T>
    void operator()(const std::vector<T>& v) {
        raw(static_cast<std::uint64_t>(v.size()));
        for (const T& x : v) (*this)(x);
    }
    std::string take() { return std::move(out_); }

private:
    template <class T>
    void raw(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        out_.append(b, sizeof(T));
    }
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
    void operator()(std::uint64_t& v) { v = raw<std::uint64_t>(); }
    void operator()(std::int64_t& v) { v = raw<std::int64_t>(); }
    void operator()(double& v) { v = raw<double>(); }
    void operator()(bool& v) { v = raw<std::uint8_t>() != 0; }
    template <class E>
        requires std::is_enum_v<E>
    void operator()(E& v) {
        const std::uint8_t byte = raw<std::uint8_t>();
        v = static_cast<E>(byte);
        if (std::string_view(to_string(v)) == "unknown") throw WireError("unknown enum value " + std::to_string(byte));
    }
    void operator()(std::string& s) {
        const std::uint64_t n = count(1);
        s = in_.substr(pos_, n);
        pos_ += n;
    }
    template <class T>
    void operator()(std::vector<T>& v) {
        v.resize(count(sizeof(T)));
        for (T& x : v) (*this)(x);
    }
    void end() const {
        if (pos_ != in_.size()) throw WireError(std::to_string(in_.size() - pos_) + " unexpected bytes at the end of a message");
    }

private:
    template <class T>
    T raw() {
        if (in_.size() - pos_ < sizeof(T)) throw WireError("truncated message (" + std::to_string(in_.size()) + " bytes)");
        T v;
        std::memcpy(&v, in_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    std::uint64_t count(std::size_t item_bytes) {
        const std::uint64_t n = raw<std::uint64_t>();
        if (item_bytes && n > (in_.size() - pos_) / item_bytes) throw WireError("truncated message (count " + std::to_string(n) + ")");
        return n;
    }
    const std::string& in_;
    std::size_t pos_ = 0;
};

// A bond law's row: an integer row as an integer, the others as the bits of their double.
template <class Row, class Params>
void law_row(Writer& w, const Row& row, const Params& p) {
    if (row.field.integer) w(static_cast<std::int64_t>(row.field.get_int(p)));
    else w(row.field.get(p));
}
template <class Row, class Params>
void law_row(Reader& r, const Row& row, Params& p) {
    double x = 0.0;
    std::int64_t n = 0;
    if (row.field.integer) r(n), row.field.set_int(p, n);
    else r(x), row.field.set(p, x);
}

// Material = exp::MaterialParams, const when written.
template <class Io, class Material>
void fields(Io& io, Material& m) {
    auto& c = m.contact;
    auto& b = m.bond;
    for (auto* x : {&c.effective_modulus, &c.stiffness_ratio, &c.friction, &b.effective_modulus, &b.stiffness_ratio,
                    &b.radius_multiplier, &b.moment_factor, &b.tensile_strength_mean, &b.tensile_strength_std, &b.cohesion_mean,
                    &b.cohesion_std, &b.friction_angle_deg})
        io(*x);
    io(b.seed);
    io(b.model);
    for_each_bond_law([&](auto kernel) {  // every law's own rows, in BondModel then row order
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) law_row(io, row, b.template law<Law>());
    });
    io(b.replaces_contact);
    for (auto* x : {&m.bond_gap_fraction, &m.bond_gap_absolute, &m.platen_friction, &m.damping}) io(*x);
    io(m.families.itz_strength_factor);
    io(m.families.itz_modulus_factor);
    io(m.families.sand_sand_bonded);
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Hello>
void fields(Io& io, M& m) {
    io(m.code_version), io(m.host), io(m.model_fingerprint), io(m.pid), io(m.threads), io(m.error);
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Prepare>
void fields(Io& io, M& m) {
    // every sand's list, then each sand's own: its length, then its seeds flattened
    io(m.seeds.common);
    std::vector<std::uint64_t> lengths, own;
    for (const auto& list : m.seeds.by_sand) {
        lengths.push_back(list.size());
        own.insert(own.end(), list.begin(), list.end());
    }
    io(lengths), io(own);
    if constexpr (!std::is_const_v<M>) {
        m.seeds.by_sand.clear();
        std::size_t at = 0;
        for (const std::uint64_t n : lengths) {
            if (n > own.size() - at) throw WireError("prepare message: seed list lengths exceed its seeds");
            m.seeds.by_sand.emplace_back(own.begin() + static_cast<std::ptrdiff_t>(at), own.begin() + static_cast<std::ptrdiff_t>(at + n));
            at += n;
        }
        if (at != own.size()) throw WireError("prepare message: seeds beyond its seed list lengths");
    }
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Prepared>
void fields(Io& io, M& m) {
    io(m.seconds), io(m.error);
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Run>
void fields(Io& io, M& m) {
    io(m.job), io(m.code_version), io(m.model_hash), io(m.timeout_s), io(m.request.sand), io(m.request.seed);
    fields(io, m.request.material);
    io(m.request.test);
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Result>
void fields(Io& io, M& m) {
    auto& o = m.outcome;
    io(m.job), io(o.status), io(o.reason);
    io(o.modulus_pa), io(o.peak_pa), io(o.strain_at_peak), io(o.poisson);
    io(o.particles), io(o.bonds), io(o.steps), io(o.wall_seconds);
    io(o.curve_strain), io(o.curve_stress_pa);
}

template <class Io, class M>
    requires std::is_same_v<std::remove_const_t<M>, Stop>
void fields(Io& io, M& m) {
    io(m.reason);
}

template <class M>
std::string encode_message(Kind kind, const M& m) {
    Writer w(kind);
    fields(w, m);
    return w.take();
}

template <class M>
M decode_message(const std::string& bytes, Kind kind) {
    Reader r(bytes, kind);
    M m;
    fields(r, m);
    r.end();
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

std::string encode(const Hello& m) { return encode_message(Kind::hello, m); }
Hello decode_hello(const std::string& bytes) { return decode_message<Hello>(bytes, Kind::hello); }

std::string encode(const Prepare& m) { return encode_message(Kind::prepare, m); }
Prepare decode_prepare(const std::string& bytes) { return decode_message<Prepare>(bytes, Kind::prepare); }

std::string encode(const Prepared& m) { return encode_message(Kind::prepared, m); }
Prepared decode_prepared(const std::string& bytes) { return decode_message<Prepared>(bytes, Kind::prepared); }

std::string encode(const Run& m) { return encode_message(Kind::run, m); }
Run decode_run(const std::string& bytes) { return decode_message<Run>(bytes, Kind::run); }

std::string encode(const Result& m) { return encode_message(Kind::result, m); }
Result decode_result(const std::string& bytes) {
    Result m = decode_message<Result>(bytes, Kind::result);
    if (m.outcome.curve_strain.size() != m.outcome.curve_stress_pa.size()) throw WireError("curve columns of different lengths");
    return m;
}

std::string encode(const Stop& m) { return encode_message(Kind::stop, m); }
Stop decode_stop(const std::string& bytes) { return decode_message<Stop>(bytes, Kind::stop); }

}  // namespace gradem::cal::wire
