// VTK XML output: the written .vtp/.pvd files are parsed back (a small reader below: DataArray
// by Name, base64 with its UInt64 length header, or ascii) and compared with the World they
// were written from: positions, radii, line connectivity, bond states, break steps, cracks.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/world.hpp"
#include "reports/vtk_output.hpp"

using namespace gradem;
using namespace gradem::report;
namespace fs = std::filesystem;

namespace {

// ------------------------------------------------------------------------------------------
// A minimal reader of the files under test.
// ------------------------------------------------------------------------------------------
std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in.good());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Value of attribute `name` inside the tag text `tag` ("" if absent).
std::string attribute(const std::string& tag, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const auto at = tag.find(key);
    if (at == std::string::npos) return "";
    const auto begin = at + key.size();
    return tag.substr(begin, tag.find('"', begin) - begin);
}

/// Text of the first opening tag `<element ...>`.
std::string opening_tag(const std::string& xml, const std::string& element) {
    const auto at = xml.find("<" + element + " ");
    REQUIRE(at != std::string::npos);
    return xml.substr(at, xml.find('>', at) - at + 1);
}

std::vector<unsigned char> base64_decode(const std::string& text) {
    static const std::string alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<unsigned char> out;
    unsigned bits = 0;
    int nbits = 0;
    for (const char c : text) {
        if (c == '=') break;
        const auto v = alphabet.find(c);
        REQUIRE(v != std::string::npos);  // no stray characters inside a block
        bits = (bits << 6) | static_cast<unsigned>(v);
        nbits += 6;
        if (nbits >= 8) {
            nbits -= 8;
            out.push_back(static_cast<unsigned char>((bits >> nbits) & 0xFFu));
        }
    }
    return out;
}

template <class T>
std::vector<double> reinterpret_as(const unsigned char* data, std::size_t bytes) {
    REQUIRE(bytes % sizeof(T) == 0);
    std::vector<double> out(bytes / sizeof(T));
    for (std::size_t k = 0; k < out.size(); ++k) {
        T v;
        std::memcpy(&v, data + k * sizeof(T), sizeof(T));
        out[k] = static_cast<double>(v);
    }
    return out;
}

struct DataArray {
    std::string type, format;
    int components = 1;
    std::vector<double> values;  // every type converted (exact for the values used here)
};

std::vector<double> decode_binary(const std::string& type, const std::string& text) {
    const std::vector<unsigned char> bytes = base64_decode(text);
    REQUIRE(bytes.size() >= 8);
    std::uint64_t header = 0;  // UInt64 byte count of the values that follow
    std::memcpy(&header, bytes.data(), 8);
    REQUIRE(header == bytes.size() - 8);
    const unsigned char* data = bytes.data() + 8;
    if (type == "Float64") return reinterpret_as<double>(data, header);
    if (type == "Int64") return reinterpret_as<std::int64_t>(data, header);
    if (type == "Int32") return reinterpret_as<std::int32_t>(data, header);
    if (type == "UInt8") return reinterpret_as<std::uint8_t>(data, header);
    FAIL("unexpected type " << type);
    return {};
}

std::vector<double> decode_ascii(const std::string& text) {
    std::istringstream in(text);
    std::vector<double> out;
    for (double v = 0; in >> v;) out.push_back(v);
    REQUIRE(in.eof());  // everything was a number
    return out;
}

DataArray find_array(const std::string& xml, const std::string& name) {
    const auto at = xml.find("Name=\"" + name + "\"");
    REQUIRE(at != std::string::npos);
    REQUIRE(xml.find("Name=\"" + name + "\"", at + 1) == std::string::npos);  // unique
    const auto tag_begin = xml.rfind("<DataArray", at);
    const auto tag_end = xml.find('>', at);
    const auto close = xml.find("</DataArray>", tag_end);
    const std::string tag = xml.substr(tag_begin, tag_end - tag_begin + 1);
    const std::string body = xml.substr(tag_end + 1, close - tag_end - 1);
    DataArray a;
    a.type = attribute(tag, "type");
    a.format = attribute(tag, "format");
    a.components = std::stoi(attribute(tag, "NumberOfComponents"));
    a.values = a.format == "binary" ? decode_binary(a.type, body) : decode_ascii(body);
    REQUIRE(a.values.size() % static_cast<std::size_t>(a.components) == 0);
    return a;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// One root VTKFile of the given type, every element used by the writer balanced.
void check_well_formed(const std::string& xml, const std::string& type) {
    CHECK(xml.rfind("<?xml version=\"1.0\"?>", 0) == 0);
    CHECK(count(xml, "<VTKFile ") == 1);
    CHECK(count(xml, "</VTKFile>") == 1);
    CHECK(xml.substr(xml.size() - 11) == "</VTKFile>\n");
    CHECK(attribute(opening_tag(xml, "VTKFile"), "type") == type);
    for (const char* e : {"PolyData", "Piece", "PointData", "CellData", "FieldData", "Points",
                          "Verts", "Lines", "DataArray", "Collection"}) {
        INFO(e);
        CHECK(count(xml, std::string("<") + e + ">") + count(xml, std::string("<") + e + " ") ==
              count(xml, std::string("</") + e + ">"));
    }
}

std::vector<double> flat(const std::vector<Vec3>& v) {
    std::vector<double> out;
    for (const Vec3& a : v) out.insert(out.end(), {a.x, a.y, a.z});
    return out;
}

// ------------------------------------------------------------------------------------------
// Fixtures
// ------------------------------------------------------------------------------------------

/// A fresh temporary folder, removed at the end of the test.
struct TempDir {
    fs::path path;
    explicit TempDir(const std::string& tag)
        : path(fs::temp_directory_path() /
               ("gradem_vtk_" + tag + "_" + std::to_string(::getpid()))) {
        fs::remove_all(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

bool has_leftover_tmp(const fs::path& dir) {
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string().find(".tmp") != std::string::npos) return true;
    return false;
}

constexpr double kR = 1.0e-3;      // sphere radius [m]
constexpr double kDt = 1.0e-7;     // time step [s]
constexpr double kPull = 1.0;      // pulling velocity of sphere 2 [m/s]

/// Three touching spheres on the x axis, two bonds (0-1, 1-2), all kinematically driven:
/// 0 and 1 held, 2 pulled along +x until bond 1-2 breaks in tension.
struct Row {
    World world;
    std::vector<Vec3> reference;

    Row() : world(make_particles(), ContactParams{}, SimParams{}) {
        ParticleSet& p = world.edit_particles();
        for (auto& f : p.flags) f = kFixedVelocity | kFixedSpin;
        REQUIRE(world.install_bonds(BondParams{}, 1e-9) == 2);
        world.set_time_step(kDt);
        world.set_particle_motion(2, {kPull, 0, 0}, {});
        reference = world.particles().position;
    }
    static ParticleSet make_particles() {
        ParticleSet p;
        p.add({0, 0, 0}, kR, 2650);
        p.add({2 * kR, 0, 0}, kR, 2650);
        p.add({4 * kR, 0, 0}, kR, 2650);
        return p;
    }
    /// Steps until the first break (at most `limit` steps).
    void pull_until_break(int limit = 5000) {
        for (int s = 0; s < limit && world.break_events().empty(); ++s) world.step();
        REQUIRE(world.break_events().size() == 1);
    }
    [[nodiscard]] std::size_t bond_of(std::int32_t j) const {
        for (std::size_t k = 0; k < world.bonds().size(); ++k)
            if (world.bonds()[k].j == j) return k;
        FAIL("no bond ending at " << j);
        return 0;
    }
};

}  // namespace

// ------------------------------------------------------------------------------------------
TEST_CASE("base64 encoding matches RFC 4648 test vectors", "[experiments][vtk]") {
    const std::map<std::string, std::string> vectors{
        {"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},        {"foo", "Zm9v"},
        {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
    for (const auto& [in, out] : vectors) CHECK(base64_encode(in.data(), in.size()) == out);
    const unsigned char high[] = {0xFB, 0xFF, 0xBF};
    CHECK(base64_encode(high, 3) == "+/+/");
}

TEST_CASE("particles .vtp of the initial state: points, radii, ids, verts", "[experiments][vtk]") {
    TempDir tmp("particles0");
    Row row;
    const fs::path file = tmp.path / "not" / "yet" / "there" / "particles_000000.vtp";
    write_particles_vtp(file, row.world, &row.reference);
    REQUIRE(fs::exists(file));
    CHECK_FALSE(has_leftover_tmp(tmp.path));

    const std::string xml = read_text(file);
    check_well_formed(xml, "PolyData");
    const std::string vtk = opening_tag(xml, "VTKFile");
    CHECK(attribute(vtk, "header_type") == "UInt64");
    CHECK(attribute(vtk, "version") == "1.0");
    CHECK(attribute(vtk, "byte_order") == "LittleEndian");
    const std::string piece = opening_tag(xml, "Piece");
    CHECK(attribute(piece, "NumberOfPoints") == "3");
    CHECK(attribute(piece, "NumberOfVerts") == "3");
    CHECK(attribute(piece, "NumberOfLines") == "0");

    const DataArray points = find_array(xml, "Points");
    CHECK(points.type == "Float64");
    CHECK(points.format == "binary");
    CHECK(points.components == 3);
    CHECK(points.values == flat(row.world.particles().position));
    CHECK(find_array(xml, "radius").values == std::vector<double>{kR, kR, kR});
    CHECK(find_array(xml, "id").type == "Int32");
    CHECK(find_array(xml, "id").values == std::vector<double>{0, 1, 2});
    CHECK(find_array(xml, "broken_bonds").values == std::vector<double>{0, 0, 0});
    CHECK(find_array(xml, "displacement").values == std::vector<double>(9, 0.0));
    CHECK(find_array(xml, "velocity").components == 3);
    CHECK(find_array(xml, "force").values.size() == 9);
    CHECK(find_array(xml, "spin").values.size() == 9);
    CHECK(find_array(xml, "connectivity").values == std::vector<double>{0, 1, 2});
    CHECK(find_array(xml, "offsets").values == std::vector<double>{1, 2, 3});
    CHECK(find_array(xml, "TimeValue").values == std::vector<double>{0.0});
    CHECK(find_array(xml, "step").values == std::vector<double>{0.0});
}

TEST_CASE("without reference positions there is no displacement array", "[experiments][vtk]") {
    TempDir tmp("nodisp");
    Row row;
    write_particles_vtp(tmp.path / "p.vtp", row.world);
    const std::string xml = read_text(tmp.path / "p.vtp");
    CHECK(xml.find("Name=\"displacement\"") == std::string::npos);
    const std::vector<Vec3> wrong(2);
    CHECK_THROWS_AS(write_particles_vtp(tmp.path / "q.vtp", row.world, &wrong),
                    std::invalid_argument);
    CHECK_FALSE(fs::exists(tmp.path / "q.vtp"));
}

TEST_CASE("bonds .vtp under load: one line per bond between the right particles",
          "[experiments][vtk]") {
    TempDir tmp("bonds_loaded");
    Row row;
    row.world.run(50);  // bond 1-2 in tension, not yet broken
    REQUIRE(row.world.break_events().empty());
    const fs::path file = tmp.path / "bonds.vtp";
    write_bonds_vtp(file, row.world);
    const std::string xml = read_text(file);
    check_well_formed(xml, "PolyData");
    const std::string piece = opening_tag(xml, "Piece");
    CHECK(attribute(piece, "NumberOfPoints") == "3");
    CHECK(attribute(piece, "NumberOfLines") == "2");
    CHECK(attribute(piece, "NumberOfVerts") == "0");

    const auto& bonds = row.world.bonds();
    std::vector<double> conn, normal, shear;
    for (const ParallelBond& b : bonds) {
        conn.insert(conn.end(), {double(b.i), double(b.j)});
        normal.push_back(b.normal_force);
        shear.push_back(norm(b.shear_force));
    }
    CHECK(find_array(xml, "connectivity").values == conn);
    CHECK(find_array(xml, "offsets").values == std::vector<double>{2, 4});
    CHECK(find_array(xml, "Points").values == flat(row.world.particles().position));
    CHECK(find_array(xml, "state").type == "UInt8");
    CHECK(find_array(xml, "state").values == std::vector<double>{3, 3});
    CHECK(find_array(xml, "normal_force").values == normal);
    CHECK(find_array(xml, "normal_force").values[row.bond_of(2)] > 0.0);  // tension positive
    CHECK(find_array(xml, "shear_force").values == shear);
    CHECK(find_array(xml, "bond_radius").values == std::vector<double>{kR, kR});  // λ̄ = 1
    CHECK(find_array(xml, "break_step").type == "Int64");
    CHECK(find_array(xml, "break_step").values == std::vector<double>{-1, -1});
    CHECK(find_array(xml, "TimeValue").values[0] == row.world.time());
    CHECK(find_array(xml, "step").values[0] == 50);
}

TEST_CASE("after a break: bond state and break step, broken-bond counts, displacement, crack",
          "[experiments][vtk]") {
    TempDir tmp("broken");
    Row row;
    row.pull_until_break();
    const BreakEvent& e = row.world.break_events().front();
    const std::size_t broken = row.bond_of(2), intact = row.bond_of(1);
    REQUIRE(static_cast<std::size_t>(e.bond) == broken);

    write_bonds_vtp(tmp.path / "bonds.vtp", row.world);
    write_particles_vtp(tmp.path / "particles.vtp", row.world, &row.reference);
    write_cracks_vtp(tmp.path / "cracks.vtp", row.world.break_events());
    CHECK_FALSE(has_leftover_tmp(tmp.path));

    SECTION("bonds") {
        const std::string xml = read_text(tmp.path / "bonds.vtp");
        const std::vector<double> state = find_array(xml, "state").values;
        const std::vector<double> step = find_array(xml, "break_step").values;
        CHECK(state[broken] == 1);  // broken in tension
        CHECK(state[intact] == 3);
        CHECK(step[broken] == double(e.step));
        CHECK(step[intact] == -1);
        CHECK(find_array(xml, "normal_force").values[broken] == 0.0);
    }
    SECTION("particles") {
        const std::string xml = read_text(tmp.path / "particles.vtp");
        const ParticleSet& p = row.world.particles();
        CHECK(find_array(xml, "broken_bonds").values == std::vector<double>{0, 1, 1});
        const std::vector<double> d = find_array(xml, "displacement").values;
        CHECK(d[6] == p.position[2].x - row.reference[2].x);
        CHECK(d[6] == Approx(kPull * row.world.time()).epsilon(1e-9));
        CHECK(d[0] == 0.0);
        const std::vector<double> v = find_array(xml, "velocity").values;
        CHECK(v[6] == kPull);
        CHECK(find_array(xml, "force").values == flat(p.force));
        CHECK(find_array(xml, "spin").values == flat(p.spin));
    }
    SECTION("cracks") {
        const std::string xml = read_text(tmp.path / "cracks.vtp");
        check_well_formed(xml, "PolyData");
        CHECK(attribute(opening_tag(xml, "Piece"), "NumberOfPoints") == "1");
        CHECK(attribute(opening_tag(xml, "Piece"), "NumberOfVerts") == "1");
        CHECK(find_array(xml, "Points").values == flat({e.position}));
        CHECK(find_array(xml, "mode").values == std::vector<double>{1});
        CHECK(find_array(xml, "normal").values == flat({e.normal}));
        CHECK(find_array(xml, "normal").values[0] == Approx(1.0));
        CHECK(find_array(xml, "radius").values == std::vector<double>{e.bond_radius});
        CHECK(find_array(xml, "step").values == std::vector<double>{double(e.step)});
        CHECK(find_array(xml, "time").values == std::vector<double>{e.time});
        CHECK(find_array(xml, "tensile_stress").values == std::vector<double>{e.tensile_stress});
        CHECK(find_array(xml, "shear_stress").values == std::vector<double>{e.shear_stress});
        CHECK(find_array(xml, "bond").values == std::vector<double>{double(e.bond)});
        CHECK(find_array(xml, "connectivity").values == std::vector<double>{0});
        CHECK(find_array(xml, "offsets").values == std::vector<double>{1});
    }
}

TEST_CASE("ascii encoding round-trips every value exactly", "[experiments][vtk]") {
    TempDir tmp("ascii");
    Row row;
    row.pull_until_break();
    row.world.run(7);
    write_particles_vtp(tmp.path / "p.vtp", row.world, &row.reference, VtkEncoding::ascii);
    write_bonds_vtp(tmp.path / "b.vtp", row.world, VtkEncoding::ascii);
    write_cracks_vtp(tmp.path / "c.vtp", row.world.break_events(), VtkEncoding::ascii);

    const std::string p = read_text(tmp.path / "p.vtp");
    check_well_formed(p, "PolyData");
    CHECK(count(p, "format=\"binary\"") == 0);
    CHECK(find_array(p, "Points").format == "ascii");
    CHECK(find_array(p, "Points").values == flat(row.world.particles().position));
    CHECK(find_array(p, "force").values == flat(row.world.particles().force));
    CHECK(find_array(p, "broken_bonds").values == std::vector<double>{0, 1, 1});

    const std::string b = read_text(tmp.path / "b.vtp");
    check_well_formed(b, "PolyData");
    const std::size_t broken = row.bond_of(2);
    CHECK(find_array(b, "state").values[broken] == 1);
    CHECK(find_array(b, "break_step").values[broken] ==
          double(row.world.break_events().front().step));
    std::vector<double> conn;
    for (const ParallelBond& bond : row.world.bonds()) conn.insert(conn.end(), {double(bond.i), double(bond.j)});
    CHECK(find_array(b, "connectivity").values == conn);

    const std::string c = read_text(tmp.path / "c.vtp");
    CHECK(find_array(c, "tensile_stress").values ==
          std::vector<double>{row.world.break_events().front().tensile_stress});
}

TEST_CASE("an empty crack list is a valid empty PolyData", "[experiments][vtk]") {
    TempDir tmp("nocracks");
    write_cracks_vtp(tmp.path / "cracks.vtp", {});
    const std::string xml = read_text(tmp.path / "cracks.vtp");
    check_well_formed(xml, "PolyData");
    CHECK(attribute(opening_tag(xml, "Piece"), "NumberOfPoints") == "0");
    CHECK(find_array(xml, "Points").values.empty());
    CHECK(find_array(xml, "mode").values.empty());
}

TEST_CASE(".pvd series lists every file with its timestep, relative to the .pvd folder",
          "[experiments][vtk]") {
    TempDir tmp("pvd");
    Row row;
    const fs::path out = tmp.path / "run" / "vtk";  // does not exist yet
    PvdSeries series(out / "series.pvd");
    auto snapshot = [&](const std::string& tag) {
        const fs::path particles = out / "frames" / ("particles_" + tag + ".vtp");
        const fs::path bonds = out / "frames" / ("bonds_" + tag + ".vtp");
        write_particles_vtp(particles, row.world, &row.reference);
        write_bonds_vtp(bonds, row.world);
        series.add(row.world.time(), particles, 0);
        series.add(row.world.time(), bonds, 1);
        series.write();
    };
    snapshot("0");  // the initial state
    row.world.run(40);
    snapshot("40");
    const double t40 = row.world.time();

    REQUIRE(fs::exists(out / "series.pvd"));
    CHECK(series.size() == 4);
    CHECK_FALSE(has_leftover_tmp(tmp.path));
    const std::string xml = read_text(out / "series.pvd");
    check_well_formed(xml, "Collection");
    REQUIRE(count(xml, "<DataSet ") == 4);

    std::vector<std::string> files, parts;
    std::vector<double> times;
    for (auto at = xml.find("<DataSet "); at != std::string::npos;
         at = xml.find("<DataSet ", at + 1)) {
        const std::string tag = xml.substr(at, xml.find("/>", at) - at + 2);
        files.push_back(attribute(tag, "file"));
        parts.push_back(attribute(tag, "part"));
        times.push_back(std::stod(attribute(tag, "timestep")));
    }
    CHECK(files == std::vector<std::string>{"frames/particles_0.vtp", "frames/bonds_0.vtp",
                                            "frames/particles_40.vtp", "frames/bonds_40.vtp"});
    CHECK(parts == std::vector<std::string>{"0", "1", "0", "1"});
    CHECK(times == std::vector<double>{0.0, 0.0, t40, t40});  // 17 digits: exact
    for (const std::string& f : files) CHECK(fs::exists(out / f));
}

TEST_CASE(".pvd file names: relative paths, parent folders and XML escaping",
          "[experiments][vtk]") {
    TempDir tmp("pvd_names");
    PvdSeries series(tmp.path / "a" / "s.pvd");
    series.add(1.5, tmp.path / "b" / "x&y.vtp");
    series.add(2.5, tmp.path / "a" / "." / "z.vtp", 3);
    series.write();
    const std::string xml = read_text(tmp.path / "a" / "s.pvd");
    CHECK(xml.find("file=\"../b/x&amp;y.vtp\"") != std::string::npos);
    CHECK(xml.find("timestep=\"1.5\" group=\"\" part=\"0\"") != std::string::npos);
    CHECK(xml.find("timestep=\"2.5\" group=\"\" part=\"3\" file=\"z.vtp\"") != std::string::npos);
}
