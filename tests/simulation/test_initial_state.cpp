// Where a run starts (scene key initial.state): the static sag and the centrifugal stretch against their closed forms,
// each start held by the run that follows it (a start at rest rings), and the refusals of a state the scene has not.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <iomanip>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "dynamics/integrate.hpp"
#include "runs.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

/// The largest minus the smallest of one column over the rows.
double range(const std::vector<Row>& rows, double (*column)(const Row&))
{
    double lo = INFINITY, hi = -INFINITY;
    for (const Row& r : rows) lo = std::min(lo, column(r)), hi = std::max(hi, column(r));
    return hi - lo;
}
double tip_uz(const Row& r)
{
    return r.extras.tip_uz;
}
double tip_ux1(const Row& r)
{
    return r.tip_ux1;
}
double tip_uy(const Row& r)
{
    return r.tip_uy;
}

/// cases/helicopter_blade.toml's blade without damping (L = 6 m, m = 8 kg/m, EI_flap = 1e5 N m^2), its spin axis
/// vertical and gravity along it, on a hub held at rest (prescribed) or free with no torque (the weight has no moment
/// about a vertical axis): FEM, Ny = Nz = 4, for a second.
Scene helicopter_at_rest(Drive drive)
{
    Motion m;
    if (drive == Drive::prescribed) {
        m.kind = Motion::Kind::held;
    } else {
        m.kind = Motion::Kind::torque;
        m.tau0 = 0.0;
        m.torque_time = 1.0;
    }
    Scene s = test::paper_scene(Method::fem, 0, 4, m);
    s.variant.nz = 4;
    Parameters& p = s.parameters;
    p.L = 6.0, p.rho = 1600.0, p.S = 0.005, p.I = 4e-5, p.I_flap = 1e-5, p.E = 1e10, p.a = 0.3;
    p.g_axis = 9.81;
    s.output.t_end = 1.0;
    s.output.dt_out = 0.01;
    return s;
}

/// The paper's beam (hub radius 0.5 m) turning at omega from t = 0, prescribed by a table theta = omega t (a natural
/// spline holds a straight line exactly, so the rate is omega throughout).
Scene constant_spin(Method method, int nx, double omega)
{
    Motion m;
    m.kind = Motion::Kind::table;
    std::vector<double> t = {0.0, 0.5, 1.0, 1.5, 2.0}, theta;
    for (double ti : t) theta.push_back(omega * ti);
    m.table = std::make_shared<const DriveTable>(t, theta, DriveTable::Interpolation::cubic_spline);
    Scene s = test::paper_scene(method, nx, 4, m);
    s.parameters.a = 0.5;
    s.output.t_end = 1.0;
    s.output.dt_out = 0.01;
    return s;
}

/// A scene file's text whose hub is prescribed by the table spin.csv (theta = 2 t: an initial spin of 2 rad/s),
/// with [gravity] g (in the plane of rotation) and [initial] state.
std::string spinning_scene(double g, const std::string& state)
{
    return "[beam]\nlength = 8.0\ndensity = 2.7667e3\narea = 7.2968e-5\nsecond_moment = 8.2189e-9\n"
           "youngs_modulus = 6.8952e10\n[gravity]\ng = " +
           std::to_string(g) +
           "\n[motion]\nkind = \"table\"\nfile = \"spin.csv\"\n"
           "[discretization]\nmethod = \"amm\"\nny = 4\nnx = 0\n[output]\nt_end = 1.0\n[initial]\nstate = \"" +
           state + "\"\n";
}

}  // namespace

TEST_CASE("initial.state static: a blade under gravity along the spin axis starts at -m g L^4/(8 EI_flap) and stays",
          "[initial]")
{
    // The closed form of a uniform cantilever under its weight (docs/model.md section 12): FEM's cubic Hermite
    // elements hold the quartic deflection's nodal values exactly, so the tip is the closed form to round-off.
    for (Drive drive : {Drive::prescribed, Drive::torque}) {
        Scene scene = helicopter_at_rest(drive);
        const Parameters& p = scene.parameters;
        const double sag = -p.rho * p.S * p.g_axis * std::pow(p.L, 4) / (8.0 * p.E * p.I_flap);
        scene.initial = InitialState::static_equilibrium;
        const test::Collected still = test::completed_run(scene);
        INFO((drive == Drive::torque ? "free hub" : "held hub")
             << ": tip " << still.rows.front().extras.tip_uz << " against " << sag);
        CHECK(still.rows.front().extras.tip_uz == Approx(sag).epsilon(1e-9));
        CHECK(still.rows.front().theta == 0.0);
        CHECK(range(still.rows, tip_uz) < 1e-9 * std::abs(sag));
        CHECK(range(still.rows, tip_uy) < 1e-9 * std::abs(sag));
        CHECK(still.summary.initial.rfind("static equilibrium at theta = 0 rad (Newton, residual ", 0) == 0);
        // From rest the blade falls and swings about the sag (to about twice it within the first period, 0.58 s).
        scene.initial = InitialState::rest;
        // (Its Jacobi integral, the energy of a start at rest, stays 0 J: round-off against itself, which the error
        // check would call the tolerance's fault.)
        scene.solver.error_check = ErrorCheck::off;
        const test::Collected fallen = test::completed_run(scene);
        CHECK(fallen.rows.front().extras.tip_uz == 0.0);
        CHECK(range(fallen.rows, tip_uz) > 1.5 * std::abs(sag));
        CHECK(fallen.summary.initial.empty());
        // A spin-up starts at rest: its steady spin is the static sag.
        scene.initial = InitialState::steady;
        scene.solver.error_check = ErrorCheck::on;
        CHECK(test::completed_run(scene).rows.front().extras.tip_uz == Approx(sag).epsilon(1e-9));
    }
}

TEST_CASE("initial.state steady: a spinning bar starts at its centrifugal stretch and stays there", "[initial]")
{
    // From the energies of the axial field (docs/model.md section 2): T holds 1/2 m Omega^2 (a + x + u)^2 and U
    // 1/2 ES u'^2, so ES u'' + m Omega^2 u = -m Omega^2 (a + x), u(0) = 0, u'(L) = 0. With k^2 = m Omega^2 / ES:
    // u(L) = -(a + L) + a cos kL + (1 + a k sin kL) tan(kL) / k. To first order in (kL)^2 the tension is
    // N(x) = m Omega^2 int_x^L (a + s) ds, and u(L) = int_0^L N / ES dx = k^2 (a L^2 / 2 + L^3 / 3).
    const double omega = 60.0;
    const Parameters p = constant_spin(Method::bim, 4, omega).parameters;
    const double m = p.rho * p.S, ES = p.E * p.S, k = omega * std::sqrt(m / ES), L = p.L, a = p.a;
    const double exact = -(a + L) + a * std::cos(k * L) + (1.0 + a * k * std::sin(k * L)) * std::tan(k * L) / k;
    const double first_order = k * k * (a * L * L / 2.0 + L * L * L / 3.0);
    REQUIRE(std::abs(exact - first_order) > 1e-3 * exact);  // kL = 0.096: the two are told apart
    CHECK(exact == Approx(first_order).epsilon(0.01));
    // BIM's polynomials of degree 4 and FEM's linear elements (nodal values exact for ES u'' = f; the k^2 u term
    // costs O(h^2 (kL)^2)); A dynamic or quasi-static (y holds B alone, A follows its equilibrium).
    std::vector<double> fem_errors;
    for (const auto& [method, nx, axial, tolerance] : {std::tuple{Method::bim, 4, Axial::dynamic, 1e-6},
                                                       {Method::fem, 4, Axial::dynamic, 1e-4},
                                                       {Method::fem, 8, Axial::dynamic, 3e-5},
                                                       {Method::bim, 4, Axial::quasi_static, 1e-6}}) {
        Scene scene = constant_spin(method, nx, omega);
        scene.axial = axial;
        scene.initial = InitialState::steady;
        const test::Collected run = test::completed_run(scene);
        const double stretch = run.rows.front().tip_ux1;
        INFO(std::setprecision(12) << to_string(method) << " nx " << nx << " " << to_string(axial) << ": " << stretch
                                   << " against " << exact << " (first order " << first_order << ")");
        CHECK(stretch == Approx(exact).epsilon(tolerance));
        if (method == Method::fem) fem_errors.push_back(std::abs(stretch - exact));
        CHECK(range(run.rows, tip_ux1) < 1e-9 * exact);
        CHECK(range(run.rows, tip_uy) < 1e-9 * exact);
        CHECK(run.rows.front().theta_dot == Approx(omega).epsilon(1e-12));
        CHECK(run.summary.initial.rfind("steady spin at theta_dot = 60 rad/s (Newton, residual ", 0) == 0);
        // "static" at a spinning start is the same equilibrium: the centrifugal load is a constant one.
        scene.initial = InitialState::static_equilibrium;
        CHECK(test::completed_run(scene).rows.front().tip_ux1 == Approx(stretch).epsilon(1e-12));
    }
    // FEM's error is the discretization's: it falls as h^2 from nx = 4 to 8.
    INFO("FEM errors " << fem_errors[0] << ", " << fem_errors[1]);
    CHECK(fem_errors[0] / fem_errors[1] == Approx(4.0).epsilon(0.1));
}

TEST_CASE("initial.state static under gravity in the plane of a spinning hub: no elastic acceleration at t = 0",
          "[initial]")
{
    // The equilibrium of the first instant: the weight at theta0 = 0.4 rad and the centrifugal load of 3 rad/s
    // (the bending stiffened by it) balanced by the beam. Its definition is the oracle: the accelerations of the
    // equations of motion there (FirstOrderSystem, the run's right-hand side, not the Newton solve) vanish, where a
    // start at rest meets the full load.
    Scene scene = helicopter_at_rest(Drive::prescribed);
    scene.parameters.g = 9.81, scene.parameters.g_axis = 0.0;
    scene.motion = constant_spin(Method::fem, 0, 3.0).motion;
    scene.motion.theta0 = 0.4;
    scene.output.t_end = scene.output.dt_out;
    const auto acceleration = [&](InitialState state) {
        scene.initial = state;
        Simulation simulation(scene);
        std::vector<double> q;
        simulation.observe_states([&](double t, const double* state_q) {
            if (t == 0.0) q.assign(state_q, state_q + simulation.model().nq());
        });
        REQUIRE(simulation.run([](const Row&) {}).completed);
        const std::size_t n = q.size();
        FirstOrderSystem system(simulation.model(), scene.motion);
        std::vector<double> y(2 * n, 0.0), f(2 * n);
        std::copy(q.begin(), q.end(), y.begin());
        REQUIRE(system.rhs(0.0, y.data(), f.data()) == 0);
        double largest = 0.0;
        for (std::size_t i = n; i < 2 * n; ++i) largest = std::max(largest, std::abs(f[i]));
        return largest;
    };
    const double at_rest = acceleration(InitialState::rest), still = acceleration(InitialState::static_equilibrium);
    INFO("largest acceleration from rest " << at_rest << ", from the static start " << still);
    CHECK(at_rest > 1.0);
    CHECK(still < 1e-9 * at_rest);
}

TEST_CASE("initial.state steady is refused under gravity in the plane of a spinning hub, and names the key",
          "[initial]")
{
    TempFolder folder("initial");
    folder.write("spin.csv", "t,theta\n0,0\n0.5,1\n1,2\n1.5,3\n");
    const std::string path = folder.write("spinning.toml", spinning_scene(9.81, "steady"));
    try {
        load_scene(path);
        FAIL("a steady spin under gravity in the plane was accepted");
    } catch (const SceneError& e) {
        CHECK(e.key == "initial.state");
        const std::string message = e.what();
        INFO(message);
        CHECK(message.rfind(path + ": initial.state: ", 0) == 0);
        CHECK(message.find("periodic") != std::string::npos);
        CHECK(message.find("use \"static\"") != std::string::npos);
        CHECK(message.find("\"rest\"") != std::string::npos);
    }
    // Without gravity, or with the hub at rest, the steady spin is there; "static" and "rest" always are.
    folder.write("weightless.toml", spinning_scene(0.0, "steady"));
    CHECK_NOTHROW(load_scene((folder.path / "weightless.toml").string()));
    for (const char* state : {"static", "rest"}) {
        folder.write("other.toml", spinning_scene(9.81, state));
        CHECK_NOTHROW(load_scene((folder.path / "other.toml").string()));
    }
    Scene held = helicopter_at_rest(Drive::prescribed);
    held.parameters.g = 9.81, held.parameters.g_axis = 0.0;
    held.initial = InitialState::steady;
    CHECK_NOTHROW(validate(held));
    // A scene changed in code after loading is refused by the run as well.
    Scene spinning = held;
    spinning.motion = constant_spin(Method::fem, 0, 2.0).motion;
    CHECK_THROWS_AS(Simulation(spinning), std::invalid_argument);
}

TEST_CASE("initial.state: an unknown word names the key and the words it takes, and sensitivities start at rest",
          "[initial]")
{
    const std::string scene =
        "[beam]\nlength = 8.0\ndensity = 2.7667e3\narea = 7.2968e-5\nsecond_moment = 8.2189e-9\n"
        "youngs_modulus = 6.8952e10\n[motion]\nkind = \"spin-up\"\nomega0 = 4.0\nduration = 15.0\n"
        "[discretization]\nmethod = \"amm\"\nny = 4\nnx = 0\n[output]\nt_end = 1.0\n";
    try {
        parse_scene(scene + "[initial]\nstate = \"moving\"\n", "moving.toml");
        FAIL("an unknown initial state was accepted");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()) ==
              "moving.toml: initial.state: expected one of \"rest\", \"static\", \"steady\", got a string \"moving\"");
    }
    CHECK_THROWS_WITH(parse_scene(scene + "[initial]\nstate = \"static\"\nspeed = 1\n", "extra.toml"),
                      Catch::Contains("initial.speed"));
    CHECK(parse_scene(scene, "default.toml").initial == InitialState::rest);
    CHECK(parse_scene(scene, "override.toml", {{"initial.state", "steady"}}).initial == InitialState::steady);
    try {
        parse_scene(scene + "[initial]\nstate = \"static\"\n", "sensitive.toml", {{"output.sensitivities", "E"}});
        FAIL("a static start with sensitivities was accepted");
    } catch (const SceneError& e) {
        CHECK(e.key == "initial.state");
    }
}
