// Modes and the linearized model (linearize.hpp) against physics computed here independently: the cantilever's
// frequencies (roots of 1 + cos z cosh z = 0), the rotating cantilever's flapwise frequencies by power series,
// the in-plane relation omega_inplane^2 = omega_flap^2 - Omega^2 (docs/model.md section 7), and the state-space
// matrices against central differences of the nonlinear equations.
#include <unistd.h>

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/modes_table.hpp>
#include <hubbeam/motion.hpp>
#include <hubbeam/scene.hpp>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/integrate.hpp"
#include "eigen_oracles.hpp"
#include "modes.hpp"

using namespace hubbeam;

namespace {

VariantKey key_of(Method method, int nx, int ny, Drive drive = Drive::prescribed, Order order = Order::first)
{
    return {.method = method, .nx = nx, .ny = ny, .order = order, .drive = drive, .extras = {}};
}

/// The natural modes of one variant from both sources, generated and assembled, at a steady spin.
struct BothSources {
    std::unique_ptr<Model> generated, assembled;
    BothSources(const VariantKey& key, const Parameters& p)
        : generated(make_model(key, p, ModelSource::generated)), assembled(make_model(key, p, ModelSource::assembled))
    {
    }
    std::pair<std::vector<NaturalMode>, std::vector<NaturalMode>> modes(double omega) const
    {
        return {natural_modes(*generated, steady_spin(*generated, omega)),
                natural_modes(*assembled, steady_spin(*assembled, omega))};
    }
};

/// The bending frequencies of the linearized model about a steady spin, dimensionless (omega / sqrt(EI/(m L^4))).
std::vector<double> bending(const Model& model, const Parameters& p, double omega)
{
    std::vector<double> out;
    for (const NaturalMode& m : natural_modes(model, steady_spin(model, omega)))
        if (m.kind == "bending") out.push_back(m.rad_s / frequency_unit(p));
    return out;
}

/// The i-th root of 1 + cos z cosh z = 0 by bisection: the cantilever's beta_i L.
double cantilever_root(int i)
{
    const auto f = [](double z) { return 1.0 + std::cos(z) * std::cosh(z); };
    double lo = (i - 0.5) * std::numbers::pi - 1.0, hi = (i - 0.5) * std::numbers::pi + 1.0;
    if (i == 1) lo = 1.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(lo) * f(mid) <= 0.0 ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

/// The flapwise (out-of-plane) frequencies, dimensionless, of a uniform cantilever spinning at nu (dimensionless
/// Omega) about an axis through its root: w'''' - (nu^2/2) ((1 - xi^2) w')' - lambda^2 w = 0, w(0) = w'(0) = 0,
/// w''(1) = w'''(1) = 0, solved by power series (the coefficients are polynomial, so the series converges on
/// [0, 1]) and bisection on the boundary determinant.
std::vector<double> flapwise(double nu, int count)
{
    const auto determinant = [&](long double lambda2) {
        long double d2[2] = {0, 0}, d3[2] = {0, 0};
        for (int s = 0; s < 2; ++s) {
            std::vector<long double> c(260, 0.0L);
            c[2 + s] = 1.0L;
            for (int k = 0; k + 4 < static_cast<int>(c.size()); ++k)
                c[k + 4] = (0.5L * nu * nu * ((k + 2.0L) * (k + 1.0L) * c[k + 2] - k * (k + 1.0L) * c[k]) + lambda2 * c[k]) /
                           ((k + 4.0L) * (k + 3.0L) * (k + 2.0L) * (k + 1.0L));
            for (int k = 2; k < static_cast<int>(c.size()); ++k) {
                d2[s] += k * (k - 1.0L) * c[k];
                d3[s] += k * (k - 1.0L) * (k - 2.0L) * c[k];
            }
        }
        return d2[0] * d3[1] - d2[1] * d3[0];
    };
    std::vector<double> roots;
    long double lo = 0.5L, step = 0.01L;
    for (long double l = lo; static_cast<int>(roots.size()) < count; l += step) {
        const long double a = determinant(l * l), b = determinant((l + step) * (l + step));
        if ((a < 0) == (b < 0)) continue;
        long double x = l, y = l + step;
        for (int k = 0; k < 100; ++k) {
            const long double mid = 0.5L * (x + y);
            ((determinant(x * x) < 0) == (determinant(mid * mid) < 0) ? x : y) = mid;
        }
        roots.push_back(static_cast<double>(0.5L * (x + y)));
    }
    return roots;
}

}  // namespace

TEST_CASE("the power series reproduces the cantilever at rest", "[modes]")
{
    const std::vector<double> series = flapwise(0.0, 4);
    for (int i = 1; i <= 4; ++i) CHECK(series[static_cast<std::size_t>(i - 1)] == Approx(std::pow(cantilever_root(i), 2)).epsilon(1e-12));
}

TEST_CASE("at rest every method converges to the cantilever's frequencies", "[modes]")
{
    const Parameters p;
    std::vector<double> exact;
    for (int i = 1; i <= 3; ++i) exact.push_back(std::pow(cantilever_root(i), 2));
    // AMM's basis is the exact mode shapes: exact at any Ny.
    const auto amm = make_model(key_of(Method::amm, 0, 6), p, ModelSource::assembled);
    for (std::size_t i = 0; i < 3; ++i) CHECK(bending(*amm, p, 0.0)[i] == Approx(exact[i]).epsilon(1e-9));
    // BIM's single polynomial converges spectrally: six digits at Ny = 12.
    const auto bim = make_model(key_of(Method::bim, 0, 12), p, ModelSource::assembled);
    for (std::size_t i = 0; i < 3; ++i) CHECK(bending(*bim, p, 0.0)[i] == Approx(exact[i]).epsilon(1e-6));
    // The cubic pieces of FEM and BSIM converge from above (Rayleigh-Ritz) as h^4: doubling Ny divides the error of
    // modes 2 and 3 by 16 in the limit, by more than 8 from Ny = 8 to 16.
    for (Method method : {Method::fem, Method::bsim}) {
        std::vector<double> error8;
        for (int ny : {8, 16}) {
            const auto model = make_model(key_of(method, 0, ny), p, ModelSource::assembled);
            const std::vector<double> f = bending(*model, p, 0.0);
            for (std::size_t i = 0; i < 3; ++i) {
                INFO(to_string(method) << " Ny " << ny << " mode " << i + 1);
                CHECK(f[i] >= exact[i] * (1.0 - 1e-12));
                if (ny == 8) error8.push_back(f[i] - exact[i]);
                else if (i > 0) CHECK(f[i] - exact[i] < error8[i] / 8.0);
            }
        }
    }
    // The axial modes: (2i - 1) pi / 2 sqrt(E / rho) / L.
    const auto both = make_model(key_of(Method::amm, 4, 4), p, ModelSource::assembled);
    std::vector<double> axial;
    for (const NaturalMode& m : natural_modes(*both, steady_spin(*both, 0.0)))
        if (m.kind == "axial") axial.push_back(m.rad_s);
    REQUIRE(axial.size() == 4);
    CHECK(axial[0] == Approx(std::numbers::pi / 2.0 * std::sqrt(p.E / p.rho) / p.L).epsilon(1e-9));
}

TEST_CASE("a conservative beam's modes keep their own digits: generated and assembled agree mode by mode to round-off",
          "[modes]")
{
    // Without damping, axial coordinates or a free hub the linearized equations are K x = omega^2 M x, solved as a
    // symmetric problem in its inverse form: its low modes err by about eps times K's conditioning, its high ones by
    // eps (omega_k / omega_1)^2 at most. The first-order form erred by eps omega_max^2 / omega_k, absolutely in
    // omega: FEM Ny = 32's first modes, whose highest is 3,900 to 4,400 times the first, to 1e-8. The two sources' M
    // and K agree to round-off of their entries, so their modes must agree to the solve's round-off.
    const BothSources sources(key_of(Method::fem, 0, 32), Parameters{});
    for (const double omega : {0.0, 3.0}) {
        const auto [g, a] = sources.modes(omega);
        REQUIRE(g.size() == 32);
        REQUIRE(a.size() == g.size());
        CHECK(a.back().rad_s > 3000.0 * a.front().rad_s);  // wide enough for the first-order form's round-off to show
        for (std::size_t k = 0; k < a.size(); ++k) {
            const double relative = std::abs(g[k].rad_s / a[k].rad_s - 1.0);
            INFO("Omega " << omega << ", mode " << k + 1 << ": " << g[k].rad_s << " and " << a[k].rad_s
                          << " rad/s, relative " << relative);
            CHECK(relative <= (k < 6 ? 1e-11 : 1e-10));
            CHECK(g[k].growth == 0.0);
        }
    }
}

TEST_CASE("a gyroscopic beam's modes keep their digits too: with axial coordinates under a prescribed spin, generated "
          "and assembled agree mode by mode to round-off",
          "[modes]")
{
    // The axial coordinates enter the rates by Coriolis terms alone: a Hermitian pencil whose frequencies err by eps
    // times the highest (the axial modes, 7,000 to 10,000 rad/s), where the first-order form's erred by eps times its
    // square: 1e-9 to 3e-9 of the first bending mode, 2.9 rad/s, for the four methods at Ny = Nx = 4.
    for (const Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        const BothSources sources(key_of(method, 4, 4), Parameters{});
        for (const double omega : {0.0, 4.0, 10.0}) {
            const auto [g, a] = sources.modes(omega);
            REQUIRE(g.size() == 8);
            REQUIRE(a.size() == g.size());
            for (std::size_t k = 0; k < a.size(); ++k) {
                INFO(to_string(method) << ", Omega " << omega << ", mode " << k + 1 << ": " << g[k].rad_s << " and "
                                       << a[k].rad_s << " rad/s");
                CHECK(std::abs(g[k].rad_s / a[k].rad_s - 1.0) <= 1e-11);
                CHECK(g[k].growth == 0.0);
                CHECK(g[k].kind == a[k].kind);
            }
        }
    }
}

TEST_CASE("spinning without axial coordinates, omega_inplane^2 = omega_flap^2 - Omega^2", "[modes]")
{
    const Parameters p;  // a = 0
    for (double omega : {4.0, 10.0, 20.0}) {
        const double nu = omega / frequency_unit(p);
        const std::vector<double> flap = flapwise(nu, 3);
        // BIM, converged to round-off at Ny = 14, holds the relation to 1e-7.
        const auto bim = make_model(key_of(Method::bim, 0, 14), p, ModelSource::assembled);
        const std::vector<double> converged = bending(*bim, p, omega);
        for (std::size_t i = 0; i < 3; ++i) {
            INFO("Omega " << omega << " mode " << i + 1);
            CHECK(converged[i] * converged[i] + nu * nu == Approx(flap[i] * flap[i]).epsilon(1e-7));
        }
        // Every method converges to it: closer at Ny = 24 than at Ny = 8, and within 5e-4 in omega^2 (FEM, the
        // slowest, is 3.6e-4 off with its 12 elements at 20 rad/s).
        for (Method method : {Method::amm, Method::fem, Method::bsim}) {
            std::vector<double> error8;
            for (int ny : {8, 24}) {
                const auto model = make_model(key_of(method, 0, ny), p, ModelSource::assembled);
                const std::vector<double> f = bending(*model, p, omega);
                for (std::size_t i = 0; i < 3; ++i) {
                    INFO(to_string(method) << " Ny " << ny << " Omega " << omega << " mode " << i + 1);
                    const double error = std::abs(f[i] * f[i] + nu * nu - flap[i] * flap[i]) / (flap[i] * flap[i]);
                    if (ny == 8) error8.push_back(error);
                    else CHECK(error < error8[i]);
                    if (ny == 24) CHECK(error < 5e-4);
                }
            }
        }
    }
}

TEST_CASE("order zero loses its first mode to divergence above the first bending frequency", "[modes]")
{
    const Parameters p;
    const auto model = make_model(key_of(Method::amm, 0, 4, Drive::prescribed, Order::zero), p, ModelSource::generated);
    const double critical = std::pow(cantilever_root(1), 2) * frequency_unit(p);
    const std::vector<NaturalMode> below = natural_modes(*model, steady_spin(*model, 0.99 * critical));
    const std::vector<NaturalMode> above = natural_modes(*model, steady_spin(*model, 1.01 * critical));
    CHECK(below[0].rad_s > 0.0);
    CHECK(below[0].growth == 0.0);
    CHECK(above[0].rad_s == 0.0);
    CHECK(above[0].growth > 0.0);
    // Order zero's stiffness at a spin is K - Omega^2 M (no stiffening): above the second frequency two modes diverge,
    // each at sqrt(Omega^2 - omega_k^2), the faster first (divergent modes lead, by growth).
    const double spin = 1.2 * std::pow(cantilever_root(2), 2) * frequency_unit(p);
    const std::vector<NaturalMode> two = natural_modes(*model, steady_spin(*model, spin));
    for (int k = 1; k <= 2; ++k) {
        const double omega_k = std::pow(cantilever_root(k), 2) * frequency_unit(p);
        INFO("mode " << k);
        CHECK(two[static_cast<std::size_t>(k - 1)].rad_s == 0.0);
        const double growth = std::sqrt(spin * spin - omega_k * omega_k);
        CHECK(two[static_cast<std::size_t>(k - 1)].growth == Approx(growth).epsilon(1e-8));
    }
}

TEST_CASE("the state-space matrices are the derivatives of the nonlinear equations", "[modes]")
{
    const Parameters p;
    for (const Drive drive : {Drive::prescribed, Drive::torque})
        for (const Method method : {Method::amm, Method::bsim}) {
            const auto model = make_model(key_of(method, 4, 4, drive), p, ModelSource::generated);
            REQUIRE(model->jacobian() != nullptr);
            const SteadySpin s = steady_spin(*model, 4.0);
            const StateSpace ss = state_space(*model, s);
            const int n = model->nq();
            const bool torque = drive == Drive::torque;
            const auto m = ss.A.rows() / 2;
            // x' = f(x, v) of the nonlinear equations, in the state order of StateSpace.
            const auto f = [&](const Eigen::VectorXd& x, double v) {
                std::vector<double> q(static_cast<std::size_t>(n)), qd(q), Q(q);
                HubInput u;
                const int shift = torque ? 0 : 1;
                for (int i = 0; i < n; ++i) {
                    q[static_cast<std::size_t>(i)] = x[i + shift];
                    qd[static_cast<std::size_t>(i)] = x[m + i + shift];
                }
                if (torque) u.tau = v;
                else u.theta_dot = x[m], u.theta_ddot = v;
                Eigen::MatrixXd M(n, n);
                model->mass(u, q.data(), M.data());
                model->forces(u, q.data(), qd.data(), Q.data());
                const Eigen::VectorXd qdd = M.llt().solve(Eigen::Map<Eigen::VectorXd>(Q.data(), n));
                Eigen::VectorXd dx(2 * m);
                dx.head(m) = x.tail(m);
                if (!torque) dx[m] = v;
                for (int i = 0; i < n; ++i) dx[m + i + shift] = qdd[i];
                return dx;
            };
            Eigen::VectorXd x0 = Eigen::VectorXd::Zero(2 * m);
            for (int i = 0; i < n; ++i) {
                x0[i + (torque ? 0 : 1)] = s.q[static_cast<std::size_t>(i)];
                x0[m + i + (torque ? 0 : 1)] = s.qd[static_cast<std::size_t>(i)];
            }
            if (!torque) x0[m] = 4.0;
            REQUIRE(f(x0, 0.0).tail(m).cwiseAbs().maxCoeff() < 1e-9);  // the steady spin is an equilibrium
            const double scale = ss.A.cwiseAbs().maxCoeff();
            for (Eigen::Index k = 0; k < 2 * m; ++k) {
                const double h = 1e-6 * std::max(1.0, std::abs(x0[k]));
                Eigen::VectorXd plus = x0, minus = x0;
                plus[k] += h;
                minus[k] -= h;
                const Eigen::VectorXd column = (f(plus, 0.0) - f(minus, 0.0)) / (2 * h);
                INFO(to_string(method) << " " << to_string(drive) << " state " << ss.states[static_cast<std::size_t>(k)]);
                CHECK((column - ss.A.col(k)).cwiseAbs().maxCoeff() <= 1e-6 * scale);
            }
            const Eigen::VectorXd input = (f(x0, 1e-3) - f(x0, -1e-3)) / 2e-3;
            CHECK((input - ss.B.col(0)).cwiseAbs().maxCoeff() <= 1e-7 * std::max(1.0, ss.B.cwiseAbs().maxCoeff()));
            // tip_uy = Phi_y(L) B: the C row against the model's tip.
            Eigen::VectorXd x1 = x0;
            x1.segment(m - 4, 4).setConstant(0.01);
            std::vector<double> q(static_cast<std::size_t>(n));
            for (int i = 0; i < n; ++i) q[static_cast<std::size_t>(i)] = x1[i + (torque ? 0 : 1)];
            CHECK(ss.C.row(0).dot(x1 - x0) == Approx(model->tip(q.data()).uy).epsilon(1e-12));
        }
}

TEST_CASE("quasi-static axial coordinates leave the bending modes and no axial ones", "[modes]")
{
    // A condensed statically (docs/model.md section 9): at rest nothing couples it to bending, so the bending
    // frequencies are the dynamic model's, up to the nonsymmetric eigensolver's round-off (7e-11 with the free
    // hub, whose eigenproblem spans 4 to 980 rad/s); spinning, the Coriolis coupling to the axial modes, 340 times
    // higher, shifts them by far less than 1e-3.
    const Parameters p;
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        const auto model = make_model(key_of(Method::amm, 4, 4, drive), p, ModelSource::generated);
        for (double omega : {0.0, 10.0}) {
            const SteadySpin s = steady_spin(*model, omega);
            std::vector<double> dynamic;
            for (const NaturalMode& m : natural_modes(*model, s, Axial::dynamic))
                if (m.kind == "bending") dynamic.push_back(m.rad_s);
            const std::vector<NaturalMode> condensed = natural_modes(*model, s, Axial::quasi_static);
            INFO(to_string(drive) << " Omega " << omega);
            REQUIRE(condensed.size() == dynamic.size());
            for (std::size_t i = 0; i < condensed.size(); ++i) {
                CHECK(condensed[i].kind == "bending");
                if (omega == 0.0) CHECK(condensed[i].rad_s == Approx(dynamic[i]).epsilon(1e-9));
                else CHECK(condensed[i].rad_s == Approx(dynamic[i]).epsilon(1e-3));
            }
        }
    }
}

TEST_CASE("the condensed modes are the eigenvalues of the quasi-static run's own equations", "[modes]")
{
    // An independent route: FirstOrderSystem's quasi-static right-hand side (A by Newton at every evaluation,
    // integrate.cpp), differentiated by central differences at the steady spin, has the condensed modes as its
    // eigenvalues (besides a free hub's zero pair). Order full too: there the other rows depend on A itself, which
    // the condensation must carry (at order first only A's rates enter them, and those are dropped).
    const Parameters p;
    for (const Order order : {Order::first, Order::full})
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        const auto model = make_model(key_of(Method::amm, 2, 3, drive, order), p, ModelSource::generated);
        const double omega = 10.0;
        Motion motion;  // long after the drive: steady spin (prescribed) or no torque (free hub)
        motion.kind = drive == Drive::torque ? Motion::Kind::torque : Motion::Kind::spin_up;
        motion.omega0 = omega;
        FirstOrderSystem system(*model, motion, Axial::quasi_static);
        const int size = system.size();
        std::vector<double> y(static_cast<std::size_t>(size), 0.0), dfdy(static_cast<std::size_t>(size * size)), dfdt(y);
        if (drive == Drive::torque) y[static_cast<std::size_t>(size / 2)] = omega;  // theta_dot
        const double t = 100.0;
        REQUIRE(system.finite_difference_jacobian(t, y.data(), dfdy.data(), dfdt.data()) == 0);
        const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(dfdy.data(), size, size);
        const Eigen::VectorXcd lambda = test::general_eigen(J).values;
        std::vector<double> reference;
        for (Eigen::Index k = 0; k < lambda.size(); ++k)
            if (lambda[k].imag() > 1e-6) reference.push_back(lambda[k].imag());
        std::sort(reference.begin(), reference.end());
        const std::vector<NaturalMode> condensed = natural_modes(*model, steady_spin(*model, omega), Axial::quasi_static);
        INFO(to_string(drive) << " " << to_string(order));
        REQUIRE(condensed.size() == reference.size());
        for (std::size_t i = 0; i < reference.size(); ++i) CHECK(condensed[i].rad_s == Approx(reference[i]).epsilon(1e-6));
    }
}

TEST_CASE("linearize prints the state names it writes, separated by commas", "[modes]")
{
    // The free hub with Nx = Ny = 4: theta, A1..A4, B1..B4, then their rates (the rows of PREFIX-A.csv).
    const Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/torque_tau10.toml");
    std::string names = "theta";
    for (const char* stem : {"A", "B"})
        for (int i = 1; i <= 4; ++i) names += ", " + std::string(stem) + std::to_string(i);
    names += ", theta_dot";
    for (const char* stem : {"A", "B"})
        for (int i = 1; i <= 4; ++i) names += ", " + std::string(stem) + std::to_string(i) + "_dot";
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("hubbeam-lin-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ostringstream out;
    run_linearize(scene, 2.0, (dir / "lin").string(), out);
    std::filesystem::remove_all(dir);
    INFO(out.str());
    CHECK(out.str().find("\nstates      18 (" + names + ")\n") != std::string::npos);
}

namespace {

/// A row of the table `hubbeam modes` prints: the columns it is read by.
struct PrintedMode {
    std::string kind, label;
    double rad_s = 0.0, growth = 0.0, undamped = 0.0, zeta = 0.0;
};

/// The rows of the printed table (a damped one: its last two columns are |lambda| and zeta).
std::vector<PrintedMode> printed_modes(const std::string& table)
{
    std::vector<PrintedMode> rows;
    std::istringstream in(table);
    std::string line;
    std::getline(in, line);  // the heading
    while (std::getline(in, line) && !line.empty()) {
        std::istringstream f(line);
        std::string method, order, label_number;
        int ny = 0, nx = 0, number = 0;
        double omega = 0.0, hz = 0.0, dimensionless = 0.0;
        PrintedMode m;
        f >> method >> ny >> nx >> order >> omega >> number >> m.kind >> m.label >> label_number >> m.rad_s >> hz >>
            dimensionless >> m.growth >> m.undamped >> m.zeta;
        REQUIRE(f);
        m.label += " " + label_number;
        rows.push_back(m);
    }
    return rows;
}

}  // namespace

TEST_CASE("modes prints every kind up to --count: a PI loop's hub modes and a bar's axial modes", "[modes]")
{
    // tests/scenes/pi_stiff_arm.toml: a nearly rigid arm, so that its hub modes are the rigid closed loop's, the
    // roots of J s^3 + kd s^2 + kp s + ki = 0 with J = J_oh + rho S L^3 / 3; and at rest its axial modes are a
    // clamped-free bar's, (2k - 1) pi / (2 L) sqrt(E / rho) (assumed modes: the bar's own shapes, so exact).
    const Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/tests/scenes/pi_stiff_arm.toml");
    const Parameters& p = scene.parameters;
    REQUIRE(scene.control);
    const double J = p.J_oh + p.rho * p.S * std::pow(p.L, 3) / 3.0;
    const double kp = scene.control->kp, kd = scene.control->kd, ki = scene.control->ki;
    // The cubic's real root by bisection between s = -kd / J - 1, where it is negative, and 0, where it is ki > 0;
    // then the quadratic left after dividing it out.
    const auto cubic = [&](double s) { return ((J * s + kd) * s + kp) * s + ki; };
    double lo = -kd / J - 1.0, hi = 0.0;
    REQUIRE(cubic(lo) < 0.0);
    for (int k = 0; k < 200; ++k) (cubic(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
    const double real_root = 0.5 * (lo + hi);
    // J s^3 + kd s^2 + kp s + ki = (s - r)(J s^2 + b s + c)
    const double b = kd + J * real_root, c = kp + b * real_root;
    const double pair_undamped = std::sqrt(c / J), pair_zeta = b / (2.0 * std::sqrt(c * J));
    const double bar = std::numbers::pi / (2.0 * p.L) * std::sqrt(p.E / p.rho);

    ModesArgs args;
    args.omega = "0";
    args.count = "8";
    std::ostringstream out;
    run_modes(scene, parse_modes_options(args, scene), out);
    INFO(out.str());
    const std::vector<PrintedMode> rows = printed_modes(out.str());
    std::vector<PrintedMode> hub, axial;
    int bending = 0;
    for (const PrintedMode& m : rows) {
        // the real root is a row of its own, of kind overdamped (it does not oscillate), before the hub's pair
        if (m.kind == "hub" || m.kind == "overdamped") hub.push_back(m);
        if (m.kind == "axial") axial.push_back(m);
        bending += m.kind == "bending";
    }
    CHECK(bending == 4);
    // the real root (a row of its own, rad_s 0, zeta 1) and the pair, by |lambda|
    REQUIRE(hub.size() == 2);
    CHECK(hub[0].kind == "overdamped");
    CHECK(hub[1].kind == "hub");
    CHECK(hub[0].rad_s == 0.0);
    CHECK(hub[0].growth < 0.0);
    CHECK(hub[0].undamped == Approx(-real_root).epsilon(1e-4));
    CHECK(hub[0].zeta == 1.0);
    CHECK(hub[1].undamped == Approx(pair_undamped).epsilon(1e-4));
    CHECK(hub[1].zeta == Approx(pair_zeta).epsilon(2e-4));  // printed to 4 digits
    CHECK(hub[1].rad_s == Approx(pair_undamped * std::sqrt(1.0 - pair_zeta * pair_zeta)).epsilon(1e-4));
    CHECK(hub[0].label != hub[1].label);
    REQUIRE(axial.size() == 2);
    for (std::size_t k = 0; k < axial.size(); ++k) {
        CHECK(axial[k].rad_s == Approx((2.0 * static_cast<double>(k) + 1.0) * bar).epsilon(1e-6));
        CHECK(axial[k].label == "axial " + std::to_string(k + 1));
    }

    // --count N: the first N of each kind, by frequency
    args.count = "1";
    std::ostringstream one;
    run_modes(scene, parse_modes_options(args, scene), one);
    std::vector<std::string> kinds;
    for (const PrintedMode& m : printed_modes(one.str())) kinds.push_back(m.kind);
    CHECK(kinds == std::vector<std::string>{"overdamped", "hub", "bending", "axial"});
}

TEST_CASE("a blade's state space also puts out tip_uz and tip_phi, the tip's values of the flapwise and twist bases",
          "[modes][out_of_plane]")
{
    // u_z(L) = Phi_z(1) Z and phi(L) = Phi_t(1) P: their rows of C hold the bases' values at the tip in Z's and P's
    // columns (and nothing else), after tip_uy and theta, whose rows a planar scene has alone.
    Parameters p;
    p.I_flap = 0.5 * p.I, p.G = 2.6e10, p.J_t = p.I, p.pitch = 0.2;
    const VariantKey key{.method = Method::bim, .nx = 0, .ny = 3, .nz = 3, .nt = 2, .drive = Drive::torque,
                         .extras = {.pitch = true}};
    const auto model = make_model(key, p, ModelSource::generated);
    const StateSpace ss = state_space(*model, steady_spin(*model, 3.0));
    REQUIRE(ss.outputs == std::vector<std::string>{"tip_uy", "theta", "tip_uz", "tip_phi"});
    REQUIRE(ss.C.rows() == 4);
    CHECK(ss.D.rows() == 4);
    const CoordinateLayout layout = coordinate_layout(key);
    for (const auto& [row, kind, basis] : {std::tuple{2, FieldKind::flap, key.flap_basis()},
                                           std::tuple{3, FieldKind::twist, key.twist_basis()}}) {
        Eigen::RowVectorXd expected = Eigen::RowVectorXd::Zero(ss.C.cols());
        const CoordinateField* f = layout.find(kind);
        for (int i = 0; i < f->count; ++i) expected(f->first + i) = basis.at(i, 1.0).v;  // theta is state 0 and q[0]
        INFO(ss.outputs[static_cast<std::size_t>(row)]);
        CHECK((ss.C.row(row) - expected).norm() < 1e-12 * expected.norm());
    }
}

TEST_CASE("a table's unstable ranges are the runs of rates where a mode grows beyond round-off", "[modes]")
{
    // Rates 1 .. 6: mode a grows at 2 and 3, mode b at 3 and at 6; at 4 a growth of round-off (1e-12 of the
    // frequency) and at 5 a decaying mode count for nothing.
    ModesBlock block;
    const auto row = [&](double omega, const char* label, double growth) {
        SpinMode m;
        m.omega = omega;
        m.label = label;
        m.mode.growth = growth;
        m.mode.rad_s = 10.0;
        m.mode.undamped_rad_s = std::hypot(10.0, growth);
        block.modes.push_back(m);
    };
    row(1, "a", 0.0), row(1, "b", -0.1);
    row(2, "a", 0.3), row(2, "b", -0.1);
    row(3, "a", 0.2), row(3, "b", 0.01);
    row(4, "a", 1e-11), row(4, "b", 0.0);
    row(5, "a", -0.2), row(5, "b", -0.1);
    row(6, "a", 0.0), row(6, "b", 0.5);
    const std::vector<UnstableRange> r = unstable_ranges(block);
    REQUIRE(r.size() == 2);
    CHECK(r[0].from == 2.0);
    CHECK(r[0].to == 3.0);
    CHECK(r[0].labels == std::vector<std::string>{"a", "b"});
    CHECK(r[1].from == 6.0);
    CHECK(r[1].to == 6.0);
    CHECK(r[1].labels == std::vector<std::string>{"b"});
}
