// The extra terms (tip body, linear taper, Rayleigh damping, gravity) against physics computed here independently:
// the tip-mass cantilever's frequency equation, the tapered cantilever's deflection by the unit-load integral, the
// Rayleigh damping ratios, q L^4 / (8 EI), the rigid pendulum integrated by RK4, and the conserved energy. The
// variants are compiled on demand (first use), then taken from the cache.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "gauss_legendre.hpp"
#include "runs.hpp"
#include "shared_oracles.hpp"

using namespace hubbeam;

namespace {

const std::vector<Method> all_methods = {Method::amm, Method::fem, Method::bim, Method::bsim};
const std::vector<int> ny_steps = {4, 8, 16};

VariantKey extras_key(Method method, int ny, Drive drive, Extras extras)
{
    return {.method = method, .nx = 0, .ny = ny, .order = Order::first, .drive = drive, .extras = extras};
}

/// The tip body, damping and a width taper in one variant family (values zero where a test does not use them), so
/// that the tests share few compilations.
constexpr Extras tip_damped_width{.tip = true, .gravity = false, .damping = true, .taper = Taper::width};
constexpr Extras tip_gravity_width{.tip = true, .gravity = true, .damping = false, .taper = Taper::width};

std::unique_ptr<Model> generated(Method method, int ny, const Parameters& p, Extras extras = tip_damped_width,
                                 Drive drive = Drive::prescribed)
{
    return make_model(extras_key(method, ny, drive, extras), p, ModelSource::generated);
}

/// The bending frequencies (rad/s; undamped |lambda|) about the steady spin omega.
std::vector<double> bending(const Model& model, double omega = 0.0)
{
    std::vector<double> out;
    for (const NaturalMode& m : natural_modes(model, steady_spin(model, omega)))
        if (m.kind == "bending") out.push_back(m.undamped_rad_s);
    return out;
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// A beam stiffer and shorter than the paper's: L = 1 m (q L^4 / (8 EI) = 4.4e-4 m with the paper's section).
Parameters short_beam()
{
    Parameters p;
    p.L = 1.0;
    return p;
}

}  // namespace

TEST_CASE("a tip mass lowers the cantilever's frequencies to the roots of its frequency equation, for every method",
          "[extras][tip][modes]")
{
    Parameters p;
    p.m_tip = 0.5 * p.rho * p.S * p.L;
    const double mu = p.m_tip / (p.rho * p.S * p.L);
    const std::vector<double> z = test::tip_mass_roots(mu, 3);
    const double unit = std::sqrt(p.E * p.I / (p.rho * p.S * std::pow(p.L, 4)));
    // The oracle against the tabulated first roots: 1.87510 without a tip mass, 1.24792 for mu = 1 (Blevins).
    CHECK(test::tip_mass_roots(0.0, 1)[0] == Approx(1.8751041).epsilon(1e-7));
    CHECK(test::tip_mass_roots(1.0, 1)[0] == Approx(1.24792).epsilon(1e-5));
    for (Method method : all_methods) {
        std::vector<double> previous(3, INFINITY);
        for (int ny : ny_steps) {
            const std::vector<double> w = bending(*generated(method, ny, p));
            for (int i = 0; i < 3; ++i) {
                const double exact = z[static_cast<std::size_t>(i)] * z[static_cast<std::size_t>(i)] * unit;
                const double error = relative(w[static_cast<std::size_t>(i)], exact);
                INFO(to_string(method) << " Ny " << ny << " mode " << i + 1 << ": " << w[static_cast<std::size_t>(i)]
                                       << " rad/s against " << exact);
                // Ritz: from above, closer as the basis grows, to within the round-off of the eigenvalues (BIM's
                // Bernstein mass matrix at Ny = 16 costs it 5e-8).
                CHECK(w[static_cast<std::size_t>(i)] >= exact * (1.0 - 1e-7));
                CHECK(error <= previous[static_cast<std::size_t>(i)] + 1e-7);
                previous[static_cast<std::size_t>(i)] = error;
                // AMM's cantilever modes carry no shear at the tip and FEM has 8 elements: mode 3 converges slowest.
                if (ny == ny_steps.back()) CHECK(error < std::array{5e-6, 1e-4, 1e-3}[static_cast<std::size_t>(i)]);
            }
        }
    }
}

TEST_CASE("with rotation and a tip mass the four methods agree as Ny grows", "[extras][tip][modes]")
{
    Parameters p;
    p.m_tip = 0.5 * p.rho * p.S * p.L;
    p.J_tip = 0.01;
    const double omega = 4.0;
    std::vector<std::vector<double>> at;  // [ny step][method] first three frequencies, flattened by mode
    for (int ny : ny_steps) {
        std::vector<double> lo(3, INFINITY), hi(3, 0.0);
        for (Method method : all_methods) {
            const std::vector<double> w = bending(*generated(method, ny, p), omega);
            for (std::size_t i = 0; i < 3; ++i) lo[i] = std::min(lo[i], w[i]), hi[i] = std::max(hi[i], w[i]);
        }
        std::vector<double> spread;
        for (std::size_t i = 0; i < 3; ++i) spread.push_back((hi[i] - lo[i]) / lo[i]);
        at.push_back(spread);
    }
    for (std::size_t i = 0; i < 3; ++i) {
        INFO("mode " << i + 1 << ": spread over the methods " << at[0][i] << ", " << at[1][i] << ", " << at[2][i]);
        CHECK(at[1][i] < at[0][i]);
        CHECK(at[2][i] < at[1][i]);
        CHECK(at[2][i] < std::array{1e-4, 2e-4, 1e-3}[i]);
    }
}

TEST_CASE("a width taper with tip ratio 1 is the uniform beam to round-off", "[extras][taper]")
{
    Parameters p;  // tip_ratio 1, no tip body, no damping: the extra terms' values are all neutral
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-0.3, 0.3);
    for (Method method : {Method::amm, Method::bim}) {
        // The paper's built-in variant against the tapered one.
        const VariantKey paper{.method = method, .nx = 0, .ny = 4, .order = Order::first, .drive = Drive::prescribed,
                               .extras = {}};
        const std::unique_ptr<Model> uniform = make_model(paper, p), tapered = generated(method, 4, p);
        const int n = uniform->nq();
        for (int trial = 0; trial < 5; ++trial) {
            std::vector<double> q(static_cast<std::size_t>(n)), qd(q);
            for (double& x : q) x = value(random);
            for (double& x : qd) x = value(random);
            HubInput u;
            u.theta_dot = 10 * value(random);
            u.theta_ddot = value(random);
            std::vector<double> M0(static_cast<std::size_t>(n * n)), M1(M0), Q0(q), Q1(q);
            uniform->mass(u, q.data(), M0.data());
            tapered->mass(u, q.data(), M1.data());
            uniform->forces(u, q.data(), qd.data(), Q0.data());
            tapered->forces(u, q.data(), qd.data(), Q1.data());
            double m_scale = 0.0, q_scale = 0.0;
            for (double x : M0) m_scale = std::max(m_scale, std::abs(x));
            for (double x : Q0) q_scale = std::max(q_scale, std::abs(x));
            for (std::size_t i = 0; i < M0.size(); ++i) CHECK(std::abs(M0[i] - M1[i]) <= 1e-13 * m_scale);
            for (std::size_t i = 0; i < Q0.size(); ++i) CHECK(std::abs(Q0[i] - Q1[i]) <= 1e-13 * q_scale);
            const Energy e0 = uniform->energy(u, q.data(), qd.data()), e1 = tapered->energy(u, q.data(), qd.data());
            CHECK(e1.kinetic() == Approx(e0.kinetic()).epsilon(1e-13));
            CHECK(e1.U == Approx(e0.U).epsilon(1e-13));
        }
    }
}

TEST_CASE("a tapered cantilever's tip deflection under its weight is the unit-load integral of M/EI",
          "[extras][taper][gravity]")
{
    Parameters p = short_beam();
    p.g = 9.81;
    p.tip_ratio = 0.5;
    // Width taper: S(x) and I(x) both scale with s(x) = 1 + c x/L, c = tip_ratio - 1, so the weight per length is
    // q0 s(x), q0 = rho S0 g, and the moment at x of the load outboard of it is
    //   M(x) = int_x^L q0 (1 + c s/L) (s - x) ds = q0 ((L - x)^2 / 2 + c/L (L^3/3 - x L^2/2 + x^3/6)).
    // The tip deflection by a unit load at the tip (moment L - x): delta = int_0^L M(x) (L - x) / (E I0 s(x)) dx.
    const double L = p.L, c = p.tip_ratio - 1.0, q0 = p.rho * p.S * p.g;
    const auto moment = [&](double x) {
        return q0 * ((L - x) * (L - x) / 2 + c / L * (L * L * L / 3 - x * L * L / 2 + x * x * x / 6));
    };
    const test::GaussRule rule = test::gauss_legendre(40);
    double delta = 0.0;
    for (std::size_t k = 0; k < rule.x.size(); ++k) {
        const double x = L / 2 * (rule.x[k] + 1.0);
        delta += L / 2 * rule.w[k] * moment(x) * (L - x) / (p.E * p.I * (1.0 + c * x / L));
    }
    // Below the uniform beam's q L^4 / (8 EI): weight and stiffness fall together, and the weight left is nearer
    // the root, where it bends the beam least.
    CHECK(delta < q0 * std::pow(L, 4) / (8 * p.E * p.I));
    for (Method method : all_methods) {
        double previous = INFINITY;
        for (int ny : {4, 8}) {
            const std::unique_ptr<Model> model = generated(method, ny, p, tip_gravity_width);
            const SteadySpin rest = held_equilibrium(*model, 0.0);
            const double tip = model->tip(rest.q.data()).uy, error = relative(-tip, delta);
            INFO(to_string(method) << " Ny " << ny << ": tip " << tip << " m against " << -delta);
            CHECK(error <= previous);
            previous = error;
        }
        CHECK(previous < 1e-4);  // AMM's uniform cantilever modes fit the tapered beam's deflection slowest
    }
    // The bending moment the fields report is the tapered section's own EI(x) times the curvature: at mid-span,
    // where EI is 3/4 of the root's, it matches the statics above (the root's EI would be a third too large).
    const std::unique_ptr<Model> model = generated(Method::bim, 8, p, tip_gravity_width);
    const SteadySpin rest = held_equilibrium(*model, 0.0);
    const BeamFields fields(model->key(), p);
    for (double x : {0.25 * L, 0.5 * L, 0.75 * L}) {
        INFO("x = " << x);
        CHECK(relative(std::abs(fields.bending_moment(rest.q.data(), x)), moment(x)) < 1e-3);
    }
}

TEST_CASE("a stiff short beam held horizontal sags by q L^4 / (8 EI), and a tip mass adds P L^3 / (3 EI)",
          "[extras][gravity]")
{
    Parameters p = short_beam();
    p.g = 9.81;
    const double q = p.rho * p.S * p.g, EI = p.E * p.I;
    for (const double m_tip : {0.0, 0.1}) {
        p.m_tip = m_tip;
        const double expected = q * std::pow(p.L, 4) / (8 * EI) + m_tip * p.g * std::pow(p.L, 3) / (3 * EI);
        for (Method method : all_methods) {
            const std::unique_ptr<Model> model = generated(method, 8, p, tip_gravity_width);
            const SteadySpin rest = held_equilibrium(*model, 0.0);
            INFO(to_string(method) << " m_tip " << m_tip);
            // At theta = 0 the weight has no component along the beam: the first-order equilibrium is linear, and
            // its error is the discretization's alone.
            // A tip load converges slowest with AMM, whose cantilever modes carry no shear at the tip.
            const double tolerance = m_tip > 0.0 && method == Method::amm ? 1e-4 : 2e-6;
            CHECK(model->tip(rest.q.data()).uy == Approx(-expected).epsilon(tolerance));
            // The modes about it: the linear equations do not see the (linear) weight, so they are the unloaded ones.
            const std::vector<double> loaded = bending(*model);
            Parameters weightless = p;
            weightless.g = 0.0;
            const std::vector<double> unloaded = bending(*generated(method, 8, weightless, tip_gravity_width));
            CHECK(loaded[0] == Approx(unloaded[0]).epsilon(1e-10));
        }
    }
    // A spin rate has no steady state under gravity.
    CHECK_THROWS_AS(steady_spin(*generated(Method::amm, 8, p, tip_gravity_width), 1.0), std::invalid_argument);
}

TEST_CASE("the tapered beam's frequencies converge across the four methods", "[extras][taper][modes]")
{
    Parameters p;
    p.tip_ratio = 0.4;
    std::vector<std::vector<double>> spread;
    std::vector<double> finest;
    for (int ny : ny_steps) {
        std::vector<double> lo(3, INFINITY), hi(3, 0.0);
        for (Method method : all_methods) {
            const std::vector<double> w = bending(*generated(method, ny, p));
            for (std::size_t i = 0; i < 3; ++i) lo[i] = std::min(lo[i], w[i]), hi[i] = std::max(hi[i], w[i]);
        }
        std::vector<double> s;
        for (std::size_t i = 0; i < 3; ++i) s.push_back((hi[i] - lo[i]) / lo[i]);
        spread.push_back(s);
        finest = lo;
    }
    for (std::size_t i = 0; i < 3; ++i) {
        INFO("mode " << i + 1 << ": spread " << spread[0][i] << ", " << spread[1][i] << ", " << spread[2][i]);
        CHECK(spread[1][i] < spread[0][i]);
        CHECK(spread[2][i] < spread[1][i]);
        CHECK(spread[2][i] < std::array{2e-5, 2e-4, 1e-3}[i]);
    }
    // A lighter tip raises the first frequency above the uniform cantilever's 1.8751^2 sqrt(EI/(m L^4)) (its root
    // section's), the classical trend of a tapered blade.
    CHECK(finest[0] > 1.87510407 * 1.87510407 * frequency_unit(p));
}

TEST_CASE("Rayleigh damping at rest gives each mode the ratio alpha/(2 omega) + beta omega/2", "[extras][damping][modes]")
{
    Parameters p;
    p.m_tip = 0.3;
    p.J_tip = 0.02;
    p.tip_ratio = 0.6;
    Parameters undamped = p;
    p.alpha = 0.15;
    p.beta = 4e-4;
    for (Method method : all_methods) {
        const std::unique_ptr<Model> model = generated(method, 8, p);
        const std::vector<double> reference = bending(*generated(method, 8, undamped));
        const std::vector<NaturalMode> modes = natural_modes(*model, steady_spin(*model, 0.0));
        REQUIRE(modes.size() == reference.size());
        for (std::size_t i = 0; i < modes.size(); ++i) {
            const double w = reference[i], zeta = p.alpha / (2 * w) + p.beta * w / 2;
            INFO(to_string(method) << " mode " << i + 1 << " at " << w << " rad/s");
            // The damping matrix alpha M + beta K is proportional: the undamped modes decouple it, each mode a
            // one-degree-of-freedom oscillator with lambda = -zeta w +- i w sqrt(1 - zeta^2).
            CHECK(modes[i].undamped_rad_s == Approx(w).epsilon(1e-8));
            CHECK(modes[i].damping_ratio == Approx(zeta).epsilon(1e-7));
            if (zeta < 1.0) {
                CHECK(modes[i].rad_s == Approx(w * std::sqrt(1 - zeta * zeta)).epsilon(1e-8));
                CHECK(modes[i].growth == Approx(-zeta * w).epsilon(1e-7));
            }
        }
    }
}

TEST_CASE("a free vibration after a torque pulse decays at the rate modes predicts", "[extras][damping][run]")
{
    Scene s = test::paper_scene(Method::amm, 0, 4, test::torque(1.0));
    s.motion.torque_time = 1.5;  // about one period of the first free-hub mode: it is excited most
    s.parameters.alpha = 0.1;
    s.parameters.beta = 2e-3;  // the higher modes die out within the first seconds
    s.solver.rtol = 1e-9;
    s.solver.atol = 1e-12;
    s.output.t_end = 40.0;
    s.output.dt_out = 0.005;
    Simulation simulation(s);
    simulation.check_error(false);
    std::vector<Row> rows;
    // Reaching t_end is what counts here: the invariant monitor may call a damped run untrustworthy while it
    // expects the Jacobi integral to stay constant.
    const RunSummary summary = simulation.run([&](const Row& r) { rows.push_back(r); });
    INFO(summary.failure);
    REQUIRE(summary.t_reached == Approx(s.output.t_end));
    const std::vector<NaturalMode> modes = natural_modes(simulation.model(), steady_spin(simulation.model(), 0.0));
    const double predicted = modes.front().growth;
    // The envelope: the tip's positive peaks after the higher modes have decayed, refined by a parabola through
    // the three samples about each; log(peak) against t is a line of slope growth.
    std::vector<double> t, log_peak;
    for (std::size_t k = 1; k + 1 < rows.size(); ++k) {
        const double a = rows[k - 1].tip_uy, b = rows[k].tip_uy, c = rows[k + 1].tip_uy;
        if (rows[k].t < 12.0 || !(b > a && b >= c && b > 0.0)) continue;
        const double d = 0.5 * (a - c) / (a - 2 * b + c);
        t.push_back(rows[k].t + d * s.output.dt_out);
        log_peak.push_back(std::log(b - 0.25 * (a - c) * d));
    }
    REQUIRE(t.size() > 10);
    double mt = 0.0, ml = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) mt += t[k], ml += log_peak[k];
    mt /= static_cast<double>(t.size()), ml /= static_cast<double>(t.size());
    double stt = 0.0, stl = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) stt += (t[k] - mt) * (t[k] - mt), stl += (t[k] - mt) * (log_peak[k] - ml);
    const double fitted = stl / stt;
    INFO("fitted decay " << fitted << " 1/s, modes " << predicted << " 1/s (first mode " << modes.front().rad_s
                         << " rad/s)");
    CHECK(predicted < 0.0);
    CHECK(fitted == Approx(predicted).epsilon(1e-3));
}

TEST_CASE("a very stiff beam on a free hub under gravity swings as the rigid pendulum", "[extras][gravity][run]")
{
    Scene s = test::paper_scene(Method::amm, 0, 4, test::torque(0.0));
    s.parameters.L = 1.0;
    s.parameters.a = 0.2;
    s.parameters.J_oh = 0.1;
    s.parameters.E *= 100;  // first bending mode near 1900 rad/s: the beam is rigid at the swing's 3 rad/s
    s.parameters.g = 9.81;
    s.output.t_end = 3.0;
    s.output.dt_out = 0.01;
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-12;
    Simulation simulation(s);
    simulation.check_error(false);
    std::vector<Row> rows;
    REQUIRE(simulation.run([&](const Row& r) { rows.push_back(r); }).completed);
    // J theta'' = -m g (a L + L^2/2) cos theta, J = J_oh + m ((a + L)^3 - a^3)/3 with m the mass per length,
    // by classical RK4 at a step of 1e-4 s (its error 1e-12 here), from theta = 0 at rest.
    const Parameters& p = s.parameters;
    const double m = p.rho * p.S, J = p.J_oh + m * (std::pow(p.a + p.L, 3) - std::pow(p.a, 3)) / 3;
    const double k = m * p.g * (p.a * p.L + p.L * p.L / 2) / J;
    const auto f = [k](double theta) { return -k * std::cos(theta); };
    double theta = 0.0, rate = 0.0, time = 0.0, worst = 0.0, lowest = 0.0;
    const double h = 1e-4;
    for (const Row& r : rows) {
        while (time < r.t - 1e-12) {
            const double step = std::min(h, r.t - time);
            const double k1 = rate, l1 = f(theta);
            const double k2 = rate + step / 2 * l1, l2 = f(theta + step / 2 * k1);
            const double k3 = rate + step / 2 * l2, l3 = f(theta + step / 2 * k2);
            const double k4 = rate + step * l3, l4 = f(theta + step * k3);
            theta += step / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
            rate += step / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
            time += step;
        }
        worst = std::max(worst, std::abs(r.theta - theta));
        lowest = std::min(lowest, theta);
    }
    INFO("largest |theta - rigid| " << worst << " rad over a swing down to " << lowest << " rad");
    CHECK(lowest < -3.0);  // the swing passes the bottom and rises on the other side
    CHECK(worst < 1e-5);
}

TEST_CASE("with gravity and neither damping nor torque, T + U (U holding the weight's) is conserved",
          "[extras][gravity][run]")
{
    Scene s = test::paper_scene(Method::amm, 0, 4, test::torque(0.0));
    s.parameters.L = 2.0;
    s.parameters.J_oh = 0.5;
    s.parameters.g = 9.81;
    s.output.t_end = 5.0;
    s.output.dt_out = 0.01;
    Simulation simulation(s);
    simulation.check_error(false);
    std::vector<Row> rows;
    REQUIRE(simulation.run([&](const Row& r) { rows.push_back(r); }).completed);
    double drift = 0.0, largest_kinetic = 0.0;
    const double e0 = rows.front().kinetic + rows.front().potential;
    for (const Row& r : rows) {
        drift = std::max(drift, std::abs(r.kinetic + r.potential - e0));
        largest_kinetic = std::max(largest_kinetic, r.kinetic);
    }
    // The beam fell from rest (T rose by joules), so only U's weight term can have paid for it.
    INFO("drift " << drift << " J against a kinetic energy of " << largest_kinetic << " J");
    CHECK(largest_kinetic > 1.0);
    CHECK(drift < 1e-7 * largest_kinetic);
}

TEST_CASE("a beam held upright buckles under its own weight at Greenhill's load - hanging, it stiffens",
          "[extras][gravity][modes]")
{
    // Greenhill: the slope t(s) of an upright cantilever, s = L - x from the free tip, buckles when
    // t'' + (q/EI) s t = 0 with t'(0) = 0 (no moment at the tip) has t(L) = 0 (clamped). By power series in
    // s (t = sum c_k s^k, c_0 = 1, c_1 = c_2 = 0, c_(k+3) = -k3 c_k / ((k+3)(k+2)), k3 = q L^3/EI at L = 1) and
    // bisection on k3: q L^3 / EI = 7.837.
    const auto slope_at_root = [](double k3) {
        std::vector<double> c(120, 0.0);
        c[0] = 1.0;
        double sum = 0.0;
        for (std::size_t k = 0; k < c.size(); ++k) {
            if (k >= 3) c[k] = -k3 * c[k - 3] / (static_cast<double>(k) * static_cast<double>(k - 1));
            sum += c[k];
        }
        return sum;
    };
    double lo = 5.0, hi = 10.0;
    for (int k = 0; k < 100; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((slope_at_root(lo) < 0.0) == (slope_at_root(mid) < 0.0) ? lo : hi) = mid;
    }
    const double greenhill = 0.5 * (lo + hi);
    CHECK(greenhill == Approx(7.837).epsilon(1e-4));
    Parameters p = short_beam();
    const double g_critical = greenhill * p.E * p.I / (p.rho * p.S * std::pow(p.L, 3));
    // Held upright (theta = pi/2), the model's first mode diverges from the g where its K loses definiteness.
    const auto divergent = [&](double g) {
        Parameters at = p;
        at.g = g;
        const std::unique_ptr<Model> model = generated(Method::fem, 16, at, tip_gravity_width);
        const std::vector<NaturalMode> modes = natural_modes(*model, held_equilibrium(*model, std::numbers::pi / 2));
        return modes.front().rad_s == 0.0 && modes.front().growth > 0.0;
    };
    double below = 0.5 * g_critical, above = 1.5 * g_critical;
    REQUIRE(!divergent(below));
    REQUIRE(divergent(above));
    for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (below + above);
        (divergent(mid) ? above : below) = mid;
    }
    INFO("the model buckles at g = " << below << " m/s^2, Greenhill's load at " << g_critical);
    // A Ritz model buckles from above (FEM at Ny = 16: 1.3e-5 above). g here is some 2000 of Earth's: what
    // buckles a 1 m beam of this section is the load q L^3 / EI alone.
    CHECK(below >= g_critical * (1.0 - 1e-9));
    CHECK(below == Approx(g_critical).epsilon(1e-4));
    // Hanging (theta = -pi/2) the weight pulls the beam straight: its frequencies rise above the horizontal
    // beam's, which the weight does not change (first order), and the upright beam's fall below them.
    p.g = 0.5 * g_critical;
    const std::unique_ptr<Model> model = generated(Method::fem, 16, p, tip_gravity_width);
    const double hanging = natural_modes(*model, held_equilibrium(*model, -std::numbers::pi / 2)).front().rad_s;
    const double level = natural_modes(*model, held_equilibrium(*model, 0.0)).front().rad_s;
    const double upright = natural_modes(*model, held_equilibrium(*model, std::numbers::pi / 2)).front().rad_s;
    CHECK(hanging > level);
    CHECK(upright < level);
    // Upright or hanging, the straight beam is the equilibrium: no sideways sag.
    CHECK(std::abs(model->tip(held_equilibrium(*model, std::numbers::pi / 2).q.data()).uy) < 1e-12);
}

TEST_CASE("under gravity the state-space matrices are those of the nonlinear equations about the held sag",
          "[extras][gravity][linearize]")
{
    Parameters p = short_beam();
    p.g = 9.81;
    p.J_oh = 0.2;
    const double held = 0.4;  // a tilted beam: the weight has components along and across it
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        Extras gravity_only;
        gravity_only.gravity = true;
        const std::unique_ptr<Model> model =
            make_model(extras_key(Method::amm, 4, drive, gravity_only), p, ModelSource::generated);
        const SteadySpin s = held_equilibrium(*model, held);
        const int n = model->nq();
        // The equilibrium: no acceleration anywhere, a free hub's included (its holding torque).
        std::vector<double> Q(static_cast<std::size_t>(n));
        model->forces(s.u, s.q.data(), s.qd.data(), Q.data());
        for (double x : Q) CHECK(std::abs(x) < 1e-9);
        // A's rows of accelerations against central differences of M^-1 Q in every state (theta of a prescribed
        // hub through the drive's angle).
        const StateSpace ss = state_space(*model, s);
        const int m = static_cast<int>(ss.states.size()) / 2;
        const bool torque = drive == Drive::torque;
        const auto accelerations = [&](int state, double h) {
            HubInput u = s.u;
            std::vector<double> q = s.q, qd = s.qd;
            const int c = state % m, index = torque ? c : c - 1;
            if (state < m) (index < 0 ? u.theta : q[static_cast<std::size_t>(index)]) += h;
            else (index < 0 ? u.theta_dot : qd[static_cast<std::size_t>(index)]) += h;
            Eigen::MatrixXd M(n, n);
            std::vector<double> Mrow(static_cast<std::size_t>(n * n)), F(static_cast<std::size_t>(n));
            model->mass(u, q.data(), Mrow.data());
            model->forces(u, q.data(), qd.data(), F.data());
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) M(i, j) = Mrow[static_cast<std::size_t>(i * n + j)];
            return Eigen::VectorXd(M.llt().solve(Eigen::Map<Eigen::VectorXd>(F.data(), n)));
        };
        for (int state = 0; state < 2 * m; ++state) {
            const double h = 1e-6;
            const Eigen::VectorXd column = (accelerations(state, h) - accelerations(state, -h)) / (2 * h);
            for (int r = torque ? 0 : 1; r < m; ++r) {
                const int index = torque ? r : r - 1;
                INFO(to_string(drive) << " row " << ss.states[static_cast<std::size_t>(m + r)] << ", column "
                                      << ss.states[static_cast<std::size_t>(state)]);
                CHECK(ss.A(m + r, state) == Approx(column[index]).margin(1e-5 * std::max(1.0, column.cwiseAbs().maxCoeff())));
            }
        }
    }
}
