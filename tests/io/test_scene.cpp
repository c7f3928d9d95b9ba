// Scene files: the paper's four load cases in cases/ parse to the values docs/model.md section 6 states, and bad
// input stops in load_scene() with one line naming the file, the key and what was expected.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <hubbeam/output.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/scene_print.hpp>
#include <map>
#include <string>
#include <vector>

#include "io/scene_io.hpp"
#include "terms.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

std::string case_path(const std::string& name)
{
    return std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + name;
}

/// Checks the beam of docs/model.md section 6 and the discretization and solver every paper case shares.
void check_paper_common(const Scene& s)
{
    CHECK(s.parameters.L == 8.0);
    CHECK(s.parameters.rho == 2.7667e3);
    CHECK(s.parameters.S == 7.2968e-5);
    CHECK(s.parameters.I == 8.2189e-9);
    CHECK(s.parameters.E == 6.8952e10);
    CHECK(s.parameters.a == 0.0);
    CHECK(s.variant.method == Method::amm);
    CHECK(s.variant.nx == 4);
    CHECK(s.variant.ny == 4);
    CHECK(s.variant.order == Order::first);
    CHECK(s.source == ModelSource::automatic);
    CHECK(s.solver.stepper == "auto");  // cases/ name no stepper: chosen by stiffness
    CHECK(s.solver.rtol == 1e-8);
    CHECK(s.solver.atol == 1e-10);
    CHECK(s.output.t_end == 30.0);
    CHECK(s.output.dt_out == 0.01);
    CHECK(s.output.file.empty());
}

using TempDir = TempFolder;

// A small valid scene; the bad inputs below are edits of it.
const std::string good_scene = R"([beam]
length = 8.0
density = 2.7667e3
area = 7.2968e-5
second_moment = 8.2189e-9
youngs_modulus = 6.8952e10

[motion]
kind = "spin-up"
omega0 = 4.0
duration = 15.0

[discretization]
method = "amm"
ny = 4
nx = 0

[output]
t_end = 30.0
)";

/// good_scene with the first occurrence of from replaced by to (which must occur).
std::string edited(const std::string& from, const std::string& to)
{
    std::string s = good_scene;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

/// The SceneError message of loading text, which must be one line opening with the file's name.
std::string error_of(const TempDir& dir, const std::string& text)
{
    const std::string file = dir.write("scene.toml", text);
    try {
        load_scene(file);
    } catch (const SceneError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find('\n') == std::string::npos);
        CHECK(message.rfind(file + ":", 0) == 0);
        return message;
    }
    FAIL("no SceneError for:\n" << text);
    return {};
}

}  // namespace

TEST_CASE("the load cases of the paper in cases/ parse to docs/model.md section 6", "[scene]")
{
    SECTION("spin-up, Omega0 = 4")
    {
        const Scene s = load_scene(case_path("spinup_omega4.toml"));
        check_paper_common(s);
        CHECK(s.motion.kind == Motion::Kind::spin_up);
        CHECK(s.motion.omega0 == 4.0);
        CHECK(s.motion.spin_time == 15.0);
        CHECK(s.variant.drive == Drive::prescribed);
        CHECK(s.path == case_path("spinup_omega4.toml"));
    }
    SECTION("spin-up, Omega0 = 10")
    {
        const Scene s = load_scene(case_path("spinup_omega10.toml"));
        check_paper_common(s);
        CHECK(s.motion.kind == Motion::Kind::spin_up);
        CHECK(s.motion.omega0 == 10.0);
        CHECK(s.motion.spin_time == 15.0);
        CHECK(s.variant.drive == Drive::prescribed);
    }
    SECTION("hub torque, tau0 = 1")
    {
        const Scene s = load_scene(case_path("torque_tau1.toml"));
        check_paper_common(s);
        CHECK(s.motion.kind == Motion::Kind::torque);
        CHECK(s.motion.tau0 == 1.0);
        CHECK(s.motion.torque_time == 10.0);
        CHECK(s.parameters.J_oh == 30.0);
        CHECK(s.variant.drive == Drive::torque);
    }
    SECTION("hub torque, tau0 = 10")
    {
        const Scene s = load_scene(case_path("torque_tau10.toml"));
        check_paper_common(s);
        CHECK(s.motion.kind == Motion::Kind::torque);
        CHECK(s.motion.tau0 == 10.0);
        CHECK(s.motion.torque_time == 10.0);
        CHECK(s.parameters.J_oh == 30.0);
        CHECK(s.variant.drive == Drive::torque);
    }
}

TEST_CASE("optional scene keys take their documented defaults", "[scene]")
{
    const TempDir dir;
    const Scene s = load_scene(dir.write("minimal.toml", edited("length = 8.0", "length = 8")));
    CHECK(s.parameters.L == 8.0);  // a TOML integer is a number
    CHECK(s.parameters.a == 0.0);
    CHECK(s.parameters.J_oh == 30.0);
    CHECK(s.variant.spline == SplineBasis::paper);
    CHECK(s.variant.order == Order::first);
    CHECK(s.source == ModelSource::automatic);
    CHECK(s.solver.stepper == "auto");
    CHECK(s.solver.rtol == 1e-8);
    CHECK(s.solver.atol == 1e-10);
    CHECK(s.solver.h0 == 1e-4);
    CHECK(s.solver.max_steps == 10'000'000);
    CHECK(s.output.dt_out == 0.01);
    CHECK(s.output.file.empty());

    const Scene t = load_scene(dir.write("full.toml", good_scene + R"(
[hub]
radius = 0.5
inertia = 12

[model]
order = "zero"
source = "assembled"

[solver]
stepper = "rk8pd"
rtol = 1e-6
atol = 1e-9
h0 = 1e-3
max_steps = 2e5
)"));
    CHECK(t.parameters.a == 0.5);
    CHECK(t.parameters.J_oh == 12.0);
    CHECK(t.variant.order == Order::zero);
    CHECK(t.source == ModelSource::assembled);
    CHECK(t.solver.stepper == "rk8pd");
    CHECK(t.solver.rtol == 1e-6);
    CHECK(t.solver.atol == 1e-9);
    CHECK(t.solver.h0 == 1e-3);
    CHECK(t.solver.max_steps == 200'000);

    const Scene u = load_scene(dir.write("open.toml", edited("method = \"amm\"\nny = 4",
                                                             "method = \"bsim\"\n"
                                                             "spline_basis = \"open\"\nny = 3")));
    CHECK(u.variant.method == Method::bsim);
    CHECK(u.variant.spline == SplineBasis::open);
    CHECK(u.variant.ny == 3);
}

TEST_CASE("bad scene input throws SceneError naming the file and the key", "[scene]")
{
    const TempDir dir;
    const auto names = [&](const std::string& text, const std::string& key, const std::string& detail) {
        const std::string message = error_of(dir, text);
        INFO(message);
        CHECK(message.find(": " + key + ": ") != std::string::npos);
        CHECK(message.find(detail) != std::string::npos);
    };

    SECTION("missing key")
    {
        names(edited("length = 8.0\n", ""), "beam.length", "missing");
    }
    SECTION("missing table")
    {
        names(edited("[output]\nt_end = 30.0\n", ""), "output", "missing");
    }
    SECTION("mistyped key")
    {
        names(edited("length = 8.0", "lenght = 8.0"), "beam.lenght", "unknown key");
    }
    SECTION("unknown table")
    {
        names(good_scene + "[extras]\nx = 1\n", "extras", "unknown table");
    }
    SECTION("key of the other motion kind")
    {
        names(edited("omega0 = 4.0", "tau0 = 4.0"), "motion.tau0", "unknown key");
    }
    SECTION("non-positive length")
    {
        names(edited("length = 8.0", "length = 0"), "beam.length", "> 0");
    }
    SECTION("negative length")
    {
        names(edited("length = 8.0", "length = -8.0"), "beam.length", "got -8");
    }
    SECTION("a pitch of more than a turn, either way")
    {
        names(edited("length = 8.0", "length = 8.0\npitch = 1e308"), "beam.pitch", "from -2 pi to 2 pi");
        names(edited("length = 8.0", "length = 8.0\npitch = -6.3"), "beam.pitch", "got -6.3");
    }
    SECTION("a pre-twist of more than a turn, either way (a propeller's of a radian and more is taken)")
    {
        names(edited("length = 8.0", "length = 8.0\ntwist = 6.3"), "beam.twist", "from -2 pi to 2 pi");
        names(edited("length = 8.0", "length = 8.0\ntwist = -1e308"), "beam.twist", "got -1e+308");
    }
    SECTION("non-positive density")
    {
        names(edited("density = 2.7667e3", "density = -1"), "beam.density", "> 0");
    }
    SECTION("non-positive Young's modulus")
    {
        names(edited("youngs_modulus = 6.8952e10", "youngs_modulus = 0.0"), "beam.youngs_modulus", "> 0");
    }
    SECTION("non-positive second moment")
    {
        names(edited("second_moment = 8.2189e-9", "second_moment = -8.2189e-9"), "beam.second_moment", "> 0");
    }
    SECTION("step budget not a whole number")
    {
        names(good_scene + "[solver]\nmax_steps = 1.5\n", "solver.max_steps", "got 1.5");
    }
    SECTION("step budget below one")
    {
        names(good_scene + "[solver]\nmax_steps = 0\n", "solver.max_steps", "a whole number from 1");
    }
    SECTION("not a number")
    {
        names(edited("area = 7.2968e-5", "area = nan"), "beam.area", "got nan");
    }
    SECTION("unknown method")
    {
        names(edited("method = \"amm\"", "method = \"xfem\""), "discretization.method", "\"fem\"");
    }
    SECTION("odd ny for FEM")
    {
        names(edited("method = \"amm\"\nny = 4", "method = \"fem\"\nny = 3"), "discretization.ny", "even");
    }
    SECTION("ny = 3 for BSIM with the paper's basis")
    {
        names(edited("method = \"amm\"\nny = 4", "method = \"bsim\"\nny = 3"), "discretization.ny", "ny >= 4");
    }
    SECTION("nx = 1 for BSIM")
    {
        names(edited("method = \"amm\"\nny = 4\nnx = 0", "method = \"bsim\"\nny = 4\nnx = 1"), "discretization.nx",
              "nx = 0 or nx >= 3");
    }
    SECTION("ny = 0")
    {
        names(edited("ny = 4", "ny = 0"), "discretization.ny", "integer >= 1");
    }
    SECTION("wrong type: string for a number")
    {
        names(edited("length = 8.0", "length = \"8.0\""), "beam.length", "got a string \"8.0\"");
    }
    SECTION("wrong type: float for a DOF count")
    {
        names(edited("ny = 4", "ny = 4.0"), "discretization.ny", "float");
    }
    SECTION("wrong type: table for a key")
    {
        names(edited("t_end = 30.0", "t_end = { x = 1 }"), "output.t_end", "got a table");
    }
    SECTION("wrong type: key for a table")
    {
        names("beam = 8.0\n" + good_scene.substr(good_scene.find("[motion]")), "beam", "got a float 8");
    }
    SECTION("unknown motion kind")
    {
        names(edited("\"spin-up\"", "\"spinup\""), "motion.kind", "\"spin-up\"");
    }
    SECTION("torque without hub inertia")
    {
        names(edited("kind = \"spin-up\"\nomega0 = 4.0", "kind = \"torque\"\ntau0 = 1.0"), "hub.inertia", "missing");
    }
    SECTION("unknown stepper")
    {
        names(good_scene + "[solver]\nstepper = \"euler\"\n", "solver.stepper", "msadams");
    }
    SECTION("non-positive tolerance")
    {
        names(good_scene + "[solver]\nrtol = 0\n", "solver.rtol", "(0, 1)");
    }
    SECTION("output interval beyond the end time")
    {
        names(edited("t_end = 30.0", "t_end = 1.0\ndt_out = 2.0"), "output.dt_out", "<= output.t_end");
    }
    SECTION("a tip body's flap inertia, torsion inertia or offset on a beam in its plane")
    {
        for (const std::string key : {"inertia_flap", "inertia_twist", "offset"})
            names(edited("[motion]", "[tip]\nmass = 1.0\n" + key + " = 0.5\n\n[motion]"), "tip." + key,
                  "a beam that leaves the plane");
    }
    SECTION("a tip body in the blade's axes at order full, and a negative inertia")
    {
        std::string full = edited("[motion]", "[tip]\noffset = 0.1\n\n[model]\norder = \"full\"\n\n[motion]");
        full.replace(full.find("nx = 0\n"), 7, "nx = 0\nnz = 2\n");
        names(full, "tip.offset", "order first or zero");
        names(edited("[motion]", "[tip]\ninertia_twist = -1.0\n\n[motion]"), "tip.inertia_twist", ">= 0");
    }
    SECTION("unknown model order")
    {
        names(good_scene + "[model]\norder = \"second\"\n", "model.order", "\"first\"");
    }
    SECTION("TOML syntax error: line and column")
    {
        const std::string message = error_of(dir, edited("length = 8.0", "length = = 8.0"));
        const std::string file = (dir.path / "scene.toml").string();
        CHECK(message.rfind(file + ":2:", 0) == 0);
    }
    SECTION("missing file")
    {
        const std::string file = (dir.path / "no-such-scene.toml").string();
        CHECK_THROWS_WITH(load_scene(file), file + ": cannot open: No such file or directory");
    }
}

TEST_CASE("solver.error_check takes on, off and full, from the file and as an override - other words are refused",
          "[scene]")
{
    const TempDir dir;
    CHECK(load_scene(dir.write("default.toml", good_scene)).solver.error_check == ErrorCheck::on);
    for (const auto& [word, check] : {std::pair{"on", ErrorCheck::on}, {"off", ErrorCheck::off},
                                      {"full", ErrorCheck::full}}) {
        INFO(word);
        const std::string text = good_scene + "\n[solver]\nerror_check = \"" + word + "\"\n";
        CHECK(load_scene(dir.write(std::string(word) + ".toml", text)).solver.error_check == check);
        const std::string file = dir.write("override.toml", good_scene);
        CHECK(load_scene(file, {{"solver.error_check", word}}).solver.error_check == check);
        CHECK(to_string(check) == word);
    }
    const std::string message = error_of(dir, good_scene + "\n[solver]\nerror_check = \"whole\"\n");
    CHECK(message.find("solver.error_check: expected one of \"on\", \"off\", \"full\", got ") != std::string::npos);
    CHECK(message.find("\"whole\"") != std::string::npos);
}

TEST_CASE("each term's own key refuses a value outside its range, naming the key and what it takes", "[scene][terms]")
{
    // The ranges docs/scene.md gives these keys, written here apart from the registry that the reader checks.
    const std::map<std::string, std::vector<std::string>> refused = {
        {"tip.mass", {"-1", "nan"}},
        {"tip.inertia", {"-1e-9"}},
        {"tip.inertia_flap", {"-1"}},
        {"tip.inertia_twist", {"-1"}},
        {"tip.offset", {"inf", "-inf"}},
        {"gravity.g", {"nan", "inf"}},
        {"damping.mass_proportional", {"-0.5"}},
        {"damping.stiffness_proportional", {"-1e-3"}},
        {"support.stiffness_x", {"-1"}},
        {"support.stiffness_y", {"-1"}},
        {"support.damping_x", {"-1"}},
        {"support.damping_y", {"inf"}}};
    std::size_t seen = 0;
    for (const TermInfo& t : terms())
        for (const TermSceneKey& k : t.scene_keys) {
            const std::string name = k.name();
            REQUIRE(refused.count(name) == 1);
            ++seen;
            CHECK(scene_key(name).expected == k.expected());
            for (const std::string& value : refused.at(name)) {
                INFO(name << " = " << value);
                try {
                    (void)load_scene(case_path("spinup_omega4.toml"), {{name, value}});
                    FAIL("accepted");
                } catch (const SceneError& e) {
                    CHECK(e.key == name);
                    CHECK(e.expected == k.expected());
                }
            }
        }
    CHECK(seen == refused.size());
}

TEST_CASE("validate() re-checks a scene changed after loading", "[scene]")
{
    Scene s = load_scene(case_path("spinup_omega4.toml"));
    REQUIRE_NOTHROW(validate(s));
    s.variant.method = Method::fem;
    s.variant.ny = 3;
    CHECK_THROWS_WITH(validate(s), Catch::Contains("discretization.ny: FEM needs an even ny"));
    s.variant.ny = 4;
    REQUIRE_NOTHROW(validate(s));
    s.output.dt_out = 0.0;
    CHECK_THROWS_AS(validate(s), SceneError);
    s.output.dt_out = 0.01;
    s.solver.stepper = "euler";
    CHECK_THROWS_WITH(validate(s), Catch::Contains("solver.stepper"));
}

TEST_CASE("overrides set keys before validation, and SceneError carries file, key, expected and got", "[scene]")
{
    const std::string file = case_path("spinup_omega4.toml");
    const Scene s = load_scene(file, {{"discretization.method", "fem"}, {"discretization.ny", "8"},
                                      {"solver.rtol", "1e-6"}, {"output.file", "x.csv"}});
    CHECK(s.variant.method == Method::fem);
    CHECK(s.variant.ny == 8);
    CHECK(s.solver.rtol == 1e-6);
    CHECK(s.output.file == "x.csv");
    try {
        load_scene(file, {{"discretization.ny", "4.5"}});
        FAIL("a non-integer ny was accepted");
    } catch (const SceneError& e) {
        CHECK(e.file == file);
        CHECK(e.key == "discretization.ny");
        CHECK(e.expected == "an integer >= 1 (Ny)");
        CHECK(e.got == "\"4.5\"");
        CHECK(e.problem() == "expected an integer >= 1 (Ny), got \"4.5\"");
    }
    try {
        load_scene(file, {{"discretization.method", "fem"}, {"discretization.ny", "3"}});
        FAIL("an odd FEM ny was accepted");
    } catch (const SceneError& e) {
        CHECK(e.key == "discretization.ny");
        CHECK(e.detail == "FEM needs an even ny (a deflection and a slope per node), got 3");
        CHECK(e.problem() == e.detail);
        CHECK(std::string(e.what()) == file + ": discretization.ny: " + e.detail);
    }
}

TEST_CASE("a table accepts exactly the keys the key table gives it, [motion] those of its kind", "[scene]")
{
    // Each key of the table, set in each paper case (as an override, which puts it into the parsed file), is
    // either accepted or refused for its value, never as unknown; a [motion] key of the other kind is unknown.
    const std::vector<std::string> kinds = {"spin-up", "torque", "held", "table", "torque-table", "step"};
    const TempDir dir;
    dir.write("rig.csv", "t,tau\n0,0\n1,1\n40,0\n");
    const std::map<std::string, std::string> files = {
        {"spin-up", case_path("spinup_omega4.toml")},
        {"torque", case_path("torque_tau10.toml")},
        {"held", case_path("held_gravity.toml")},
        {"table", case_path("table_spinup.toml")},
        {"torque-table", dir.write("rig.toml", edited("kind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0",
                                                      "kind = \"torque-table\"\nfile = \"rig.csv\"") +
                                             "[hub]\ninertia = 30.0\n")},
        {"step", case_path("controlled_step.toml")}};
    for (const SceneKey& key : scene_keys()) {
        for (const std::string& k : key.motion_kinds) CHECK(std::find(kinds.begin(), kinds.end(), k) != kinds.end());
        const std::string value = key.kind == SceneKey::Kind::integer  ? "4"
                                  : key.kind == SceneKey::Kind::number ? "0.5"
                                                                       : "x";
        for (const std::string& kind : kinds) {
            INFO(key.name << " = " << value << " in a " << kind << " scene");
            const bool belongs = key.motion_kinds.empty() ||
                                 std::find(key.motion_kinds.begin(), key.motion_kinds.end(), kind) != key.motion_kinds.end();
            std::string got;
            try {
                load_scene(files.at(kind), {{key.name, value}});
            } catch (const SceneError& e) {
                got = e.got;
                if (e.key != key.name) continue;  // another key's value check came first: says nothing of this one
            }
            CHECK((got == "an unknown key") == !belongs);
        }
    }
    // And nothing else: a key of one table is unknown in another, and the message lists the table's own keys.
    try {
        const std::string text = "[beam]\nlength = 8\ndensity = 1\narea = 1\nsecond_moment = 1\nyoungs_modulus = 1\n"
                                 "ny = 4\n[motion]\nkind = \"spin-up\"\nomega0 = 1\nduration = 1\n"
                                 "[discretization]\nmethod = \"amm\"\nny = 4\nnx = 0\n[output]\nt_end = 1\n";
        parse_scene(text, "s.toml");
        FAIL("beam.ny was accepted");
    } catch (const SceneError& e) {
        CHECK(e.key == "beam.ny");
        CHECK(e.expected == "one of length, density, area, second_moment, youngs_modulus, taper, tip_ratio, profile, "
                            "blade_file, blade_stations, second_moment_flap, shear_modulus, torsion_constant, pitch, "
                            "twist, precone");
        CHECK(e.got == "an unknown key");
    }
    // The parameters of the paper's two motions: Omega0 and T_s (eq. 58), tau0 and T_t (eq. 59).
    CHECK(table_keys("motion", "spin-up") == std::vector<std::string>{"kind", "omega0", "duration", "theta0"});
    CHECK(table_keys("motion", "torque") == std::vector<std::string>{"kind", "tau0", "duration", "theta0"});
    // A held hub has its angle only; a table its file, and the angle it starts from.
    CHECK(table_keys("motion", "held") == std::vector<std::string>{"kind", "angle"});
    CHECK(table_keys("motion", "step") == std::vector<std::string>{"kind", "angle"});
    CHECK(table_keys("motion", "table") == std::vector<std::string>{"kind", "theta0", "file"});
    CHECK(table_keys("motion", "torque-table") == std::vector<std::string>{"kind", "theta0", "file"});
    CHECK(scene_tables() == std::vector<std::string>{"beam", "blade_scale", "hub", "support", "tip", "damping",
                                                     "gravity", "motion", "control", "rotor", "discretization",
                                                     "model", "solver", "output", "initial"});
    // [blade_scale]'s keys are the factors the reader and the printer iterate, in their order.
    std::vector<std::string> factors;
    for (const scene_io::BladeScaleField& f : scene_io::blade_scale_fields) factors.push_back(f.key);
    CHECK(table_keys("blade_scale") == factors);
}

TEST_CASE("printable() escapes what could move, recolour or reorder a terminal, in hubbeam.printable's forms",
          "[scene]")
{
    CHECK(printable("plain ascii, \"quoted\" \\ backslash") == "plain ascii, \"quoted\" \\ backslash");
    CHECK(printable("\x1b[31m\n\t\x7f") == "\\x1b[31m\\x0a\\x09\\x7f");
    CHECK(printable(std::string("a\0b", 3)) == "a\\x00b");
    // Letters of other scripts pass as they are.
    CHECK(printable("\xc3\xa9t\xc3\xa9 \xe4\xb8\xad \xf0\x9f\x99\x82") == "\xc3\xa9t\xc3\xa9 \xe4\xb8\xad \xf0\x9f\x99\x82");
    // C1 controls (U+0085, U+009B: a one-byte CSI on some terminals) as Python writes them.
    CHECK(printable("\xc2\x85\xc2\x9b") == "\\x85\\x9b");
    // Bidirectional overrides, isolates and marks; zero-width characters; line separators; a language tag.
    CHECK(printable("\xe2\x80\xae") == "\\u202e");                            // U+202E
    CHECK(printable("\xe2\x81\xa6\xe2\x81\xa9") == "\\u2066\\u2069");         // U+2066, U+2069
    CHECK(printable("\xe2\x80\x8e\xe2\x80\x8f\xd8\x9c") == "\\u200e\\u200f\\u061c");
    CHECK(printable("\xe2\x80\x8b\xef\xbb\xbf\xe2\x80\xa8") == "\\u200b\\ufeff\\u2028");
    CHECK(printable("\xf3\xa0\x80\x81") == "\\U000e0001");
    // Bytes that are not UTF-8, one escape each: a stray continuation byte, 0xff, an overlong '/', a surrogate,
    // a sequence cut short at the end.
    CHECK(printable("\x80\xff") == "\\x80\\xff");
    CHECK(printable("\xc0\xaf") == "\\xc0\\xaf");
    CHECK(printable("\xed\xa0\x80") == "\\xed\\xa0\\x80");
    CHECK(printable("x\xe2\x80") == "x\\xe2\\x80");
    // Escaping twice changes nothing: messages built from printable parts may pass through it again.
    const std::string once = printable("\x1b\xe2\x80\xae\xff");
    CHECK(printable(once) == once);
    // The cap cuts between characters, never inside one.
    CHECK(printable(std::string(10, 'a') + "\xc3\xa9", 10) == "aaaaaaaaaa...");
    CHECK(printable("\xc3\xa9\xc3\xa9", 1) == "\xc3\xa9...");
}

TEST_CASE("messages quoting a scene value escape it, from the file or from an override", "[scene]")
{
    const TempDir dir;
    const std::string esc_rlo = "x\\u001b[31m\\u202e";  // TOML's spelling of x ESC [31m U+202E
    const auto no_raw = [](const std::string& message) {
        INFO(message);
        CHECK(message.find('\x1b') == std::string::npos);
        CHECK(message.find("\xe2\x80\xae") == std::string::npos);
    };
    SECTION("a string where a word is expected")
    {
        const std::string m = error_of(dir, edited("method = \"amm\"", "method = \"" + esc_rlo + "\""));
        no_raw(m);
        CHECK(m.find("discretization.method: expected one of") != std::string::npos);
        CHECK(m.find("got a string \"x\\x1b[31m\\u202e\"") != std::string::npos);
    }
    SECTION("an unknown stepper set by an override, as --stepper reports it")
    {
        const Overrides overrides = {{"solver.stepper", "x\x1b[31m\xe2\x80\xae"}};
        try {
            load_scene(case_path("spinup_omega4.toml"), overrides);
            FAIL("the stepper was accepted");
        } catch (const SceneError& e) {
            const std::string m = message_for(e, overrides);
            no_raw(m);
            CHECK(m.rfind("--stepper: expected one of", 0) == 0);
            CHECK(m.find("got \"x\\x1b[31m\\u202e\"") == m.size() - std::string("got \"x\\x1b[31m\\u202e\"").size());
        }
    }
}

TEST_CASE("the printed scene escapes what could drive a terminal, in TOML's and JSON's forms, and reads back",
          "[scene]")
{
    // By hand: U+202E (a right-to-left override), U+E0001 (a language tag: beyond U+FFFF, where TOML writes
    // \U and JSON a surrogate pair: 0xE0001 - 0x10000 = 0xD0001, whose top ten bits 0x340 and low ten 0x001).
    CHECK(quoted_string("a\xe2\x80\xae" "b") == "\"a\\u202eb\"");
    CHECK(quoted_string("\xf3\xa0\x80\x81", Quoting::toml) == "\"\\U000e0001\"");
    CHECK(quoted_string("\xf3\xa0\x80\x81", Quoting::json) == "\"\\udb40\\udc01\"");
    CHECK(quoted_string("\x1b\x9b\"\\\n\t\xc3\xa9") == "\"\\u001b\\u009b\\\"\\\\\\n\\t\xc3\xa9\"");
    // --print-scene's text: the override's U+202E escaped, and the printed scene reads back to the same name.
    const TempDir dir;
    const std::string name = (dir.path / "x\xe2\x80\xae.csv").string();
    const Scene s = load_scene(case_path("spinup_omega4.toml"), {{"output.file", name}});
    const std::string toml = effective_scene_toml(s);
    CHECK(toml.find("\xe2\x80\xae") == std::string::npos);
    CHECK(toml.find("x\\u202e.csv\"") != std::string::npos);
    CHECK(load_scene(dir.write("printed.toml", toml)).output.file == name);
}

TEST_CASE("output.file holds a file name: no NUL inside, not empty", "[scene]")
{
    const TempDir dir;
    SECTION("a NUL in the scene file")
    {
        const std::string m = error_of(dir, good_scene + "file = \"a\\u0000b.csv\"\n");
        CHECK(m.find(": output.file: expected a file name with no NUL character, got a string \"a\\x00b.csv\"") !=
              std::string::npos);
    }
    SECTION("a NUL in another string key")
    {
        const std::string m = error_of(dir, good_scene + "[solver]\nstepper = \"rk4\\u0000imp\"\n");
        CHECK(m.find(": solver.stepper: expected one of") != std::string::npos);
        CHECK(m.find("with no NUL character, got a string \"rk4\\x00imp\"") != std::string::npos);
    }
    SECTION("an empty name in the scene file")
    {
        const std::string m = error_of(dir, good_scene + "file = \"\"\n");
        CHECK(m.find(": output.file: expected a file name, got an empty one") != std::string::npos);
    }
    SECTION("overrides, as -o reports them")
    {
        for (const std::string& name : {std::string(), std::string("a\0b.csv", 7)}) {
            const Overrides overrides = {{"output.file", name}};
            try {
                load_scene(case_path("spinup_omega4.toml"), overrides);
                FAIL("output.file = \"" << printable(name) << "\" was accepted");
            } catch (const SceneError& e) {
                const std::string m = message_for(e, overrides);
                CHECK(m == (name.empty() ? "-o: expected a file name, got an empty one"
                                         : "-o: expected a file name with no NUL character, got a string "
                                           "\"a\\x00b.csv\""));
            }
        }
    }
}

TEST_CASE("the held, table and torque-table scenes in cases/ and in files parse to their values", "[scene]")
{
    SECTION("held under gravity")
    {
        const Scene s = load_scene(case_path("held_gravity.toml"));
        CHECK(s.motion.kind == Motion::Kind::held);
        CHECK(s.motion.angle == 0.0);
        CHECK(s.motion.drive() == Drive::prescribed);
        CHECK(s.parameters.g == 9.81);
        CHECK(s.key().extras.gravity);
    }
    SECTION("a table of the paper's spin-up, next to its scene")
    {
        const Scene s = load_scene(case_path("table_spinup.toml"));
        CHECK(s.motion.kind == Motion::Kind::table);
        REQUIRE(s.motion.table);
        CHECK(s.motion.table_file == case_path("table_spinup.csv"));
        CHECK(s.motion.table->times().size() == 121);
        CHECK(s.motion.table->last_time() == 30.0);
        CHECK(s.motion.drive() == Drive::prescribed);
        // Its rows are eq. 58's angle: 4 rad/s reached at T_s = 15 s after turning Omega0 T_s / 2 = 30 rad.
        CHECK(s.motion.theta(15.0) == Approx(30.0).epsilon(1e-12));
        CHECK(s.motion.at(30.0).theta_dot == Approx(4.0).epsilon(1e-6));
    }
    SECTION("theta0, a torque table relative to the scene's folder, and an absolute path")
    {
        const TempDir dir;
        std::filesystem::create_directories(dir.path / "sub");
        dir.write("sub/rig.csv", "time_note,t , tau\r\nx,0,1.5\r\n\r\ny,2,-0.5\r\n");  // CRLF, blanks, extra column
        const std::string torque_table = "kind = \"torque-table\"\ntheta0 = 0.25\nfile = \"rig.csv\"";
        const Scene s = load_scene(dir.write("sub/scene.toml", edited("kind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0",
                                                                     torque_table) +
                                                              "[hub]\ninertia = 30.0\n"),
                                   {{"output.t_end", "2"}});
        CHECK(s.motion.kind == Motion::Kind::torque_table);
        CHECK(s.motion.drive() == Drive::torque);
        CHECK(s.motion.theta0 == 0.25);
        CHECK(s.motion.initial_theta() == 0.25);
        CHECK(s.motion.at(1.0).tau == Approx(0.5).epsilon(1e-15));
        CHECK(s.motion.breakpoints() == std::vector<double>{0.0, 2.0});
        const std::string absolute = (dir.path / "sub" / "rig.csv").string();
        const Scene a = load_scene(dir.write("elsewhere.toml", edited("kind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0",
                                                                     "kind = \"torque-table\"\nfile = \"" + absolute +
                                                                         "\"") +
                                                                   "[hub]\ninertia = 30.0\n"),
                                   {{"output.t_end", "2"}});
        CHECK(a.motion.table_file == absolute);
        CHECK(a.motion.theta0 == 0.0);
        const Scene u = load_scene(dir.write("spin.toml", edited("duration = 15.0", "duration = 15.0\ntheta0 = -1")));
        CHECK(u.motion.theta0 == -1.0);
        CHECK(u.motion.at(0.0).theta == -1.0);
    }
}

TEST_CASE("a bad [motion] of the new kinds, or a bad motion table, is refused naming the scene, the key and the CSV",
          "[scene]")
{
    const TempDir dir;
    const std::string spin = "kind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0";
    const std::string scene_file = (dir.path / "scene.toml").string();
    // The table scene of `kind` reading `csv` (written next to it under that name) with `rows` as its text.
    const auto table_error = [&](const std::string& rows, const std::string& kind = "table",
                                 const std::string& csv = "m.csv", const std::string& extra = "") {
        if (!rows.empty()) dir.write(csv, rows);
        std::string text = edited(spin, "kind = \"" + kind + "\"\nfile = \"" + csv + "\"" + extra);
        if (kind == "torque-table") text += "[hub]\ninertia = 30.0\n";
        return error_of(dir, text);
    };
    // Every table problem: "SCENE: motion.file: CSV[:LINE]: what".
    const auto names = [&](const std::string& message, const std::string& where, const std::string& what) {
        INFO(message);
        CHECK(message.rfind(scene_file + ": motion.file: " + (dir.path / where).string() + ": ", 0) == 0);
        CHECK(message.find(what) != std::string::npos);
    };
    const std::string good = "t,theta\n0,0\n1,0.5\n2,2\n";

    SECTION("a missing column")
    {
        names(table_error("t,angle\n0,0\n1,0.5\n2,2\n"), "m.csv:1", "expected a column theta in its header");
        names(table_error("time,tau\n0,0\n1,0.5\n", "torque-table"), "m.csv:1", "expected a column t in its header");
    }
    SECTION("a value that is not a number, or not finite")
    {
        // Where, never what the file holds (docs/security.md): the field is named by its column and position.
        const std::string theta = "expected a finite number in column theta (the hub angle, rad), field 2 of the line";
        names(table_error("t,theta\n0,0\n1,abc\n2,2\n"), "m.csv:3", theta);
        names(table_error("t,theta\n0,0\n1,0.5x\n2,2\n"), "m.csv:3", theta);
        names(table_error("t,theta\n0,0\nnan,0.5\n2,2\n"), "m.csv:3",
              "expected a finite number in column t (time, s), field 1 of the line");
        names(table_error("theta,t\n0,0\n1,inf\n2,2\n"), "m.csv:3", "column t (time, s), field 2 of the line");
        names(table_error("t,theta\n0,0\n1,1e999\n2,2\n"), "m.csv:3", theta);
        names(table_error("t,theta\n0,0\n1,\n2,2\n"), "m.csv:3", theta);
    }
    SECTION("a row with too few or too many fields")
    {
        names(table_error("t,theta\n0,0\n1\n2,2\n"), "m.csv:3", "expected 2 fields as the header has, got 1");
        names(table_error("t,theta\n0,0\n1,2,3\n2,2\n"), "m.csv:3", "expected 2 fields as the header has, got 3");
    }
    SECTION("too few rows: 3 for the spline, 2 for linear")
    {
        names(table_error("t,theta\n0,0\n40,1\n"), "m.csv", "expected at least 3 rows (a cubic spline), got 2");
        names(table_error("t,tau\n0,1\n", "torque-table"), "m.csv", "expected at least 2 rows, got 1");
        names(table_error("t,tau\n", "torque-table"), "m.csv", "expected at least 2 rows, got 0");
        names(table_error("\n\n", "torque-table"), "m.csv", "expected a header line with columns t, tau, got an empty file");
    }
    SECTION("times that do not increase strictly")
    {
        names(table_error("t,theta\n0,0\n1,0.5\n1,0.7\n2,2\n"), "m.csv:4",
              "expected times that increase strictly, got t = 1 after t = 1 (line 3)");
        names(table_error("t,theta\n0,0\n\n2,0.5\n1,0.7\n"), "m.csv:5", "got t = 1 after t = 2 (line 4)");
    }
    SECTION("a table that does not cover the run: no extrapolation")
    {
        names(table_error(good), "m.csv", "its rows cover t = 0 to 2 s, the run needs t = 0 to output.t_end = 30 s");
        names(table_error("t,theta\n0.5,0\n1,0.5\n40,2\n"), "m.csv", "its rows cover t = 0.5 to 40 s");
        // t_end from an override is checked too; within the rows the scene loads.
        dir.write("m.csv", good);
        CHECK_NOTHROW(load_scene(dir.write("ok.toml", edited(spin, "kind = \"table\"\nfile = \"m.csv\"")),
                                 {{"output.t_end", "2"}}));
        try {
            load_scene(dir.write("ok.toml", edited(spin, "kind = \"table\"\nfile = \"m.csv\"")), {{"output.t_end", "2.5"}});
            FAIL("a run past the table was accepted");
        } catch (const SceneError& e) {
            CHECK(e.key == "motion.file");
            CHECK(std::string(e.what()).find("output.t_end = 2.5 s") != std::string::npos);
        }
    }
    SECTION("a file that cannot be read: missing, a folder, too large")
    {
        names(table_error("", "table", "absent.csv"), "absent.csv", "cannot open: No such file or directory");
        std::filesystem::create_directories(dir.path / "folder.csv");
        names(table_error("", "table", "folder.csv"), "folder.csv", "not a regular file");
        {
            std::ofstream(dir.path / "big.csv") << "t,theta\n";
            std::filesystem::resize_file(dir.path / "big.csv", max_table_bytes + 1);
        }
        names(table_error("", "table", "big.csv"), "big.csv", "is larger than a motion table can be (16 MB)");
    }
    SECTION("the [motion] keys of the new kinds")
    {
        const auto keyed = [&](const std::string& text, const std::string& key, const std::string& what) {
            const std::string message = error_of(dir, text);
            INFO(message);
            CHECK(message.find(": " + key + ": ") != std::string::npos);
            CHECK(message.find(what) != std::string::npos);
        };
        dir.write("m.csv", "t,theta\n0,0\n1,0.5\n40,2\n");
        keyed(edited(spin, "kind = \"held\""), "motion.angle", "missing");
        keyed(edited(spin, "kind = \"held\"\nangle = \"up\""), "motion.angle", "a finite number (the hub angle, rad)");
        keyed(edited(spin, "kind = \"held\"\nangle = 0\ntheta0 = 1"), "motion.theta0", "unknown key");
        keyed(edited(spin, "kind = \"held\"\nangle = 0\nduration = 1"), "motion.duration", "unknown key");
        keyed(edited(spin, "kind = \"table\""), "motion.file", "missing");
        keyed(edited(spin, "kind = \"table\"\nfile = \"\""), "motion.file", "got an empty one");
        keyed(edited(spin, "kind = \"table\"\nfile = 3"), "motion.file", "got an integer 3");
        keyed(edited(spin, "kind = \"table\"\nfile = \"m.csv\"\nduration = 15.0"), "motion.duration", "unknown key");
        dir.write("r.csv", "t,tau\n0,0\n40,2\n");
        keyed(edited(spin, "kind = \"torque-table\"\nfile = \"r.csv\""), "hub.inertia",
              "required for kind = \"torque-table\"");
        keyed(edited(spin, "kind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0\nfile = \"m.csv\""), "motion.file",
              "unknown key");
        keyed(edited(spin, spin + "\ntheta0 = nan"), "motion.theta0", "got nan");
        keyed(edited(spin, "kind = \"spun\""),
              "motion.kind", "one of \"spin-up\", \"torque\", \"held\", \"table\", \"torque-table\"");
    }
}

TEST_CASE("a run's summary says how the hub moves: held, from which table, from which angle", "[scene]")
{
    const auto first_line = [](const Scene& s) {
        const std::string text = format_summary(RunSummary{}, s);
        return text.substr(0, text.find('\n'));
    };
    CHECK(first_line(load_scene(case_path("held_gravity.toml"), {{"motion.angle", "0.25"}})) ==
          "scene       " + case_path("held_gravity.toml") + " (hub held at theta = 0.25 rad)");
    CHECK(first_line(load_scene(case_path("table_spinup.toml"), {{"motion.theta0", "-0.5"}})) ==
          "scene       " + case_path("table_spinup.toml") + " (hub angle from " + case_path("table_spinup.csv") +
              ", 121 rows to t = 30 s, natural cubic spline, theta0 = -0.5 rad)");
    // The paper's scenes say what they always said.
    CHECK(first_line(load_scene(case_path("torque_tau1.toml"))) ==
          "scene       " + case_path("torque_tau1.toml") + " (hub torque tau0 = 1 N m for T_t = 10 s)");
}

TEST_CASE("[blade_scale] multiplies the blade file's columns, each its own, as BModes' property multipliers do",
          "[scene][blade_files]")
{
    // A BModes section file whose columns all differ from 0 and from each other; each factor of 1.5 alone must scale
    // its column of the scene's profile (docs/model.md 12.4's values: m, EI edge, ES, EI_flap, GJ, j_c, j_n) or
    // offsets, and nothing else.
    const TempFolder folder("blade-scale");
    folder.write("blade.dat",
                 "blade\n2 n_secs\n\nsec_loc str_tw tw_iner mass_den flp_iner edge_iner flp_stff edge_stff tor_stff "
                 "axial_stff cg_offst sc_offst tc_offst\n(-) (deg) (deg) (kg/m) (kg-m) (kg-m) (Nm^2) (Nm^2) (Nm^2) (N) "
                 "(m) (m) (m)\n0 5 5 10 2 3 400 900 100 1e6 0.1 0.05 0.02\n1 4 4 8 1.5 2.5 300 700 80 8e5 0.08 0.04 "
                 "0.01\n");
    const auto scene = [&](const std::string& scale) {
        const std::string text = "[beam]\nlength = 10\nblade_file = \"blade.dat\"\n" + scale +
                                 "[motion]\nkind = \"spin-up\"\nomega0 = 1\nduration = 1\n[discretization]\n"
                                 "method = \"fem\"\nny = 4\nnx = 4\nnz = 4\nnt = 2\n[output]\nt_end = 1\n";
        return parse_scene(text, (folder.path / "s.toml").string());
    };
    const Scene plain = scene("");
    using V = ProfileValue;
    const std::vector<std::pair<std::string, int>> columns = {
        {"mass", static_cast<int>(V::m)},
        {"inertia_flap", static_cast<int>(V::j_c)},
        {"inertia_edge", static_cast<int>(V::j_n)},
        {"stiffness_flap", static_cast<int>(V::EI_flap)},
        {"stiffness_edge", static_cast<int>(V::EI)},
        {"stiffness_torsion", static_cast<int>(V::GJ)},
        {"stiffness_axial", static_cast<int>(V::ES)},
        {"cg_offset", -1 - static_cast<int>(SectionOffset::mass)},
        {"tc_offset", -1 - static_cast<int>(SectionOffset::tension)}};
    const std::size_t w = max_profile_value_count;
    for (const auto& [key, column] : columns) {
        INFO(key);
        const Scene scaled = scene("[blade_scale]\n" + key + " = 1.5\n");
        REQUIRE(scaled.parameters.profile.size() == plain.parameters.profile.size());
        for (std::size_t i = 0; i < plain.parameters.profile.size(); ++i) {
            const double ratio = static_cast<int>(i % w) == column ? 1.5 : 1.0;
            CHECK(scaled.parameters.profile[i] == plain.parameters.profile[i] * ratio);
        }
        REQUIRE(scaled.parameters.offsets.size() == plain.parameters.offsets.size());
        for (std::size_t i = 0; i < plain.parameters.offsets.size(); ++i) {
            const int which = static_cast<int>(i % section_offset_count);
            CHECK(scaled.parameters.offsets[i] == plain.parameters.offsets[i] * (-1 - which == column ? 1.5 : 1.0));
        }
        // The effective scene names every factor, 1 where the file leaves one out.
        const std::string printed = effective_scene_toml(scaled);
        CHECK(printed.find("\n" + key + " = 1.5\n") != std::string::npos);
        CHECK(printed.find("[blade_scale]\nmass = " + std::string(key == "mass" ? "1.5" : "1") + "\n") !=
              std::string::npos);
    }
    // Out of range, or with no blade file to scale, a factor is refused naming its key.
    const auto refused = [&](const std::string& text, const std::string& key) {
        try {
            (void)parse_scene(text, (folder.path / "s.toml").string());
            FAIL(key << " was accepted");
        } catch (const SceneError& e) {
            CHECK(e.key == key);
        }
    };
    const std::string uniform = "[beam]\nlength = 8\ndensity = 1\narea = 1\nsecond_moment = 1\nyoungs_modulus = 1\n"
                                "[motion]\nkind = \"spin-up\"\nomega0 = 1\nduration = 1\n[discretization]\n"
                                "method = \"amm\"\nny = 4\nnx = 0\n[output]\nt_end = 1\n";
    refused(uniform + "[blade_scale]\nmass = 2\n", "blade_scale.mass");
    const Scene unscaled = parse_scene(uniform + "[blade_scale]\nmass = 1\n", (folder.path / "s.toml").string());
    CHECK(effective_scene_toml(unscaled).find("blade_scale") == std::string::npos);  // no blade file to scale
    for (const char* bad : {"mass = 0", "stiffness_flap = -1", "inertia_edge = -0.5", "cg_offset = inf"}) {
        const std::string line = bad;
        refused("[blade_scale]\n" + line + "\n[beam]\nlength = 10\nblade_file = \"blade.dat\"\n[motion]\n"
                "kind = \"spin-up\"\nomega0 = 1\nduration = 1\n[discretization]\nmethod = \"fem\"\nny = 4\n"
                "nx = 4\nnz = 4\nnt = 2\n[output]\nt_end = 1\n",
                "blade_scale." + line.substr(0, line.find(' ')));
    }
    CHECK_NOTHROW(scene("[blade_scale]\ninertia_edge = 0\ncg_offset = -2\n"));
}
