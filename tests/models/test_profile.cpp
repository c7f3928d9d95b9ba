// A beam whose section is given by a table (docs/model.md section 11.2): stations x/L with mass per length, EI
// and ES, linear between them. Generated kernels (hat functions integrated exactly, AMM's panels split at the
// stations) against the hand-assembled path (the profile interpolated at quadrature nodes), against the uniform
// beam (a constant table) and the width taper (a linear table), and the static deflection under gravity against
// the unit-load integral of the beam's own EI(x) and weight.
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <random>
#include <string>
#include <vector>

#include "gauss_legendre.hpp"
#include "models/generated_model.hpp"
#include "random_state.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

/// Irregular stations, none at a piece boundary of FEM's or BSIM's Ny = 4 bases.
const std::vector<double> stations = {0.0, 0.3, 0.55, 1.0};

/// A profile variant with a tip body, gravity and damping (generator/variants.txt has it built in at Ny = Nx = 4).
VariantKey profile_key(Method method, Drive drive, int ny = 4, int nx = 4, Order order = Order::first)
{
    return {.method = method,
            .nx = nx,
            .ny = ny,
            .order = order,
            .drive = drive,
            .extras = {.tip = true, .gravity = true, .damping = true, .tabulated = true}};
}

/// The paper's beam on a hub of radius 0.35 m, each extra term switched on at a size where it shows.
Parameters with_terms()
{
    Parameters p;
    p.a = 0.35;
    p.m_tip = 0.55;
    p.J_tip = 0.35;
    p.g = 9.81;
    p.alpha = 0.15;
    p.beta = 2.5e-3;
    return p;
}

/// p's profile set to stations x and m, EI, ES of each from functions of x/L.
template <class M, class EI, class ES>
void tabulate(Parameters& p, const std::vector<double>& x, M m, EI ei, ES es)
{
    p.stations = x;
    p.profile.clear();
    for (double xk : x) p.profile.insert(p.profile.end(), {m(xk), ei(xk), es(xk)});
}

/// A profile unlike the paper's uniform beam: heavier and stiffer at the root, a bump at 0.55.
void irregular(Parameters& p)
{
    p.stations = stations;
    p.profile = {0.35, 900.0, 7e6,     // x/L = 0
                 0.20, 480.0, 4.2e6,   // 0.3
                 0.26, 610.0, 5.1e6,   // 0.55
                 0.09, 150.0, 2.4e6};  // 1
}

/// M, Q, the energies, the momentum and dQ/dtheta of a model at a state, stacked.
VectorXd everything(const Model& model, const test::State& s)
{
    const int n = model.nq();
    RowMajorMatrix M(n, n);
    model.mass(s.u, s.q.data(), M.data());
    VectorXd Q(n), dQ(n);
    model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
    model.forces_theta(s.u, s.q.data(), s.qd.data(), dQ.data());
    const Energy e = model.energy(s.u, s.q.data(), s.qd.data());
    VectorXd v(n * n + 2 * n + 5);
    v << M.reshaped<Eigen::RowMajor>(), Q, dQ, e.T2, e.T1, e.T0, e.U, model.momentum(s.u, s.q.data(), s.qd.data());
    return v;
}

/// Compares two models at random states, each part of everything() against its own size.
void compare(const Model& a, const Model& b, double tolerance, std::mt19937& rng)
{
    REQUIRE(a.nq() == b.nq());
    for (int trial = 0; trial < 4; ++trial) {
        const test::State s = test::random_state_with_angle(a.key(), rng);
        const VectorXd va = everything(a, s), vb = everything(b, s);
        const int n = a.nq();
        INFO("trial " << trial);
        CHECK(test::relative_error(va.head(n * n), vb.head(n * n)) < tolerance);
        CHECK(test::relative_error(va.segment(n * n, n), vb.segment(n * n, n)) < tolerance);
        CHECK((va.segment(n * n + n, n) - vb.segment(n * n + n, n)).lpNorm<Eigen::Infinity>() <=
              tolerance * std::max(vb.segment(n * n, n).lpNorm<Eigen::Infinity>(), 1e-300));
        CHECK(test::relative_error(va.tail(5), vb.tail(5)) < tolerance);
    }
}

const Method methods[] = {Method::amm, Method::fem, Method::bim, Method::bsim};

}  // namespace

TEST_CASE("profile: generated and assembled agree at random states", "[profile][generated][assembled]")
{
    std::mt19937 rng(2213);
    for (Method method : methods)
        for (Drive drive : {Drive::prescribed, Drive::torque}) {
            const VariantKey key = profile_key(method, drive);
            SECTION(key.name())
            {
                Parameters p = with_terms();
                irregular(p);
                const auto gen = make_model(key, p, ModelSource::generated);
                const auto asm_ = make_model(key, p, ModelSource::assembled);
                REQUIRE(std::string(gen->source()) == "generated");
                REQUIRE(std::string(asm_->source()) == "assembled");
                compare(*gen, *asm_, 1e-12, rng);
                // The profile's values are read: the same variant with every value doubled at the middle stations
                // differs by far more than the tolerance.
                Parameters q = p;
                for (std::size_t j = 3; j < 9; ++j) q.profile[j] *= 2.0;
                const auto other = make_model(key, q, ModelSource::generated);
                const test::State s = test::random_state_with_angle(key, rng);
                CHECK(test::relative_error(everything(*other, s), everything(*gen, s)) > 1e-3);
            }
        }
}

TEST_CASE("profile: a constant table is the uniform beam", "[profile][generated][assembled]")
{
    std::mt19937 rng(2214);
    for (Method method : methods)
        for (Drive drive : {Drive::prescribed, Drive::torque}) {
            const VariantKey key = profile_key(method, drive);
            SECTION(key.name())
            {
                Parameters p;  // the paper's beam; the extra terms off, as the uniform variant has none
                p.a = 0.35;
                tabulate(
                    p, stations, [&](double) { return p.rho * p.S; }, [&](double) { return p.E * p.I; },
                    [&](double) { return p.E * p.S; });
                const VariantKey uniform{
                    .method = method, .nx = 4, .ny = 4, .order = Order::first, .drive = drive, .extras = {}};
                Parameters plain = p;
                plain.profile.clear();
                plain.stations.clear();
                const auto reference = make_model(uniform, plain, ModelSource::generated);
                REQUIRE(std::string(reference->source()) == "generated");
                compare(*make_model(key, p, ModelSource::generated), *reference, 1e-12, rng);
                compare(*make_model(key, p, ModelSource::assembled), *reference, 1e-12, rng);
            }
        }
}

TEST_CASE("profile: a linear table is the width taper", "[profile][generated][assembled]")
{
    std::mt19937 rng(2215);
    const double r = 0.45;  // the tip's width over the root's
    for (Method method : methods)
        for (Drive drive : {Drive::prescribed, Drive::torque}) {
            Parameters p = with_terms();
            const auto ratio = [&](double x) { return 1.0 + (r - 1.0) * x; };
            VariantKey width{.method = method,
                             .nx = 4,
                             .ny = 4,
                             .order = Order::first,
                             .drive = drive,
                             .extras = {.tip = true, .gravity = true, .damping = true, .taper = Taper::width}};
            Parameters tapered = p;
            tapered.tip_ratio = r;
            const auto reference = make_model(width, tapered, ModelSource::assembled);
            // Two stations (the table a linear profile needs) and four: one built-in variant takes both tables.
            const VariantKey key = profile_key(method, drive);
            for (const std::vector<double>& x : {std::vector<double>{0.0, 1.0}, stations}) {
                SECTION(key.name() + " at " + std::to_string(x.size()) + " stations")
                {
                    tabulate(
                        p, x, [&](double xi) { return p.rho * p.S * ratio(xi); },
                        [&](double xi) { return p.E * p.I * ratio(xi); },
                        [&](double xi) { return p.E * p.S * ratio(xi); });
                    compare(*make_model(key, p, ModelSource::assembled), *reference, 1e-12, rng);
                    compare(*make_model(key, p, ModelSource::generated), *reference, 1e-12, rng);
                    // Where the build has the generated width taper of this method and drive, against it too.
                    for (const std::string& name : generated_variant_names())
                        if (name == width.name())
                            compare(*make_model(key, p, ModelSource::generated),
                                    *make_model(width, tapered, ModelSource::generated), 1e-12, rng);
                }
            }
        }
}

namespace {

/// m (j = ProfileValue::m) or EI of p's table at stations x, at xi.
double table_value(const Parameters& p, const std::vector<double>& x, ProfileValue j, double xi)
{
    std::size_t k = 0;
    while (k + 2 < x.size() && xi > x[k + 1]) ++k;
    const double t = (xi - x[k]) / (x[k + 1] - x[k]);
    const std::size_t v = static_cast<std::size_t>(j);
    return (1.0 - t) * p.profile[3 * k + v] + t * p.profile[3 * (k + 1) + v];
}

/// int_from^L f(x) dx by Gauss-Legendre on every station interval (x/L stations x).
template <class F>
double on_pieces(const Parameters& p, const std::vector<double>& x, double from, const F& f)
{
    const test::GaussRule rule = test::gauss_legendre(20);  // on [-1, 1]
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < x.size(); ++k) {
        const double lo = std::max(from, x[k] * p.L), hi = x[k + 1] * p.L;
        if (hi <= lo) continue;
        for (std::size_t g = 0; g < rule.x.size(); ++g)
            sum += 0.5 * (hi - lo) * rule.w[g] * f(0.5 * (lo + hi) + 0.5 * (hi - lo) * rule.x[g]);
    }
    return sum;
}

/// The moment about x of the weight outboard of it: int_x^L g m(s) (s - x) ds (exact: a cubic on each interval).
double static_moment(const Parameters& p, const std::vector<double>& x, double at)
{
    return on_pieces(p, x, at, [&](double s) { return p.g * table_value(p, x, ProfileValue::m, s / p.L) * (s - at); });
}

/// The tip deflection of a horizontal cantilever under its own weight, by the unit-load theorem: u_y(L) =
/// -int_0^L M(x) (L - x) / EI(x) dx with M(x) the static moment above, m and EI linear between the stations x (x/L)
/// with p.profile's values (1/EI is smooth on each interval).
double unit_load_deflection(const Parameters& p, const std::vector<double>& x)
{
    return -on_pieces(p, x, 0.0, [&](double at) {
        return static_moment(p, x, at) * (p.L - at) / table_value(p, x, ProfileValue::EI, at / p.L);
    });
}

}  // namespace

TEST_CASE("profile: static deflection under gravity is the unit-load integral", "[profile][assembled][generated]")
{
    // A horizontal beam held at the hub under its own weight, order zero (linear), against the unit-load integral.
    Parameters p;
    p.g = 9.81;
    irregular(p);
    // FEM with the stations at element nodes of 16 and 32 elements (a kink of EI inside an element slows the
    // convergence there): the tip deflection is the compliance of the load's own shape, whose error falls at least as
    // h^4 for the cubic elements (the square of the energy norm's h^2).
    const std::vector<double> at_nodes = {0.0, 0.25, 0.5625, 1.0};
    const double deflection = unit_load_deflection(p, at_nodes);
    Parameters on_nodes = p;
    on_nodes.stations = at_nodes;
    for (Drive drive : {Drive::prescribed, Drive::torque}) {
        SECTION(to_string(drive))
        {
            std::vector<double> errors;
            for (int ny : {16, 32, 64}) {
                VariantKey key = profile_key(Method::fem, drive, ny, 0, Order::zero);
                key.extras.tip = key.extras.damping = false;
                const auto model = make_model(key, on_nodes, ModelSource::assembled);
                const SteadySpin held = held_equilibrium(*model, 0.0);
                const Tip tip = model->tip(held.q.data());
                errors.push_back(std::abs(tip.uy - deflection) / std::abs(deflection));
                INFO("ny " << ny << ": u_y(L) = " << tip.uy << ", unit load " << deflection);
                CHECK(tip.uy < 0.0);
                if (ny == 64 && drive == Drive::prescribed) {
                    // The fields' bending moment is the table's own EI(x) times the curvature: the statics of the
                    // weight outboard of x, M(x) = int_x^L g m(s) (s - x) ds, hogging, to the cubic elements' pointwise
                    // accuracy (the root's EI would be off by 23 % to a factor 2.9 at these x).
                    const BeamFields fields(key, on_nodes);
                    for (double xi : {0.1, 0.4, 0.7, 0.85}) {
                        const double x = xi * p.L, statics = static_moment(p, at_nodes, x);
                        INFO("x/L = " << xi << ": EI u_y'' = " << fields.bending_moment(held.q.data(), x)
                                      << ", statics " << -statics);
                        CHECK(std::abs(fields.bending_moment(held.q.data(), x) + statics) < 1e-3 * statics);
                    }
                }
            }
            INFO("relative errors " << errors[0] << ", " << errors[1] << ", " << errors[2]);
            CHECK(errors[0] < 1e-4);
            CHECK(errors[0] / errors[1] > 15.0);
            CHECK(errors[1] / errors[2] > 15.0);
        }
    }
    // The generated 4-station variants at Ny = 4 against the assembled ones: the same approximation, which for
    // the irregular stations is within a few percent of its own unit-load integral.
    const double irregular_deflection = unit_load_deflection(p, stations);
    Parameters held = p;
    for (Method method : methods) {
        const VariantKey key = profile_key(method, Drive::torque);
        SECTION(key.name())
        {
            const auto gen = make_model(key, held, ModelSource::generated);
            const auto asm_ = make_model(key, held, ModelSource::assembled);
            const double ug = gen->tip(held_equilibrium(*gen, 0.0).q.data()).uy;
            const double ua = asm_->tip(held_equilibrium(*asm_, 0.0).q.data()).uy;
            CHECK(std::abs(ug - ua) < 1e-10 * std::abs(ua));
            CHECK(std::abs(ua - irregular_deflection) < 0.05 * std::abs(irregular_deflection));
        }
    }
}

namespace {

/// A folder of its own for a scene and its profile table, removed afterwards.
struct Folder : TempFolder {
    Folder() : TempFolder("profile") {}
    std::string scene() const { return (path / "blade.toml").string(); }
};

/// A spin-up scene whose [beam] has the lines given (beam.length is there).
std::string scene_with(const std::string& beam)
{
    return "[beam]\nlength = 8.0\n" + beam +
           "\n[motion]\nkind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0\n[discretization]\nmethod = \"fem\"\nny = 4\n"
           "nx = 4\n[output]\nt_end = 1.0\ndt_out = 0.1\n";
}

const std::string good_table =
    "x/L, m, EI, ES\n0, 0.35, 900, 7e6\n0.3, 0.2, 480, 4.2e6\n0.55, 0.26, 610, 5.1e6\n"
    "1, 0.09, 150, 2.4e6\n";

/// The message of the SceneError the scene raises, which names beam.profile or the key given.
std::string error_of(const Folder& f, const std::string& table, const std::string& beam = "profile = \"blade.csv\"\n",
                     const std::string& key = "beam.profile")
{
    f.write("blade.csv", table);
    f.write("blade.toml", scene_with(beam));
    try {
        load_scene(f.scene());
    } catch (const SceneError& e) {
        CHECK(e.key == key);
        CHECK(std::string(e.what()).find(f.scene()) == 0);
        return e.what();
    }
    FAIL("the scene was accepted");
    return {};
}

}  // namespace

TEST_CASE("profile: a scene reads its table beside it", "[profile][scene]")
{
    const Folder f;
    f.write("blade.csv", "# a comment line\n" + good_table);
    f.write("blade.toml", scene_with("profile = \"blade.csv\"\n[gravity]\ng = 9.81\n"));
    const Scene s = load_scene(f.scene());
    const VariantKey key = s.key();
    CHECK(key.name() == "fem_nx4_ny4_prescribed_first_gravity_profile");
    Parameters p;
    irregular(p);
    CHECK(s.parameters.stations == p.stations);
    CHECK(s.parameters.profile == p.profile);
    // The root's values stand for rho S, E I, E S.
    CHECK(s.parameters.rho * s.parameters.S == 0.35);
    CHECK(std::abs(s.parameters.E * s.parameters.I - 900.0) < 1e-12 * 900.0);
    CHECK(s.parameters.E * s.parameters.S == 7e6);
    // An empty name is no table: the section's keys are then required as without the key.
    f.write("blade.toml", scene_with("profile = \"\"\ndensity = 2.7667e3\narea = 7.2968e-5\nsecond_moment = 8.2189e-9\n"
                                     "youngs_modulus = 6.8952e10\n"));
    CHECK_FALSE(load_scene(f.scene()).variant.extras.profile());
}

TEST_CASE("profile: bad tables and scenes are refused naming the scene, the key, the table and its line",
          "[profile][scene]")
{
    const Folder f;
    const std::string csv = (f.path / "blade.csv").string();
    const auto has = [](const std::string& message, const std::string& part) {
        INFO(message);
        CHECK(message.find(part) != std::string::npos);
    };
    has(error_of(f, "x/L, m, EI\n0, 1, 1\n1, 1, 1\n"), csv + ":1: expected a column ES in its header");
    has(error_of(f, "x/L, m, EI, ES, Q\n0, 1, 1, 1, 1\n1, 1, 1, 1, 1\n"),
        csv +
            ":1: expected the columns x/L, m, EI, ES and, for a blade, any of EI_flap, GJ, twist, j_c, j_n, "
            "inertia_twist, cg_offset, tc_offset in its header, got 1 other columns");
    // Comment and blank lines before the header: the message names the header's own line.
    has(error_of(f, "# blade\n\n# x/L from root to tip\nx/L, m, EI, ES, Q\n0, 1, 1, 1, 1\n1, 1, 1, 1, 1\n"),
        csv + ":4: expected the columns x/L, m, EI, ES and");
    // A blade's column in a planar scene would be ignored.
    has(error_of(f, "x/L, m, EI, ES, GJ\n0, 1, 1, 1, 1\n1, 1, 1, 1, 1\n"),
        csv + ": column GJ describes a blade that leaves the plane: expected discretization.nz or nt > 0");
    has(error_of(f, "x/L, m, EI, ES\n0.1, 1, 1, 1\n1, 1, 1, 1\n"), csv + ":2: the first station must be x/L = 0");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 1, 1\n0.5, 1, 1, 1\n0.5, 1, 1, 1\n1, 1, 1, 1\n"),
        csv + ":4: the stations must increase strictly");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 1, 1\n0.5, 1, 1, 1\n"), csv + ": the last station must be x/L = 1");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 1, 1\n"), csv + ": expected at least 2 stations, got 1");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 0, 1\n1, 1, 1, 1\n"), csv + ":2: expected EI > 0, got 0");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 1, 1\n1, 1, 1, inf\n"),
        csv + ":3: expected a finite number in column ES (axial stiffness, N), field 4 of the line");
    has(error_of(f, "x/L, m, EI, ES\n0, 1, 1, 1\n1, 1, 1\n"), csv + ":3: expected 4 fields as the header has, got 3");
    std::string many = "x/L, m, EI, ES\n";
    for (int k = 0; k <= 10000; ++k) many += std::to_string(k / 10000.0) + ", 1, 1, 1\n";
    has(error_of(f, many), csv + ":10002: more than 10000 stations");
    has(error_of(f, std::string((1 << 22) + 1, '#')), "is larger than a profile table can be (4 MB)");
    has(error_of(f, good_table, "profile = \"missing.csv\"\n"), (f.path / "missing.csv").string() + ": cannot open");
    // The section's own keys and a taper do not go with a table.
    has(error_of(f, good_table, "profile = \"blade.csv\"\ndensity = 2.7667e3\n", "beam.density"),
        "not used with beam.profile");
    has(error_of(f, good_table, "profile = \"blade.csv\"\ntaper = \"width\"\ntip_ratio = 0.5\n", "beam.taper"),
        "not used with beam.profile");
}

TEST_CASE("profile: the variant's name says only that there is a table", "[profile][variant]")
{
    VariantKey key = profile_key(Method::bsim, Drive::torque);
    key.spline = SplineBasis::open;
    CHECK(key.name() == "bsim_nx4_ny4_torque_first_open_tip_gravity_damped_profile");
    CHECK(VariantKey::parse(key.name()) == key);
    // The stations were once part of the name: such a name, or a profile with a taper, is not a variant.
    for (const char* bad : {"fem_nx0_ny4_prescribed_first_profile100x0x30x100",
                            "fem_nx0_ny4_prescribed_first_width_profile", "fem_nx0_ny4_prescribed_first_profile_tip"}) {
        INFO(bad);
        CHECK_THROWS_AS(VariantKey::parse(bad), std::invalid_argument);
    }
}

TEST_CASE("profile: a thousand irregular stations run the built-in variant and agree with the assembled path",
          "[profile][generated][assembled]")
{
    // Stations at random spacing, a table with a kink at each: the generated kernels' section integrals (exact for
    // the polynomial bases, converged for AMM) against the assembled path's own quadrature.
    std::mt19937 rng(2216);
    std::uniform_real_distribution<double> gap(0.2, 1.8), wobble(0.9, 1.1);
    std::vector<double> x = {0.0};
    for (int k = 1; k < 1000; ++k) x.push_back(x.back() + gap(rng));
    const double span = x.back() + gap(rng);
    for (double& xk : x) xk /= span;
    x.push_back(1.0);
    for (Method method : methods) {
        const VariantKey key = profile_key(method, Drive::torque);
        SECTION(key.name())
        {
            Parameters p = with_terms();
            tabulate(
                p, x, [&](double xi) { return 0.3 * (1.0 - 0.6 * xi) * wobble(rng); },
                [&](double xi) { return 700.0 * (1.0 - 0.7 * xi) * wobble(rng); },
                [&](double xi) { return 6e6 * (1.0 - 0.5 * xi) * wobble(rng); });
            const auto gen = make_model(key, p, ModelSource::generated);
            REQUIRE(std::string(gen->source()) == "generated");
            REQUIRE(gen->origin() == "built in");
            compare(*gen, *make_model(key, p, ModelSource::assembled), 1e-12, rng);
        }
    }
}
