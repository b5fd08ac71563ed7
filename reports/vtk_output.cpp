#include "reports/vtk_output.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "common/atomic_file.hpp"

namespace gradem::report {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// base64
// ---------------------------------------------------------------------------------------------
namespace {

constexpr char kBase64Alphabet[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Streaming base64 encoder: bytes may arrive in several pieces (the VTK length header, then
/// the values) and are encoded as one contiguous stream; finish() pads the last group.
class Base64Stream {
public:
    explicit Base64Stream(std::string& out) : out_(out) {}

    void feed(const unsigned char* bytes, std::size_t size) {
        std::size_t k = 0;
        while (carried_ > 0 && carried_ < 3 && k < size) carry_[carried_++] = bytes[k++];
        if (carried_ == 3) {
            emit(carry_[0], carry_[1], carry_[2]);
            carried_ = 0;
        }
        for (; k + 3 <= size; k += 3) emit(bytes[k], bytes[k + 1], bytes[k + 2]);
        while (k < size) carry_[carried_++] = bytes[k++];
    }

    void finish() {
        if (carried_ == 0) return;
        const unsigned char b1 = carried_ > 1 ? carry_[1] : 0;
        const unsigned v = (unsigned{carry_[0]} << 16) | (unsigned{b1} << 8);
        out_ += kBase64Alphabet[(v >> 18) & 63u];
        out_ += kBase64Alphabet[(v >> 12) & 63u];
        out_ += carried_ > 1 ? kBase64Alphabet[(v >> 6) & 63u] : '=';
        out_ += '=';
        carried_ = 0;
    }

private:
    std::string& out_;
    std::array<unsigned char, 3> carry_{};
    int carried_ = 0;

    void emit(unsigned char a, unsigned char b, unsigned char c) {
        const unsigned v = (unsigned{a} << 16) | (unsigned{b} << 8) | unsigned{c};
        out_ += kBase64Alphabet[(v >> 18) & 63u];
        out_ += kBase64Alphabet[(v >> 12) & 63u];
        out_ += kBase64Alphabet[(v >> 6) & 63u];
        out_ += kBase64Alphabet[v & 63u];
    }
};

}  // namespace

std::string base64_encode(const void* data, std::size_t size) {
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    Base64Stream stream(out);
    stream.feed(static_cast<const unsigned char*>(data), size);
    stream.finish();
    return out;
}

// ---------------------------------------------------------------------------------------------
// VTK XML building blocks
// ---------------------------------------------------------------------------------------------
namespace {

template <class T>
constexpr const char* vtk_type_name() {
    if constexpr (std::is_same_v<T, double>) return "Float64";
    else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
    else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
    else if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
    else static_assert(sizeof(T) == 0, "no VTK type for T");
}

constexpr const char* byte_order() {
    return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
}

/// Appends a number as text; doubles with 17 significant digits (exact round trip).
template <class T>
void append_number(std::string& out, T value) {
    std::array<char, 32> buf{};
    std::to_chars_result r{};
    if constexpr (std::is_floating_point_v<T>)
        r = std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::general,
                          17);
    else if constexpr (std::is_same_v<T, std::uint8_t>)
        r = std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<unsigned>(value));
    else
        r = std::to_chars(buf.data(), buf.data() + buf.size(), value);
    out.append(buf.data(), r.ptr);
}

/// Escapes the five XML special characters of an attribute value.
std::string xml_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

std::vector<double> flatten(const std::vector<Vec3>& v) {
    std::vector<double> out;
    out.reserve(3 * v.size());
    for (const Vec3& a : v) {
        out.push_back(a.x);
        out.push_back(a.y);
        out.push_back(a.z);
    }
    return out;
}

/// 0, 1, ..., n-1 (Vert connectivity) or step, 2 step, ..., n step (cell offsets).
std::vector<std::int64_t> arithmetic_sequence(std::size_t n, std::int64_t first,
                                              std::int64_t step) {
    std::vector<std::int64_t> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = first + static_cast<std::int64_t>(k) * step;
    return out;
}

/// One PolyData document built in memory, then written atomically.
class VtpDocument {
public:
    struct Counts {
        std::size_t points = 0, verts = 0, lines = 0;
    };

    explicit VtpDocument(VtkEncoding encoding) : encoding_(encoding) {
        out_ += "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"";
        out_ += byte_order();
        out_ += "\" header_type=\"UInt64\">\n<PolyData>\n";
    }

    /// FieldData with the simulation time [s] (ParaView's TimeValue) and step.
    void field_time(double time, std::int64_t step) {
        out_ += "<FieldData>\n";
        array("TimeValue", 1, std::vector<double>{time}, true);
        array("step", 1, std::vector<std::int64_t>{step}, true);
        out_ += "</FieldData>\n";
    }

    void begin_piece(const Counts& c) {
        out_ += "<Piece NumberOfPoints=\"";
        append_number(out_, c.points);
        out_ += "\" NumberOfVerts=\"";
        append_number(out_, c.verts);
        out_ += "\" NumberOfLines=\"";
        append_number(out_, c.lines);
        out_ += "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
    }

    void open(const char* section) {
        out_ += '<';
        out_ += section;
        out_ += ">\n";
    }
    void close(const char* section) {
        out_ += "</";
        out_ += section;
        out_ += ">\n";
    }

    /// Points [m] section.
    void points(const std::vector<Vec3>& x) {
        open("Points");
        array("Points", 3, flatten(x));
        close("Points");
    }

    /// Cell section ("Verts" or "Lines") from connectivity and offsets (named exactly so).
    void cells(const char* section, const std::vector<std::int64_t>& connectivity,
               const std::vector<std::int64_t>& offsets) {
        open(section);
        array("connectivity", 1, connectivity);
        array("offsets", 1, offsets);
        close(section);
    }

    template <class T>
    void array(const char* name, int components, const std::vector<T>& values,
               bool with_tuple_count = false) {
        out_ += "<DataArray type=\"";
        out_ += vtk_type_name<T>();
        out_ += "\" Name=\"";
        out_ += name;
        out_ += "\" NumberOfComponents=\"";
        append_number(out_, components);
        if (with_tuple_count) {
            out_ += "\" NumberOfTuples=\"";
            append_number(out_, values.size() / static_cast<std::size_t>(components));
        }
        out_ += encoding_ == VtkEncoding::base64 ? "\" format=\"binary\">" : "\" format=\"ascii\">";
        if (encoding_ == VtkEncoding::base64)
            append_base64(values);
        else
            append_ascii(values, components);
        out_ += "</DataArray>\n";
    }

    void write(const fs::path& path) {
        out_ += "</PolyData>\n</VTKFile>\n";
        common::write_file_atomically(path, out_);
    }

private:
    VtkEncoding encoding_;
    std::string out_;

    /// VTK inline binary: base64 of [UInt64 byte count][values], encoded as one stream.
    template <class T>
    void append_base64(const std::vector<T>& values) {
        const std::uint64_t bytes = values.size() * sizeof(T);
        out_.reserve(out_.size() + (bytes + sizeof bytes + 2) / 3 * 4);
        Base64Stream stream(out_);
        stream.feed(reinterpret_cast<const unsigned char*>(&bytes), sizeof bytes);
        if (!values.empty())
            stream.feed(reinterpret_cast<const unsigned char*>(values.data()), bytes);
        stream.finish();
    }

    /// Values separated by blanks, one tuple per line.
    template <class T>
    void append_ascii(const std::vector<T>& values, int components) {
        out_ += '\n';
        for (std::size_t k = 0; k < values.size(); ++k) {
            append_number(out_, values[k]);
            out_ += (k + 1) % static_cast<std::size_t>(components) == 0 ? '\n' : ' ';
        }
    }
};

/// Number of broken bonds touching each particle.
std::vector<std::int32_t> broken_bond_counts(const World& world) {
    std::vector<std::int32_t> count(world.particles().size(), 0);
    for (const ParallelBond& b : world.bonds()) {
        if (b.state != BondState::broken_tension && b.state != BondState::broken_shear) continue;
        ++count[static_cast<std::size_t>(b.i)];
        ++count[static_cast<std::size_t>(b.j)];
    }
    return count;
}

/// Step at which each bond broke, -1 if it never did.
std::vector<std::int64_t> bond_break_steps(const World& world) {
    std::vector<std::int64_t> step(world.bonds().size(), -1);
    for (const BreakEvent& e : world.break_events())
        if (e.bond >= 0 && static_cast<std::size_t>(e.bond) < step.size())
            step[static_cast<std::size_t>(e.bond)] = e.step;
    return step;
}

std::vector<Vec3> displacements(const ParticleSet& p, const std::vector<Vec3>& reference) {
    if (reference.size() != p.size())
        throw std::invalid_argument("write_particles_vtp: reference_positions has " +
                                    std::to_string(reference.size()) + " entries for " +
                                    std::to_string(p.size()) + " particles");
    std::vector<Vec3> d(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) d[k] = p.position[k] - reference[k];
    return d;
}

/// "Verts" section with one vertex per point.
void one_vert_per_point(VtpDocument& doc, std::size_t n) {
    doc.cells("Verts", arithmetic_sequence(n, 0, 1), arithmetic_sequence(n, 1, 1));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Particles, bonds, cracks
// ---------------------------------------------------------------------------------------------
void write_particles_vtp(const fs::path& path, const World& world,
                         const std::vector<Vec3>* reference_positions, VtkEncoding encoding) {
    const ParticleSet& p = world.particles();
    const std::size_t n = p.size();
    VtpDocument doc(encoding);
    doc.field_time(world.time(), world.step_count());
    doc.begin_piece({n, n, 0});
    doc.open("PointData");
    std::vector<std::int32_t> id(n);
    for (std::size_t k = 0; k < n; ++k) id[k] = static_cast<std::int32_t>(k);
    doc.array("id", 1, id);
    doc.array("radius", 1, p.radius);              // [m]
    doc.array("velocity", 3, flatten(p.velocity));  // [m/s]
    doc.array("force", 3, flatten(p.force));        // [N]
    doc.array("spin", 3, flatten(p.spin));          // [rad/s]
    doc.array("broken_bonds", 1, broken_bond_counts(world));
    if (reference_positions != nullptr)
        doc.array("displacement", 3, flatten(displacements(p, *reference_positions)));  // [m]
    doc.close("PointData");
    doc.points(p.position);
    one_vert_per_point(doc, n);
    doc.close("Piece");
    doc.write(path);
}

void write_bonds_vtp(const fs::path& path, const World& world, VtkEncoding encoding) {
    const ParticleSet& p = world.particles();
    const std::vector<ParallelBond>& bonds = world.bonds();
    const std::size_t m = bonds.size();
    const double lambda = world.bond_params().radius_multiplier;  // λ̄ [-]
    std::vector<std::uint8_t> state(m);
    std::vector<double> normal_force(m), shear_force(m), radius(m);
    std::vector<std::int64_t> connectivity(2 * m);
    for (std::size_t k = 0; k < m; ++k) {
        const ParallelBond& b = bonds[k];
        const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
        state[k] = static_cast<std::uint8_t>(b.state);
        normal_force[k] = b.normal_force;     // tension positive [N]
        shear_force[k] = norm(b.shear_force);  // [N]
        radius[k] = lambda * std::min(p.radius[i], p.radius[j]);  // R̄ [m]
        connectivity[2 * k] = b.i;
        connectivity[2 * k + 1] = b.j;
    }
    VtpDocument doc(encoding);
    doc.field_time(world.time(), world.step_count());
    doc.begin_piece({p.size(), 0, m});
    doc.open("CellData");
    doc.array("state", 1, state);
    doc.array("normal_force", 1, normal_force);
    doc.array("shear_force", 1, shear_force);
    doc.array("bond_radius", 1, radius);
    doc.array("break_step", 1, bond_break_steps(world));
    doc.close("CellData");
    doc.points(p.position);
    doc.cells("Lines", connectivity, arithmetic_sequence(m, 2, 2));
    doc.close("Piece");
    doc.write(path);
}

void write_cracks_vtp(const fs::path& path, const std::vector<BreakEvent>& cracks,
                      VtkEncoding encoding) {
    const std::size_t n = cracks.size();
    std::vector<Vec3> position(n), normal(n);
    std::vector<std::uint8_t> mode(n);
    std::vector<double> radius(n), time(n), tensile(n), shear(n);
    std::vector<std::int64_t> step(n);
    std::vector<std::int32_t> bond(n);
    for (std::size_t k = 0; k < n; ++k) {
        const BreakEvent& e = cracks[k];
        position[k] = e.position;
        normal[k] = e.normal;
        mode[k] = static_cast<std::uint8_t>(e.mode);
        radius[k] = e.bond_radius;
        step[k] = e.step;
        time[k] = e.time;
        tensile[k] = e.tensile_stress;
        shear[k] = e.shear_stress;
        bond[k] = e.bond;
    }
    VtpDocument doc(encoding);
    doc.begin_piece({n, n, 0});
    doc.open("PointData");
    doc.array("mode", 1, mode);              // 1 tension, 2 shear
    doc.array("normal", 3, flatten(normal));  // unit normal i -> j
    doc.array("radius", 1, radius);           // R̄ [m], for disc glyphs
    doc.array("step", 1, step);
    doc.array("time", 1, time);               // [s]
    doc.array("tensile_stress", 1, tensile);  // σ̄ at break [Pa]
    doc.array("shear_stress", 1, shear);      // τ̄ at break [Pa]
    doc.array("bond", 1, bond);               // index into World::bonds()
    doc.close("PointData");
    doc.points(position);
    one_vert_per_point(doc, n);
    doc.close("Piece");
    doc.write(path);
}

// ---------------------------------------------------------------------------------------------
// .pvd collection
// ---------------------------------------------------------------------------------------------
namespace {

/// `file` relative to `folder` with '/' separators; absolute if no relative path exists.
std::string relative_to(const fs::path& file, const fs::path& folder) {
    const fs::path abs_file = fs::absolute(file).lexically_normal();
    fs::path dir = fs::absolute(folder.empty() ? fs::path(".") : folder).lexically_normal();
    if (!dir.has_filename()) dir = dir.parent_path();  // drop a trailing separator
    const fs::path rel = abs_file.lexically_relative(dir);
    return (rel.empty() ? abs_file : rel).generic_string();
}

}  // namespace

PvdSeries::PvdSeries(fs::path pvd_path) : pvd_path_(std::move(pvd_path)) {}

void PvdSeries::add(double time, const fs::path& file, int part) {
    entries_.push_back({time, part, relative_to(file, pvd_path_.parent_path())});
}

void PvdSeries::write() const {
    std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"";
    out += byte_order();
    out += "\">\n<Collection>\n";
    for (const Entry& e : entries_) {
        out += "  <DataSet timestep=\"";
        append_number(out, e.time);
        out += "\" group=\"\" part=\"";
        append_number(out, e.part);
        out += "\" file=\"";
        out += xml_escape(e.file);
        out += "\"/>\n";
    }
    out += "</Collection>\n</VTKFile>\n";
    common::write_file_atomically(pvd_path_, out);
}

}  // namespace gradem::report
