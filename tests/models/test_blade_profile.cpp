// A blade whose section is a table (docs/model.md section 12.4): the profile's columns EI_flap, GJ, twist, j_c and j_n
// beside m, EI and ES. Against the uniform blade (a constant table, its chord angle added to the pitch), against the
// linear pre-twist (a table of it converges at second order in the stations' spacing), against the unit-load
// integral of a tabulated blade's flap sag, and the scene's reading and refusals of the columns.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <random>
#include <string>
#include <vector>

#include "csv_file.hpp"
#include "gauss_legendre.hpp"
#include "model_values.hpp"
#include "random_state.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

using test::forces_of;
using test::mass_of;

/// A uniform blade with every out-of-plane value unlike the others (test::with_every_term's).
Parameters blade()
{
    Parameters p = test::with_every_term();
    p.alpha = p.beta = 0.0;
    return p;
}

/// p's uniform section as a table at stations x (chord angle `twist_at(x)` beside the pitch).
template <class Twist>
Parameters tabulated(Parameters p, const std::vector<double>& x, Twist twist_at)
{
    p.stations = x;
    p.profile.clear();
    for (double xk : x)
        p.profile.insert(p.profile.end(), {p.rho * p.S, p.E * p.I, p.E * p.S, p.E * p.I_flap, p.G * p.J_t, twist_at(xk),
                                           p.rho * p.I_flap, p.rho * p.I, twist_at(xk)});
    return p;
}

/// key with a profile (its stations are the parameters', set by tabulated).
VariantKey with_table(VariantKey key)
{
    key.extras.tabulated = true;
    return key;
}

/// The largest relative difference of M and Q of two models at a few random states.
double difference(const Model& a, const Model& b, const VariantKey& key, std::mt19937& rng)
{
    double worst = 0.0;
    for (int trial = 0; trial < 3; ++trial) {
        const test::State s = test::random_state_with_angle(key, rng);
        worst = std::max({worst, test::relative_error(mass_of(a, s).reshaped(), mass_of(b, s).reshaped()),
                          test::relative_error(forces_of(a, s), forces_of(b, s))});
    }
    return worst;
}

}  // namespace

TEST_CASE("blade profile: a constant table is the uniform blade, its chord angle added to the pitch",
          "[profile][out_of_plane]")
{
    // Generated from the table against the hand-assembled uniform blade pitched by pitch + the table's angle: every
    // column maps to its uniform value (EI_flap = E I_flap, GJ = G J_t, j_c = rho I_flap, j_n = rho I).
    const Parameters p = blade();
    Parameters uniform = p;
    uniform.pitch = p.pitch + 0.35;
    std::mt19937 rng(2009);
    for (Method method : {Method::fem, Method::bsim}) {
        const Extras extras{.gravity = true, .pitch = true, .cone = true};
        const VariantKey plain{
            .method = method, .nx = 3, .ny = 4, .nz = 4, .nt = 3, .drive = Drive::torque, .extras = extras};
        const VariantKey table = with_table(plain);
        INFO(table.name());
        const auto gen =
            make_model(table, tabulated(p, {0.0, 1.0}, [](double) { return 0.35; }), ModelSource::generated);
        const auto asm_ = make_model(plain, uniform, ModelSource::assembled);
        CHECK(difference(*gen, *asm_, plain, rng) < 1e-11);
    }
}

TEST_CASE("blade profile: a table of the linear pre-twist converges to it at second order in the spacing",
          "[profile][out_of_plane]")
{
    // Between stations each component of the turned section is linear (section 12.4), the uniform blade's turns with
    // x: their difference is (2 twist h)^2 / 8 of the deviator at most, a quarter for half the spacing.
    Parameters p = blade();
    p.twist = -0.5;
    p.I_flap = 0.2 * p.I;  // a large deviator (EI - EI_flap)/2
    const VariantKey plain{.method = Method::fem,
                           .nx = 0,
                           .ny = 4,
                           .nz = 4,
                           .nt = 2,
                           .drive = Drive::prescribed,
                           .extras = {.pitch = true, .twist = true}};
    const auto exact = make_model(plain, p, ModelSource::assembled);
    std::vector<double> errors;
    for (int n : {4, 8, 16}) {
        std::vector<double> x;
        for (int k = 0; k <= n; ++k) x.push_back(static_cast<double>(k) / n);
        VariantKey key = with_table(plain);
        key.extras.twist = false;
        const Parameters t = tabulated(p, x, [&](double xk) { return p.twist * xk; });
        std::mt19937 rng(1994);  // the same states for every spacing
        errors.push_back(difference(*make_model(key, t, ModelSource::assembled), *exact, plain, rng));
    }
    INFO(errors[0] << ", " << errors[1] << ", " << errors[2]);
    CHECK(errors[0] < 1e-2);
    for (std::size_t i = 1; i < errors.size(); ++i) CHECK(errors[i - 1] / errors[i] == Approx(4.0).epsilon(0.15));
}

TEST_CASE("blade profile: a held blade's flap sag under gravity along the axis is the unit-load integral of its table",
          "[profile][out_of_plane]")
{
    // m(x) and EI_flap(x) linear between three stations; u_z(L) = -int_0^L M(x) (L - x) / EI_flap(x) dx with the
    // weight's moment M(x) = g_axis int_x^L m(s) (s - x) ds, by Gauss-Legendre on each interval (1/EI_flap is smooth
    // there).
    Parameters p = blade();
    p.L = 2.0, p.a = 0.0, p.g = 0.0, p.g_axis = 0.01, p.pitch = 0.0;
    const std::vector<double> x = {0.0, 0.4, 1.0};
    const std::vector<double> m = {3.0, 2.0, 0.5}, EI_flap = {900.0, 400.0, 150.0};
    p.stations = x;
    p.profile.clear();
    for (std::size_t k = 0; k < x.size(); ++k)
        p.profile.insert(p.profile.end(), {m[k], 4.0 * EI_flap[k], 1e6, EI_flap[k], 0.0, 0.0, 0.0, 0.0, 0.0});
    const auto linear = [&](const std::vector<double>& v, double s) {
        const double xi = s / p.L;
        const std::size_t k = xi > x[1] ? 1 : 0;
        const double t = (xi - x[k]) / (x[k + 1] - x[k]);
        return (1.0 - t) * v[k] + t * v[k + 1];
    };
    const test::GaussRule g = test::gauss_legendre(12);  // on [-1, 1]
    const auto integral = [&](double lo, double hi, auto f) {
        double sum = 0.0;
        std::vector<double> cuts = {lo};
        for (double c : x)
            if (c * p.L > lo && c * p.L < hi) cuts.push_back(c * p.L);
        cuts.push_back(hi);
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            for (std::size_t j = 0; j < g.x.size(); ++j) {
                const double half = 0.5 * (cuts[k + 1] - cuts[k]);
                sum += half * g.w[j] * f(cuts[k] + half * (1.0 + g.x[j]));
            }
        return sum;
    };
    const auto moment = [&](double at) {
        return p.g_axis * integral(at, p.L, [&](double s) { return linear(m, s) * (s - at); });
    };
    const double sag = -integral(0.0, p.L, [&](double s) { return moment(s) * (p.L - s) / linear(EI_flap, s); });
    // FEM's nodal values are not exact where EI_flap varies: they converge, and BIM's (3.3e-5 at Nz = 12) with them.
    std::vector<double> errors;
    for (const auto& [method, n] :
         {std::pair{Method::fem, 4}, {Method::fem, 8}, {Method::fem, 16}, {Method::bim, 12}}) {
        VariantKey key{
            .method = method, .nx = 0, .ny = 2, .nz = n, .drive = Drive::prescribed, .extras = {.gravity = true}};
        key = with_table(key);
        const auto model = make_model(key, p, ModelSource::generated);
        const double uz = model->tip(held_equilibrium(*model, 0.0).q.data()).uz;
        INFO(to_string(method) << " " << n << ": " << uz << " against " << sag);
        errors.push_back(std::abs(uz / sag - 1.0));
        CHECK(errors.back() < 1e-3);
    }
    // The fields CSV's flapwise moment EI_flap(x) u_z'' is the weight's moment -M(x) (statics), with EI_flap the
    // table's where it varies (x/L = 0.25, 0.5, 0.75).
    {
        VariantKey key{
            .method = Method::bim, .nx = 0, .ny = 2, .nz = 12, .drive = Drive::prescribed, .extras = {.gravity = true}};
        key = with_table(key);
        const auto model = make_model(key, p, ModelSource::generated);
        const std::vector<double> q = held_equilibrium(*model, 0.0).q;
        const TempFolder folder("blade-fields");
        const std::string path = (folder.path / "fields.csv").string();
        FieldRecorder recorder(key, p, {0.0}, 5, path);
        recorder.state(0.0, q.data());
        REQUIRE(recorder.finish());
        const test::Csv csv = test::read_csv(path);
        const std::size_t at = csv.column("x"), flap = csv.column("flap_moment");
        int checked = 0;
        for (const std::vector<double>& row : csv.rows) {
            const double xi = row[at] / p.L;
            if (std::abs(xi - 0.25) > 1e-6 && std::abs(xi - 0.5) > 1e-6 && std::abs(xi - 0.75) > 1e-6) continue;
            INFO("x/L = " << xi);
            // A moment from the model's curvature converges slower than its deflection: BIM Nz = 12 is within 0.13 %,
            // 1.2 % and 1.8 % at the three places (a uniform EI_flap would be 2.5 times off at x/L = 0.5).
            CHECK(row[flap] == Approx(-moment(row[at])).epsilon(3e-2));
            ++checked;
        }
        CHECK(checked == 3);
    }
    CHECK(errors[1] < errors[0] / 3.0);
    CHECK(errors[2] < errors[1] / 3.0);
    CHECK(errors[2] < 2e-5);
    CHECK(errors[3] < 1e-4);  // one polynomial over the span: slower across the kink of EI_flap at x/L = 0.4
}

TEST_CASE("blade fields: a held, pitched and twisted blade's chord moments are its weight's moment turned to the chord",
          "[profile][out_of_plane]")
{
    // Statics, sharing no code with the recorder: the weight along the spin axis loads the span along z only, so
    // the section's moment is (M_y, M_z) = (0, -M(x)) with M(x) = g_axis m (L - x)^2 / 2 whatever the section's
    // angle beta(x) = pitch + twist x / L; about the chord c = (cos beta, sin beta) and its normal n = (-sin beta,
    // cos beta) it is edge = -sin beta M(x) and flap = -cos beta M(x) (docs/model.md section 12).
    Parameters p = blade();
    p.a = 0.0, p.m_tip = p.J_tip = 0.0, p.g = 0.0, p.precone = 0.0, p.g_axis = 0.01;
    p.pitch = 0.4, p.twist = 0.3;
    const VariantKey key{.method = Method::bim,
                         .nx = 0,
                         .ny = 12,
                         .nz = 12,
                         .drive = Drive::prescribed,
                         .extras = {.gravity = true, .pitch = true, .twist = true}};
    const auto model = make_model(key, p, ModelSource::generated);
    const std::vector<double> q = held_equilibrium(*model, 0.0).q;
    const TempFolder folder("pitched-fields");
    const std::string path = (folder.path / "fields.csv").string();
    FieldRecorder recorder(key, p, {0.0}, 9, path);
    recorder.state(0.0, q.data());
    REQUIRE(recorder.finish());
    const test::Csv csv = test::read_csv(path);
    const std::size_t at = csv.column("x"), edge = csv.column("bending_moment"), flap = csv.column("flap_moment");
    int checked = 0;
    for (const std::vector<double>& row : csv.rows) {
        const double x = row[at], beta = p.pitch + p.twist * x / p.L;
        if (x > 0.8 * p.L) continue;  // near the tip both moments vanish: a relative check means little there
        const double M = p.g_axis * p.rho * p.S * (p.L - x) * (p.L - x) / 2.0;
        INFO("x = " << x << ": edge " << row[edge] << ", flap " << row[flap] << ", M " << M);
        CHECK(row[edge] == Approx(-std::sin(beta) * M).epsilon(1e-3));
        CHECK(row[flap] == Approx(-std::cos(beta) * M).epsilon(1e-3));
        ++checked;
    }
    CHECK(checked >= 6);
}

namespace {

struct Folder : TempFolder {
    Folder() : TempFolder("blade-profile") {}
    std::string scene() const { return (path / "blade.toml").string(); }
};

/// A blade scene (nz = nt = 2 unless discretization says otherwise) whose [beam] has the lines given.
std::string blade_scene(const std::string& beam, const std::string& discretization = "nz = 2\nnt = 2\n")
{
    return "[beam]\nlength = 2.0\n" + beam +
           "\n[motion]\nkind = \"spin-up\"\nomega0 = 4.0\nduration = 1.0\n[discretization]\nmethod = \"fem\"\nny = 2\n"
           "nx = 0\n" +
           discretization + "[output]\nt_end = 1.0\ndt_out = 0.1\n";
}

const std::string blade_table =
    "x/L, m, EI, ES, EI_flap, GJ, twist, j_c, j_n\n0, 3, 900, 1e6, 300, 50, 0.2, 0.01, 0.04\n"
    "1, 1, 100, 1e6, 40, 20, -0.1, 0.002, 0.01\n";

/// The SceneError's message of the scene, checked to name the scene and key.
std::string error_of(const Folder& f, const std::string& table, const std::string& beam = "profile = \"blade.csv\"\n",
                     const std::string& discretization = "nz = 2\nnt = 2\n", const std::string& key = "beam.profile")
{
    f.write("blade.csv", table);
    f.write("blade.toml", blade_scene(beam, discretization));
    try {
        load_scene(f.scene());
    } catch (const SceneError& e) {
        CHECK(e.key == key);
        return e.what();
    }
    FAIL("the scene was accepted");
    return {};
}

}  // namespace

TEST_CASE("blade profile: a scene reads the blade's columns, each absent one at its default", "[profile][scene]")
{
    const Folder f;
    f.write("blade.csv", blade_table);
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\npitch = 0.1\n"));
    const Scene s = load_scene(f.scene());
    CHECK(s.key().name() == "fem_nx0_ny2_nz2_nt2_prescribed_first_profile_pitched");
    // The inertia axes along the chord where no inertia_twist is given.
    CHECK(s.parameters.profile == std::vector<double>{3,   900, 1e6, 300, 50, 0.2,  0.01,  0.04, 0.2,
                                                      1,   100, 1e6, 40,  20, -0.1, 0.002, 0.01, -0.1});
    f.write("blade.csv", "x/L, m, EI, ES, EI_flap, GJ, twist, j_c, j_n, inertia_twist\n0, 3, 900, 1e6, 300, 50, 0.2, "
                         "0.01, 0.04, 0.5\n1, 1, 100, 1e6, 40, 20, -0.1, 0.002, 0.01, -0.7\n");
    const std::vector<double> axes = load_scene(f.scene()).parameters.profile;
    CHECK(axes[static_cast<std::size_t>(ProfileValue::inertia_twist)] == 0.5);
    CHECK(axes[max_profile_value_count + static_cast<std::size_t>(ProfileValue::inertia_twist)] == -0.7);
    // Without a twist field the torsional columns may be left out: EI_flap defaults to EI, the rest to 0.
    f.write("blade.csv", "x/L, m, EI, ES\n0, 3, 900, 1e6\n1, 1, 100, 1e6\n");
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n", "nz = 2\n"));
    CHECK(load_scene(f.scene()).parameters.profile ==
          std::vector<double>{3, 900, 1e6, 900, 0, 0, 0, 0, 0, 1, 100, 1e6, 100, 0, 0, 0, 0, 0});
    // A planar scene keeps the planar values.
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n", ""));
    CHECK(load_scene(f.scene()).parameters.profile == std::vector<double>{3, 900, 1e6, 1, 100, 1e6});
}

TEST_CASE("blade profile: a cg_offset column makes the variant with section offsets, and only where one is not 0",
          "[profile][scene][section_offsets]")
{
    const Folder f;
    f.write("blade.csv", "x/L, m, EI, ES, cg_offset\n0, 3, 900, 1e6, 0.05\n1, 1, 100, 1e6, -0.02\n");
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n", "nz = 2\n"));
    const Scene s = load_scene(f.scene());
    CHECK(s.key().name() == "fem_nx0_ny2_nz2_prescribed_first_profile_offsets");
    CHECK(s.parameters.offsets == std::vector<double>{0.05, 0.0, -0.02, 0.0});  // cg_offset, tc_offset by station
    f.write("blade.csv", "x/L, m, EI, ES, cg_offset\n0, 3, 900, 1e6, 0\n1, 1, 100, 1e6, 0\n");
    CHECK(load_scene(f.scene()).key().name() == "fem_nx0_ny2_nz2_prescribed_first_profile");
    // In the plane a chord has no offset to carry; order full and gravity are not modelled with one.
    const std::string offset = "x/L, m, EI, ES, cg_offset\n0, 3, 900, 1e6, 0.05\n1, 1, 100, 1e6, 0\n";
    CHECK_THAT(error_of(f, offset, "profile = \"blade.csv\"\n", ""),
               Catch::Contains("column cg_offset describes a blade that leaves the plane"));
    f.write("blade.csv", offset);
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n", "nz = 2\n") + "[model]\norder = \"full\"\n");
    CHECK_THROWS_WITH(load_scene(f.scene()), Catch::Contains("order first or zero, not full"));
}

TEST_CASE("blade profile: a tc_offset column makes the variant with section offsets, and needs an axial field",
          "[profile][scene][section_offsets]")
{
    const Folder f;
    f.write("blade.csv", "x/L, m, EI, ES, tc_offset\n0, 3, 900, 1e6, 0.01\n1, 1, 100, 1e6, -0.02\n");
    std::string scene = blade_scene("profile = \"blade.csv\"\n", "nz = 2\n");
    scene.replace(scene.find("nx = 0"), 6, "nx = 2");
    f.write("blade.toml", scene);
    const Scene s = load_scene(f.scene());
    CHECK(s.key().name() == "fem_nx2_ny2_nz2_prescribed_first_profile_offsets");
    CHECK(s.parameters.offsets == std::vector<double>{0.0, 0.01, 0.0, -0.02});
    // With nx = 0 the offset would leave the bending stiffness about the reference axis: refused, naming the column.
    f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n", "nz = 2\n"));
    CHECK_THROWS_WITH(load_scene(f.scene()),
                      Catch::Contains("blade.csv") && Catch::Contains("column tc_offset") &&
                          Catch::Contains("expected discretization.nx > 0"));
    // A column of zeros is no offset: nx = 0 runs the variant without offsets.
    f.write("blade.csv", "x/L, m, EI, ES, tc_offset\n0, 3, 900, 1e6, 0\n1, 1, 100, 1e6, 0\n");
    CHECK(load_scene(f.scene()).key().name() == "fem_nx0_ny2_nz2_prescribed_first_profile");
}

TEST_CASE("blade profile: a table without what the blade needs is refused, naming the column", "[profile][scene]")
{
    const Folder f;
    const std::string csv = (f.path / "blade.csv").string();
    const auto has = [](const std::string& message, const std::string& part) {
        INFO(message);
        CHECK(message.find(part) != std::string::npos);
    };
    has(error_of(f, "x/L, m, EI, ES, EI_flap, j_c, j_n\n0, 1, 1, 1, 1, 1, 1\n1, 1, 1, 1, 1, 1, 1\n"),
        csv + ": expected a column GJ with discretization.nt > 0 (the twist field's stiffness)");
    has(error_of(f, "x/L, m, EI, ES, GJ, j_c\n0, 1, 1, 1, 1, 1\n1, 1, 1, 1, 1, 1\n"),
        csv + ": expected a column j_n with discretization.nt > 0 (the twist field's inertia)");
    has(error_of(f, "x/L, m, EI, ES, GJ, j_c, j_n\n0, 1, 1, 1, 1, 1, 1\n1, 1, 1, 1, 0, 1, 1\n"),
        csv + ": expected GJ > 0 at every station with discretization.nt > 0, got 0 at station 2");
    has(error_of(f, "x/L, m, EI, ES, GJ, j_c, j_n\n0, 1, 1, 1, 1, 0, 0\n1, 1, 1, 1, 1, 1, 1\n"),
        csv + ": expected j_c + j_n > 0 at every station with discretization.nt > 0, got 0 at station 1");
    has(error_of(f, "x/L, m, EI, ES, GJ, j_c, j_n\n0, 1, 1, 1, 1, -1, 2\n1, 1, 1, 1, 1, 1, 1\n"),
        csv + ":2: expected j_c >= 0, got -1");
    has(error_of(f, "x/L, m, EI, ES, EI_flap\n0, 1, 1, 1, 0\n1, 1, 1, 1, 1\n", "profile = \"blade.csv\"\n", "nz = 2\n"),
        csv + ":2: expected EI_flap > 0, got 0");
    has(error_of(f, "x/L, m, EI, ES, twist\n0, 1, 1, 1, nan\n1, 1, 1, 1, 0\n", "profile = \"blade.csv\"\n", "nz = 2\n"),
        csv + ":2: expected a finite number in column twist (the chord's angle added to beam.pitch, rad)");
    // An angle of more than a turn names no other section, and 1e308 only loses the digits of its cosine.
    has(error_of(f, "x/L, m, EI, ES, twist\n0, 1, 1, 1, 0\n1, 1, 1, 1, -1e308\n", "profile = \"blade.csv\"\n",
                 "nz = 2\n"),
        csv + ":3: expected twist from -2 pi to 2 pi (rad: one turn either way)");
    // The uniform section's keys do not go with a table: its columns give them.
    for (const char* key :
         {"second_moment_flap = 1e-8", "shear_modulus = 1e9", "torsion_constant = 1e-8", "twist = 0.1"}) {
        const std::string name = std::string(key).substr(0, std::string(key).find(' '));
        has(error_of(f, blade_table, std::string("profile = \"blade.csv\"\n") + key + "\n", "nz = 2\nnt = 2\n",
                     "beam." + name),
            "not used with beam.profile (its table gives the section along the span)");
    }
    // Nor do sensitivities to what the table replaces.
    for (const char* name : {"I_flap", "G", "J_t", "twist"}) {
        f.write("blade.csv", blade_table);
        f.write("blade.toml", blade_scene("profile = \"blade.csv\"\n") + "sensitivities = \"" + name + "\"\n");
        try {
            load_scene(f.scene());
            FAIL("accepted a sensitivity to " << name);
        } catch (const SceneError& e) {
            has(e.what(), std::string("not ") + name + " with beam.profile");
        }
    }
}

TEST_CASE("blade profile: a BModes or ElastoDyn file is read as the blade's table, resampled when asked",
          "[profile][scene][blade_files]")
{
    const std::string blades = std::string(HUBBEAM_SOURCE_DIR) + "/tests/data/blades/";
    const Folder f;
    const auto scene = [&](const std::string& file, const std::string& more, const std::string& discretization) {
        f.write("blade.toml", blade_scene("blade_file = \"" + blades + file + "\"\n" + more, discretization));
        return f.scene();
    };
    // The file's rows (sec_loc 0.25: str_tw 30 deg, mass_den 300, flp_stff 2e9, edge_stff 6e9, tor_stff 5e8,
    // axial_stff 4e9) in the profile's order m, EI (edgewise), ES, EI_flap, GJ, twist (rad).
    const double deg = 3.14159265358979323846 / 180.0;
    const Scene s = load_scene(scene("bmodes_blade.dat", "", "nz = 2\nnt = 2\n"));
    CHECK(s.key().name() == "fem_nx0_ny2_nz2_nt2_prescribed_first_profile");
    CHECK(s.parameters.stations == std::vector<double>{0.0, 0.25, 0.5, 1.0});
    const std::vector<double>& v = s.parameters.profile;
    const std::size_t n = max_profile_value_count;
    REQUIRE(v.size() == 4 * n);
    for (std::size_t j = 0; j < 6; ++j)
        CHECK(v[n + j] == Approx(std::vector<double>{300, 6e9, 4e9, 2e9, 5e8, 30 * deg}[j]));
    // The mass moments about the principal inertia axes, and those axes' angle (tw_iner 0 deg there).
    CHECK(v[n + 6] == 2.0);
    CHECK(v[n + 7] == 10.0);
    CHECK(v[n + 8] == 0.0);
    CHECK(v[8] == Approx(90 * deg));
    // Resampled at 5 stations: 0.75 lies halfway between the file's 0.5 and 1.
    const Scene r = load_scene(scene("bmodes_blade.dat", "blade_stations = 5\n", "nz = 2\nnt = 2\n"));
    CHECK(r.key().name() == "fem_nx0_ny2_nz2_nt2_prescribed_first_profile");
    CHECK(r.parameters.stations == std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0});
    const std::vector<double>& w = r.parameters.profile;
    for (std::size_t j = 0; j < n; ++j) {
        CHECK(w[n + j] == Approx(v[n + j]).margin(1e-15));                             // the file's own station 0.25
        CHECK(w[3 * n + j] == Approx(0.5 * (v[2 * n + j] + v[3 * n + j])).margin(1e-15));  // 0.75
    }
    const auto refused = [&](const std::string& path, const std::string& key, const std::string& part) {
        try {
            load_scene(path);
            FAIL("accepted " << path);
        } catch (const SceneError& e) {
            INFO(e.what());
            CHECK(e.key == key);
            CHECK(std::string(e.what()).find(part) != std::string::npos);
        }
    };
    // OpenFAST's ElastoDyn has no EA, GJ or mass moments: a blade of flap and lead-lag only.
    CHECK(load_scene(scene("elastodyn_openfast5.dat", "", "nz = 2\n")).parameters.profile.size() == 3 * n);
    refused(scene("elastodyn_openfast5.dat", "", "nz = 2\nnt = 2\n"), "beam.blade_file", "expected a column GJ");
    std::string axial = blade_scene("blade_file = \"" + blades + "elastodyn_openfast5.dat\"\n", "nz = 2\n");
    axial.replace(axial.find("nx = 0"), 6, "nx = 2");
    f.write("axial.toml", axial);
    refused((f.path / "axial.toml").string(), "beam.blade_file", "an axial stiffness (EA) for discretization.nx > 0");
    refused(scene("bmodes_blade.dat", "", ""), "beam.blade_file", "describes a blade that leaves the plane");
    // A centre of mass off the axis is run-time data of the variant with offsets (docs/model.md section 12.5).
    const Scene offset = load_scene(scene("bmodes_cg_offset.dat", "", "nz = 2\n"));
    CHECK(offset.variant.extras.offsets);
    CHECK(offset.parameters.offsets == std::vector<double>{0.0, 0.0, 0.0, 0.0, 0.032, 0.0, 0.0, 0.0});
    CHECK_FALSE(load_scene(scene("bmodes_blade.dat", "", "nz = 2\n")).variant.extras.offsets);
    // The root loads' force summation puts each section's mass on the axis: refused beside an offset one.
    try {
        load_scene(scene("bmodes_cg_offset.dat", "", "nz = 2\n"), {{"output.loads", "root"}});
        FAIL("root loads beside a centre-of-mass offset were accepted");
    } catch (const SceneError& e) {
        CHECK(e.key == "output.loads");
    }
    refused(scene("bmodes_blade.dat", "blade_stations = 1\n", "nz = 2\n"), "beam.blade_stations",
            "expected 0 (the file's own stations) or an integer from 2 to 10000");
    refused(scene("bmodes_blade.dat", "profile = \"blade.csv\"\n", "nz = 2\n"), "beam.blade_file",
            "not used with beam.profile");
    refused(scene("bmodes_blade.dat", "density = 1000\n", "nz = 2\n"), "beam.density", "not used with beam.blade_file");
    f.write("alone.toml",
            blade_scene("density = 1\narea = 1\nsecond_moment = 1\nyoungs_modulus = 1\nblade_stations = 4\n"));
    refused((f.path / "alone.toml").string(), "beam.blade_stations", "not used without beam.blade_file");
}
