// Scene files: the paper's four load cases in cases/ parse to the values docs/model.md section 6 states, and bad
// input stops in load_scene() with one line naming the file, the key and what was expected.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "scene.hpp"

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

/// A scratch directory, removed with everything in it at the end of the test.
struct TempDir {
    std::filesystem::path path;
    TempDir()
    {
        path = std::filesystem::temp_directory_path() / ("hubbeam-test-scene-" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
    }
    ~TempDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string file = (path / name).string();
        std::ofstream(file) << text;
        return file;
    }
};

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
    const std::vector<std::string> kinds = {"spin-up", "torque"};
    const std::map<std::string, std::string> files = {{"spin-up", case_path("spinup_omega4.toml")},
                                                      {"torque", case_path("torque_tau10.toml")}};
    for (const SceneKey& key : scene_keys()) {
        if (key.motion_kind != nullptr)
            CHECK(std::find(kinds.begin(), kinds.end(), key.motion_kind) != kinds.end());
        const std::string value = key.kind == SceneKey::Kind::integer  ? "4"
                                  : key.kind == SceneKey::Kind::number ? "0.5"
                                                                       : "x";
        for (const std::string& kind : kinds) {
            INFO(key.name << " = " << value << " in a " << kind << " scene");
            const bool belongs = key.motion_kind == nullptr || key.motion_kind == kind;
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
        CHECK(e.expected == "one of length, density, area, second_moment, youngs_modulus, taper, tip_ratio, profile");
        CHECK(e.got == "an unknown key");
    }
    // The parameters of the paper's two motions: Omega0 and T_s (eq. 58), tau0 and T_t (eq. 59).
    CHECK(table_keys("motion", "spin-up") == std::vector<std::string>{"kind", "omega0", "duration"});
    CHECK(table_keys("motion", "torque") == std::vector<std::string>{"kind", "tau0", "duration"});
    CHECK(scene_tables() == std::vector<std::string>{"beam", "hub", "tip", "damping", "gravity", "motion",
                                                     "discretization", "model", "solver", "output"});
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
