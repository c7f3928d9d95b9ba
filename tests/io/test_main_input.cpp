// hubbeam import's library side (hubbeam/main_input.hpp): BModes' CertTest blade and the NREL 5 MW ElastoDyn files become
// scenes whose values are the files' (each read here from the file's text by its own search, not the importer's),
// that load; every refusal is one line naming the file, the line and the setting.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/main_input.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

constexpr double pi = std::numbers::pi;

std::string data(const std::string& name)
{
    return std::string(HUBBEAM_SOURCE_DIR) + "/tests/data/import/" + name;
}

std::string text_of(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> lines_of(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

/// The value written before `name` on its line (`VALUE NAME ...`, a trailing ':' after the name allowed), found by
/// a plain search of the text: the test's own reading of the file, shared with no code of the importer.
double value_before(const std::string& text, const std::string& name)
{
    for (const std::string& line : lines_of(text)) {
        std::istringstream in(line);
        std::string value, label;
        if (!(in >> value >> label)) continue;
        if (label == name || label == name + ":") return std::stod(value);
    }
    FAIL("no line with " << name);
    return 0.0;
}

/// text with line `line` (1-based) replaced by `by`.
std::string with_line(const std::string& text, int line, const std::string& by)
{
    std::vector<std::string> lines = lines_of(text);
    lines.at(static_cast<std::size_t>(line - 1)) = by;
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

/// The scene an input becomes, loaded by hubbeam's scene reader from a scene file in folder.
Scene imported(const std::string& input, const TempFolder& folder, std::string* toml = nullptr)
{
    const std::string scene_path = (folder.path / "imported.toml").string();
    const std::string text = imported_scene_toml(read_main_input(input), scene_path);
    if (toml) *toml = text;
    folder.write("imported.toml", text);
    return load_scene(scene_path);
}

/// The refusal of an input: its message, which must name file, line and setting.
MainInputError refusal_of(const std::string& input)
{
    try {
        const ImportedBlade b = read_main_input(input);
        (void)imported_scene_toml(b, (std::filesystem::path(input).parent_path() / "out.toml").string());
    } catch (const MainInputError& e) {
        return e;
    }
    FAIL("no refusal of " << input);
    return MainInputError("", 0, "", "");
}

}  // namespace

TEST_CASE("a BModes CertTest blade becomes a scene with the .bmi's values", "[import]")
{
    const std::string bmi = data("bmodes/Test01_hubbeam.bmi");
    const std::string text = text_of(bmi);
    TempFolder folder("import");
    std::string toml;
    const Scene scene = imported(bmi, folder, &toml);
    const Parameters& p = scene.parameters;
    CHECK(p.L == Approx(value_before(text, "radius") - value_before(text, "hub_rad")).epsilon(1e-15));
    CHECK(p.a == value_before(text, "hub_rad"));
    CHECK(p.precone == Approx(value_before(text, "precone") * pi / 180).margin(1e-15));
    CHECK(p.pitch == Approx(value_before(text, "bl_thp") * pi / 180).margin(1e-15));
    CHECK(scene.motion.kind == Motion::Kind::spin_up);
    CHECK(scene.motion.omega0 == Approx(value_before(text, "romg") * 2 * pi / 60).epsilon(1e-15));
    CHECK(p.m_tip == value_before(text, "tip_mass"));
    CHECK(p.J_tip == value_before(text, "ixx_tip"));
    // The section file named, and every column a twist field needs: flap, edge and twist out of the plane.
    REQUIRE(scene.tables.size() == 1);
    CHECK(std::filesystem::equivalent(scene.tables[0].second, data("bmodes/blade_sec_props_no_offsets.dat")));
    CHECK(scene.variant.method == Method::fem);
    CHECK(scene.variant.nz > 0);
    CHECK(scene.variant.nt > 0);
    CHECK(scene.variant.nx == 0);
    CHECK(toml.find("hubbeam modes") != std::string::npos);
}

TEST_CASE("a BModes blade with its tension centre off the axis becomes a scene whose axis stretches", "[import]")
{
    // CertTest's section file with tc_offst set to -sc_offst at every station (BModes' own e_a for that blade).
    TempFolder folder("import");
    std::vector<std::string> rows = lines_of(text_of(data("bmodes/blade_sec_props.dat")));
    std::vector<double> tc;
    for (std::size_t r = 5; r < 26; ++r) {
        std::istringstream in(rows[r]);
        std::vector<std::string> f(13);
        for (std::string& x : f) in >> x;
        tc.push_back(-std::stod(f[11]));
        f[12] = std::to_string(tc.back());
        rows[r].clear();
        for (const std::string& x : f) rows[r] += x + "  ";
    }
    std::string sections;
    for (const std::string& l : rows) sections += l + "\n";
    folder.write("blade_sec_props.dat", sections);
    const std::string bmi = folder.write(
        "tension.bmi", with_line(text_of(data("bmodes/Test01_nonunif_blade.bmi")), 8, "1.0       romg_mult:"));
    const Scene scene = imported(bmi, folder);
    CHECK(scene.variant.nx > 0);
    CHECK(scene.variant.extras.offsets);
    const std::vector<double>& o = scene.parameters.offsets;
    REQUIRE(o.size() == 2 * tc.size());
    for (std::size_t k = 0; k < tc.size(); ++k) CHECK(o[2 * k + 1] == tc[k]);
}

TEST_CASE("a BModes tip mass and a nonzero precone and pitch reach the scene in SI units", "[import]")
{
    TempFolder folder("import");
    std::string text = text_of(data("bmodes/Test01_hubbeam.bmi"));
    text = with_line(text, 11, "3.5       precone:    built-in precone angle (deg)");
    text = with_line(text, 12, "-7.25     bl_thp:     blade pitch setting (deg)");
    text = with_line(text, 19, "40.       tip_mass    blade-tip mass (kg)");
    text = with_line(text, 21, "10.0      ixx_tip     blade lag mass moment of inertia (kg-m^2)");
    std::filesystem::copy_file(data("bmodes/blade_sec_props_no_offsets.dat"),
                               folder.path / "blade_sec_props_no_offsets.dat");
    const Scene scene = imported(folder.write("tip.bmi", text), folder);
    CHECK(scene.parameters.precone == Approx(3.5 * pi / 180).margin(1e-15));
    CHECK(scene.parameters.pitch == Approx(-7.25 * pi / 180).margin(1e-15));
    CHECK(scene.parameters.m_tip == 40.0);
    CHECK(scene.parameters.J_tip == 10.0);
}

TEST_CASE("the NREL 5 MW ElastoDyn files become a scene with their values, their damping as modal ratios",
          "[import][modal_damping]")
{
    const std::string main = data("5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat");
    const std::string text = text_of(main);
    const std::string blade_text = text_of(data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat"));
    TempFolder folder("import");
    std::string toml;
    const Scene scene = imported(main, folder, &toml);
    const Parameters& p = scene.parameters;
    CHECK(p.L == Approx(value_before(text, "TipRad") - value_before(text, "HubRad")).epsilon(1e-15));
    CHECK(p.a == value_before(text, "HubRad"));
    CHECK(p.precone == Approx(value_before(text, "PreCone(1)") * pi / 180).margin(1e-15));
    CHECK(p.precone < 0.0);  // -2.5 deg: coned upwind
    CHECK(p.pitch == Approx(value_before(text, "BlPitch(1)") * pi / 180).margin(1e-15));
    CHECK(scene.motion.omega0 == Approx(value_before(text, "RotSpeed") * pi / 30).epsilon(1e-15));
    CHECK(p.m_tip == value_before(text, "TipMass(1)"));
    REQUIRE(scene.tables.size() == 1);
    CHECK(std::filesystem::equivalent(scene.tables[0].second, data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat")));
    // Its 49 stations read as they are (no resampling); no EA, GJ or mass moments.
    CHECK(scene.blade_stations == 0);
    CHECK(scene.parameters.stations.size() == 49);
    CHECK(scene.variant.nx == 0);
    CHECK(scene.variant.nt == 0);
    CHECK(scene.variant.nz > 0);

    const ImportedBlade b = read_main_input(main);
    REQUIRE(b.damping.size() == 3);
    CHECK(b.damping[0].name == "BldFlDmp(1)");
    CHECK(b.damping[0].value == value_before(blade_text, "BldFlDmp(1)"));
    CHECK(b.damping[2].name == "BldEdDmp(1)");
    CHECK(b.damping[2].value == value_before(blade_text, "BldEdDmp(1)"));
    // Percent of critical as fractions: the blade's first two flap modes and its first edge mode (docs/import.md).
    const ModalDamping& d = scene.modal_damping;
    REQUIRE(d.flap.size() == 2);
    REQUIRE(d.edge.size() == 1);
    CHECK(d.flap[0] == Approx(value_before(blade_text, "BldFlDmp(1)") / 100).epsilon(1e-15));
    CHECK(d.flap[1] == Approx(value_before(blade_text, "BldFlDmp(2)") / 100).epsilon(1e-15));
    CHECK(d.edge[0] == Approx(value_before(blade_text, "BldEdDmp(1)") / 100).epsilon(1e-15));
    CHECK(scene.parameters.alpha == 0.0);
    CHECK(scene.parameters.beta == 0.0);
    CHECK(toml.find("not modelled") == std::string::npos);
    CHECK(toml.find("BldEdDmp(1) = 0.477465 % (NRELOffshrBsline5MW_Blade.dat:7)") != std::string::npos);
}

TEST_CASE("ElastoDyn's Gravity becomes a commented [gravity], a tip mass a [tip]", "[import]")
{
    TempFolder folder("import");
    std::filesystem::create_directories(folder.path / "5MW_Baseline");
    std::filesystem::create_directories(folder.path / "main");
    std::filesystem::copy_file(data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat"),
                               folder.path / "5MW_Baseline/NRELOffshrBsline5MW_Blade.dat");
    std::string text = text_of(data("5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"));
    // FAST v8's layout: an ENVIRONMENTAL CONDITION section after SIMULATION CONTROL.
    text = with_line(text, 6,
                     "\"DEFAULT\"     DT          - Integration time step (s)\n"
                     "---------------------- ENVIRONMENTAL CONDITION ---------------------------------\n"
                     "   9.80665    Gravity     - Gravitational acceleration (m/s^2)");
    text = with_line(text, 71 + 2, "        350   TipMass(1)  - Tip-brake mass, blade 1 (kg)");
    text = with_line(text, 72 + 2, "        350   TipMass(2)  - Tip-brake mass, blade 2 (kg)");
    text = with_line(text, 73 + 2, "        350   TipMass(3)  - Tip-brake mass, blade 3 (kg)");
    std::string toml;
    const Scene scene = imported(folder.write("main/ed.dat", text), folder, &toml);
    CHECK(scene.parameters.m_tip == 350.0);
    CHECK(scene.parameters.g == 0.0);  // commented: the modes about a steady spin are without gravity
    CHECK(toml.find("# [gravity]\n# g = 9.80665\n") != std::string::npos);
}

TEST_CASE("every setting hubbeam does not model is refused naming the file, the line and the setting", "[import]")
{
    struct Case {
        const char* input;  // in tests/data/import
        int line;           // 0: the input as it is
        const char* by;
        int refused_line;
        const char* setting;
        const char* says;
    };
    const Case bmi = {"bmodes/Test01_hubbeam.bmi", 0, "", 0, "", ""};
    const std::vector<Case> cases = {
        {bmi.input, 8, "-1.0      romg_mult:  rotor speed muliplicative factor (-)", 8, "romg_mult", ">= 0"},
        {bmi.input, 6, "2         beam_type   1: blade, 2: tower (-)", 6, "beam_type", "not a tower"},
        {bmi.input, 13, "2         hub_conn:   hub-to-blade connection", 13, "hub_conn", "cantilevered"},
        {bmi.input, 22, "-1.75     iyy_tip     blade flap inertia", 22, "iyy_tip", ">= 0"},
        {bmi.input, 24, "0.1       ixy_tip     cross product", 24, "ixy_tip", "principal axes"},
        {bmi.input, 25, "0.1       izx_tip     cross product", 25, "izx_tip", "principal axes"},
        {bmi.input, 29, "2         id_mat:     material_type", 29, "id_mat", "isotropic"},
        {bmi.input, 33, "-1.1      sec_mass_mult:   mass density multiplier (-)", 33, "sec_mass_mult",
         "blade_scale.mass"},
        {bmi.input, 38, "0         tor_stff_mult:   torsion stiffness multiplier (-)", 38, "tor_stff_mult", "> 0"},
        {bmi.input, 42, "fast      tc_offst_mult:   tension center multiplier (-)", 42, "tc_offst_mult",
         "a finite number"},
        {bmi.input, 7, "fast      romg:       rotor speed (rpm)", 7, "romg", "a finite number"},
        {bmi.input, 9, "35.0      hub_rad:    swapped", 9, "radius", "by position"},
        {bmi.input, 9, "1.0       radius:     shorter than the hub", 9, "radius", "above hub_rad"},
        {bmi.input, 11, "120.      precone:    far beyond the scene's bound (deg)", 11, "precone", "beam.precone"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.setting, c.line);
        TempFolder folder("import");
        std::string input = data(c.input);
        if (c.line > 0) {
            std::filesystem::copy_file(data("bmodes/blade_sec_props_no_offsets.dat"),
                                       folder.path / "blade_sec_props_no_offsets.dat");
            input = folder.write("edited.bmi", with_line(text_of(input), c.line, c.by));
        }
        const MainInputError e = refusal_of(input);
        CHECK(e.line == c.refused_line);
        CHECK(e.setting == c.setting);
        CHECK(
            std::string(e.what()).starts_with(e.file + ":" + std::to_string(c.refused_line) + ": " + c.setting + ": "));
        CHECK_THAT(e.what(), Catch::Contains(c.says));
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
    }
}

TEST_CASE("an ElastoDyn setting hubbeam does not model, or blades unlike blade 1, are refused by line", "[import]")
{
    struct Case {
        int line;
        const char* by;
        const char* setting;
        const char* says;
    };
    const std::vector<Case> cases = {
        {26, "        0.1   OoPDefl     - Initial out-of-plane blade-tip displacement (meters)", "OoPDefl",
         "undeformed"},
        {27, "        0.1   IPDefl      - Initial in-plane blade-tip deflection (meters)", "IPDefl", "undeformed"},
        {29, "          2   BlPitch(2)  - Blade 2 initial pitch (degrees)", "BlPitch(2)", "alike"},
        {48, "         -3   PreCone(2)  - Blade 2 cone angle (degrees)", "PreCone(2)", "alike"},
        {73, "         10   TipMass(3)  - Tip-brake mass, blade 3 (kg)", "TipMass(3)", "alike"},
        {88, "\"other.dat\"    BldFile(3)  - blade 3", "BldFile(3)", "alike"},
        {50, "          0   NewSetting  - a setting hubbeam does not know", "NewSetting", "knows"},
        {33, "       fast   RotSpeed    - Initial or fixed rotor speed (rpm)", "RotSpeed", "a finite number"},
        {45, "          1   TipRad      - The distance from the rotor apex to the blade tip (meters)", "TipRad",
         "above HubRad"},
        {47, "        100   PreCone(1)  - Blade 1 cone angle (degrees)", "PreCone(1)", "beam.precone"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.setting);
        TempFolder folder("import");
        std::filesystem::create_directories(folder.path / "5MW_Baseline");
        std::filesystem::create_directories(folder.path / "main");
        std::filesystem::copy_file(data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat"),
                                   folder.path / "5MW_Baseline/NRELOffshrBsline5MW_Blade.dat");
        std::string text = text_of(data("5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"));
        if (std::string(c.setting) == "PreCone(1)")  // all three alike, so that the scene's bound refuses it
            for (int line : {47, 48, 49})
                text = with_line(text, line, "        100   PreCone(" + std::to_string(line - 46) + ")  - cone");
        else
            text = with_line(text, c.line, c.by);
        const MainInputError e = refusal_of(folder.write("main/ed.dat", text));
        CHECK(e.line == c.line);
        CHECK(e.setting == c.setting);
        CHECK(std::string(e.what()).starts_with(e.file + ":" + std::to_string(c.line) + ": " + c.setting + ": "));
        CHECK_THAT(e.what(), Catch::Contains(c.says));
    }
}

TEST_CASE("a blade file's modal tuner other than 1 is refused, and two blades leave blade 3's settings unread",
          "[import]")
{
    TempFolder folder("import");
    std::filesystem::create_directories(folder.path / "5MW_Baseline");
    std::filesystem::create_directories(folder.path / "main");
    const std::string blade = (folder.path / "5MW_Baseline/NRELOffshrBsline5MW_Blade.dat").string();
    std::ofstream(blade) << with_line(text_of(data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat")), 9,
                                      "        1.1   FlStTunr(1) - Blade flapwise modal stiffness tuner, 1st mode (-)");
    const std::string text = text_of(data("5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"));
    const MainInputError e = refusal_of(folder.write("main/ed.dat", text));
    CHECK(e.line == 9);
    CHECK(e.setting == "FlStTunr(1)");
    CHECK_THAT(e.what(), Catch::Contains("NRELOffshrBsline5MW_Blade.dat:9: FlStTunr(1): expected 1"));

    std::filesystem::copy_file(data("5MW_Baseline/NRELOffshrBsline5MW_Blade.dat"), blade,
                               std::filesystem::copy_options::overwrite_existing);
    std::string two = with_line(text, 44, "          2   NumBl       - Number of blades (-)");
    two = with_line(two, 49, "         -9   PreCone(3)  - Blade 3 cone angle (degrees) [unused for 2 blades]");
    CHECK_NOTHROW(imported(folder.write("main/two.dat", two), folder));
}

TEST_CASE("a missing or malformed blade file is refused naming its file and line", "[import]")
{
    TempFolder folder("import");
    // The .bmi as it is, without its section file beside it.
    const MainInputError lonely = refusal_of(folder.write("lonely.bmi", text_of(data("bmodes/Test01_hubbeam.bmi"))));
    CHECK(lonely.line == 30);
    CHECK(lonely.setting == "sec_props_file");
    CHECK_THAT(lonely.what(), Catch::EndsWith("blade_sec_props_no_offsets.dat"));
    std::filesystem::create_directories(folder.path / "main");
    const MainInputError no_blade = refusal_of(
        folder.write("main/ed.dat", text_of(data("5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"))));
    CHECK(no_blade.line == 86);
    CHECK(no_blade.setting == "BldFile(1)");
    CHECK_THAT(no_blade.what(), Catch::Contains("ed.dat:86: BldFile(1): expected a file that exists"));
    // CertTest's own section file, with its shear-centre offsets (read, not used: docs/model.md section 12.6), and its
    // romg_mult 2 of BModes v1, which divides the stiffnesses by its square and multiplies the frequencies by it: the
    // blade at twice romg.
    const std::string certtest = folder.write("certtest.bmi", text_of(data("bmodes/Test01_nonunif_blade.bmi")));
    std::filesystem::copy_file(data("bmodes/blade_sec_props.dat"), folder.path / "blade_sec_props.dat");
    std::string certtest_toml;
    const Scene certtest_scene = imported(certtest, folder, &certtest_toml);
    CHECK(certtest_scene.motion.omega0 == Approx(2.0 * 60.0 * pi / 30).epsilon(1e-15));
    CHECK_THAT(certtest_toml, Catch::Contains("romg = 60.0 rpm (certtest.bmi:7) times romg_mult = 2.0 (certtest.bmi:8)"));
    // A file of neither format.
    const std::string neither = folder.write("neither.dat", "just some text\n");
    CHECK_THROWS_AS(read_main_input(neither), MainInputError);
    try {
        (void)read_main_input((folder.path / "absent.bmi").string());
    } catch (const MainInputError& e) {
        CHECK_THAT(e.what(), Catch::EndsWith("absent.bmi: expected an existing file"));
    }
}

TEST_CASE("a BModes v3 file, with rot_rpm and a cm_axial line, reads alike, and an axial offset is refused", "[import]")
{
    TempFolder folder("import");
    std::filesystem::copy_file(data("bmodes/blade_sec_props_no_offsets.dat"),
                               folder.path / "blade_sec_props_no_offsets.dat");
    std::string text = text_of(data("bmodes/Test01_hubbeam.bmi"));
    text = with_line(text, 7, "60.0      rot_rpm:    rotor speed (rpm)");
    text = with_line(text, 8, "1.0       rpm_mult:   rotor speed multiplicative factor (-)");
    text = with_line(text, 20,
                     "0.        cm_loc      tip-mass c.m. offset (m)\n"
                     "0.        cm_axial    tip-mass c.m. axial offset (m)");
    const Scene scene = imported(folder.write("v3.bmi", text), folder);
    CHECK(scene.motion.omega0 == Approx(60.0 * pi / 30).epsilon(1e-15));
    CHECK(scene.parameters.J_tip == 0.0);
    // BModes v3 spins the blade at rot_rpm times rpm_mult (BModes.f90: rot_rpm = rot_rpm*rpm_mult).
    const Scene faster = imported(
        folder.write("v3_mult.bmi", with_line(text, 8, "1.5       rpm_mult:   rotor speed multiplicative factor (-)")),
        folder);
    CHECK(faster.motion.omega0 == Approx(90.0 * pi / 30).epsilon(1e-15));

    const MainInputError e = refusal_of(
        folder.write("v3_offset.bmi", with_line(text, 21, "0.2       cm_axial    tip-mass c.m. axial offset")));
    CHECK(e.line == 21);
    CHECK(e.setting == "cm_axial");
    CHECK_THAT(e.what(), Catch::Contains("tip section's plane"));
}

TEST_CASE("BModes' CertTest 02 tip body becomes [tip]'s mass, lag, flap and torsion inertias and offset", "[import]")
{
    // tests/data/import/bmodes/Test02_blade_with_tip_mass.bmi is BModes' own, with its section file pointed at the
    // copy without shear and tension centre offsets (hubbeam refuses those).
    TempFolder folder("import");
    std::filesystem::copy_file(data("bmodes/blade_sec_props_no_offsets.dat"),
                               folder.path / "blade_sec_props_no_offsets.dat");
    const std::string text = text_of(data("bmodes/Test02_blade_with_tip_mass.bmi"));
    REQUIRE(lines_of(text).at(30).find("sec_props_file") != std::string::npos);
    std::string toml;
    const Scene scene = imported(
        folder.write("test02.bmi", with_line(text, 31, "'blade_sec_props_no_offsets.dat' sec_props_file")), folder,
        &toml);
    const Parameters& p = scene.parameters;
    CHECK(p.m_tip == value_before(text, "tip_mass"));
    CHECK(p.J_tip == value_before(text, "ixx_tip"));  // lag: about the chord's normal
    CHECK(p.J_tip_flap == value_before(text, "iyy_tip"));
    CHECK(p.J_tip_twist == value_before(text, "izz_tip"));
    CHECK(p.tip_offset == value_before(text, "cm_loc"));  // towards the trailing edge, as cg_offst
    CHECK(p.tip_offset == 0.05);
    CHECK(scene.key().extras.tip_body);
    CHECK(toml.find("offset = 0.05") != std::string::npos);
    CHECK(toml.find("cm_loc = 0.05 m (test02.bmi:20)") != std::string::npos);
}

TEST_CASE("BModes' property multipliers become [blade_scale], each naming its line, and scale the blade as BModes does",
          "[import]")
{
    // The mass and both mass moments four times the section file's, its stiffnesses as they are: at rest every
    // natural frequency is half the unscaled blade's (K q = omega^2 M q with M four times larger), bending and twist
    // alike. sc_offst_mult is read and not used.
    TempFolder folder("import");
    std::filesystem::copy_file(data("bmodes/blade_sec_props_no_offsets.dat"),
                               folder.path / "blade_sec_props_no_offsets.dat");
    const std::string text = text_of(data("bmodes/Test01_hubbeam.bmi"));
    std::string heavy = with_line(text, 33, "4.0       sec_mass_mult:   mass density multiplier (-)");
    heavy = with_line(heavy, 34, "4.0       flp_iner_mult:   blade flap inertia multiplier (-)");
    heavy = with_line(heavy, 35, "4.0       lag_iner_mult:   blade lag inertia multiplier (-)");
    heavy = with_line(heavy, 41, "7.0       sc_offst_mult:   shear center multiplier (-)");
    std::string toml;
    const Scene plain = imported(folder.write("plain.bmi", text), folder);
    const Scene scaled = imported(folder.write("heavy.bmi", heavy), folder, &toml);
    CHECK_THAT(toml, Catch::Contains("[blade_scale]"));
    CHECK_THAT(toml, Catch::Contains("# sec_mass_mult = 4.0 (heavy.bmi:33)"));
    CHECK_THAT(toml, Catch::Contains("# lag_iner_mult = 4.0 (heavy.bmi:35)"));
    CHECK(toml.find("sc_offst_mult") == std::string::npos);
    CHECK(scaled.blade_scale.mass == 4.0);
    CHECK(scaled.blade_scale.inertia_flap == 4.0);
    CHECK(scaled.blade_scale.inertia_edge == 4.0);
    CHECK(scaled.blade_scale.stiffness_flap == 1.0);
    const auto rates = [](const Scene& s) {
        const auto model = make_model(s.key(), s.parameters, ModelSource::assembled);
        std::vector<double> out;
        for (const NaturalMode& m : natural_modes(*model, steady_spin(*model, 0.0))) out.push_back(m.rad_s);
        return out;
    };
    const std::vector<double> a = rates(plain), b = rates(scaled);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() >= 6);
    // To the round-off of the symmetric eigen-solve in its inverse form, eps (omega_k / omega_1)^2 of mode k
    // (docs/performance.md, "A real blade's Campbell table"): at most 8e-11 here, the highest mode 600 times the first.
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("mode " << i << ": " << a[i] << " and " << b[i] << " rad/s");
        CHECK(std::abs(b[i] - a[i] / 2.0) < 1e-10 * a[i]);
    }
}
