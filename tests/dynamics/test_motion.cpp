// The drive profiles of runtime/include/hubbeam/motion.hpp on their own (docs/model.md section 6, paper eqs. 58-59):
// each profile's rate, angle and impulse are the integrals of its acceleration, rate and torque, checked against an
// independent composite Gauss-Legendre quadrature, and the end values section 6 states. Then the held hub, the
// initial angle theta0, and the tables: a spline's derivatives converge to those of the smooth theta(t) it samples,
// a linear torque table is its rows' straight lines, and a table of the paper's spin-up drives the beam as eq. 58.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <memory>
#include <numbers>
#include <vector>

#include <hubbeam/motion.hpp>
#include <hubbeam/scene.hpp>
#include "gauss_legendre.hpp"
#include "runs.hpp"

using namespace hubbeam;

namespace {

constexpr double pi = std::numbers::pi;

/// int_a^b f by composite 10-point Gauss-Legendre on `panels` equal panels (0 for an empty interval).
double integrate(const std::function<double(double)>& f, double a, double b, int panels = 40)
{
    static const test::GaussRule rule = test::gauss_legendre(10);
    if (b <= a) return 0.0;
    const double h = (b - a) / panels;
    double sum = 0.0;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h;
        for (std::size_t k = 0; k < rule.x.size(); ++k) sum += rule.w[k] * f(mid + 0.5 * h * rule.x[k]);
    }
    return 0.5 * h * sum;
}

/// int_0^t f, split at the drive's breakpoint tb where f changes formula (it is smooth on either side).
double integrate_from_rest(const std::function<double(double)>& f, double t, double tb)
{
    return integrate(f, 0.0, std::min(t, tb)) + integrate(f, tb, t);
}

Motion spin_up(double omega0, double spin_time) { return {Motion::Kind::spin_up, omega0, spin_time, 0.0, 10.0}; }
Motion torque(double tau0, double torque_time) { return {Motion::Kind::torque, 0.0, 15.0, tau0, torque_time}; }

}  // namespace

TEST_CASE("quadrature of the test is exact for polynomials and accurate for the drive's trigonometry", "[motion]")
{
    // The reference below is only as good as this rule: 10 points integrate degree 19 exactly.
    CHECK(integrate([](double x) { return std::pow(x, 19) + x; }, 0.0, 1.0, 1) ==
          Approx(1.0 / 20 + 0.5).epsilon(1e-14));
    CHECK(integrate([](double x) { return std::sin(x); }, 0.0, pi) == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("spin-up: rate and angle are the integrals of acceleration and rate (eq. 58)", "[motion]")
{
    for (const Motion& m : {spin_up(4.0, 15.0), spin_up(10.0, 15.0), spin_up(2.5, 7.0)}) {
        const double W = m.omega0, Ts = m.spin_time;
        INFO("Omega0 = " << W << ", T_s = " << Ts);
        const auto theta_ddot = [&](double t) { return m.at(t).theta_ddot; };
        const auto theta_dot = [&](double t) { return m.at(t).theta_dot; };
        for (double f : {0.013, 0.1, 0.25, 0.5, 0.61, 0.75, 0.999, 1.0, 1.02, 1.5, 3.0}) {
            const double t = f * Ts;
            INFO("t = " << t);
            // Scales of the quantities (their values at T_s), so that values near t = 0 are not held to 1e-10 of
            // almost nothing.
            CHECK(m.at(t).theta_dot ==
                  Approx(integrate_from_rest(theta_ddot, t, Ts)).epsilon(1e-10).margin(1e-13 * W));
            CHECK(m.theta(t) == Approx(integrate_from_rest(theta_dot, t, Ts)).epsilon(1e-10).margin(1e-13 * W * Ts));
            CHECK(m.at(t).tau == 0.0);
            CHECK(m.torque_impulse(t) == 0.0);
        }
        // End values at T_s: at rest in acceleration, at full rate, turned by Omega0 T_s / 2.
        CHECK(m.at(0.0).theta_dot == 0.0);
        CHECK(std::abs(m.at(0.0).theta_ddot) <= 1e-15 * W / Ts);
        CHECK(m.theta(0.0) == 0.0);
        CHECK(m.at(Ts).theta_dot == Approx(W).epsilon(1e-14));
        CHECK(std::abs(m.at(Ts).theta_ddot) <= 1e-14 * W / Ts);
        CHECK(m.theta(Ts) == Approx(W * Ts / 2.0).epsilon(1e-14));
        // The acceleration peaks at 2 Omega0 / T_s at T_s / 2.
        CHECK(m.at(Ts / 2.0).theta_ddot == Approx(2.0 * W / Ts).epsilon(1e-14));
        // After T_s: constant rate, no acceleration, angle growing at Omega0 from Omega0 T_s / 2.
        for (double t : {Ts * (1.0 + 1e-9), Ts + 0.3, 2.0 * Ts, 100.0 * Ts}) {
            INFO("t = " << t);
            CHECK(m.at(t).theta_dot == W);
            CHECK(m.at(t).theta_ddot == 0.0);
            CHECK(m.theta(t) == Approx(W * Ts / 2.0 + W * (t - Ts)).epsilon(1e-14));
        }
        CHECK(m.drive() == Drive::prescribed);
        CHECK(m.breakpoints() == std::vector<double>{Ts});
    }
}

TEST_CASE("hub torque: the impulse is the integral of the torque (eq. 59)", "[motion]")
{
    for (const Motion& m : {torque(1.0, 10.0), torque(10.0, 10.0), torque(-3.0, 4.0)}) {
        const double tau0 = m.tau0, Tt = m.torque_time;
        INFO("tau0 = " << tau0 << ", T_t = " << Tt);
        const auto tau = [&](double t) { return m.at(t).tau; };
        const double peak = tau0 * Tt / pi;  // the impulse at T_t / 2
        for (double f : {0.013, 0.1, 0.25, 0.5, 0.61, 0.75, 0.999, 1.0, 1.02, 1.5, 3.0}) {
            const double t = f * Tt;
            INFO("t = " << t);
            CHECK(m.torque_impulse(t) ==
                  Approx(integrate_from_rest(tau, t, Tt)).epsilon(1e-10).margin(1e-13 * std::abs(peak)));
            // A torque drive prescribes no rotation.
            CHECK(m.at(t).theta_dot == 0.0);
            CHECK(m.at(t).theta_ddot == 0.0);
            CHECK(m.theta(t) == 0.0);
        }
        CHECK(m.at(0.0).tau == 0.0);
        CHECK(m.torque_impulse(0.0) == 0.0);
        CHECK(m.at(Tt / 4.0).tau == Approx(tau0).epsilon(1e-14));
        CHECK(m.torque_impulse(Tt / 2.0) == Approx(peak).epsilon(1e-14));
        // Back to zero at T_t (a full sine period) and after it; no torque after T_t.
        CHECK(std::abs(m.torque_impulse(Tt)) <= 1e-14 * std::abs(peak));
        for (double t : {Tt * (1.0 + 1e-9), Tt + 0.3, 2.0 * Tt, 100.0 * Tt}) {
            INFO("t = " << t);
            CHECK(m.at(t).tau == 0.0);
            CHECK(std::abs(m.torque_impulse(t)) <= 1e-14 * std::abs(peak));
        }
        CHECK(m.drive() == Drive::torque);
        CHECK(m.breakpoints() == std::vector<double>{Tt});
    }
}

namespace {

/// A smooth angle with zero acceleration at t = 0 and t = T (the natural spline's end conditions), its first three
/// derivatives by hand.
struct SmoothAngle {
    double T = 10.0, A = 2.0, B = 0.3, C = 0.7;
    std::array<double, 4> at(double t) const
    {
        const double w1 = pi / T, w3 = 3.0 * pi / T;
        return {A * std::sin(w1 * t) + B * std::sin(w3 * t) + C * t,
                A * w1 * std::cos(w1 * t) + B * w3 * std::cos(w3 * t) + C,
                -A * w1 * w1 * std::sin(w1 * t) - B * w3 * w3 * std::sin(w3 * t),
                -A * w1 * w1 * w1 * std::cos(w1 * t) - B * w3 * w3 * w3 * std::cos(w3 * t)};
    }
};

/// f sampled at `rows` evenly spaced times from t0 to t1.
std::shared_ptr<const DriveTable> sampled(const std::function<double(double)>& f, double t0, double t1, int rows,
                                          DriveTable::Interpolation interpolation)
{
    std::vector<double> t(static_cast<std::size_t>(rows)), v(t.size());
    for (int i = 0; i < rows; ++i) {
        t[static_cast<std::size_t>(i)] = t0 + (t1 - t0) * i / (rows - 1);
        v[static_cast<std::size_t>(i)] = f(t[static_cast<std::size_t>(i)]);
    }
    return std::make_shared<const DriveTable>(std::move(t), std::move(v), interpolation);
}

Motion table_motion(std::shared_ptr<const DriveTable> table, Motion::Kind kind = Motion::Kind::table)
{
    Motion m;
    m.kind = kind;
    m.table = std::move(table);
    return m;
}

}  // namespace

TEST_CASE("a table's cubic spline: angle, rate, acceleration and its rate converge to the sampled theta(t)'s",
          "[motion]")
{
    // Interpolation theory for a cubic spline whose end conditions hold for the function: errors O(h^4), O(h^3),
    // O(h^2), O(h) in the value and its first three derivatives. Each doubling of the rows must cut each error by
    // nearly 2^order (three quarters of it, for the pre-asymptotic rows).
    const SmoothAngle f;
    const std::array<int, 4> order = {4, 3, 2, 1};
    std::array<double, 4> previous{};
    for (int rows : {21, 41, 81, 161}) {
        const Motion m = table_motion(sampled([&](double t) { return f.at(t)[0]; }, 0.0, f.T, rows,
                                              DriveTable::Interpolation::cubic_spline));
        std::array<double, 4> error{};
        for (int k = 0; k <= 2000; ++k) {
            const double t = f.T * k / 2000.0;
            const std::array<double, 4> exact = f.at(t);
            const HubInput u = m.at(t), r = m.rate(t);
            const std::array<double, 4> got = {u.theta, u.theta_dot, u.theta_ddot, r.theta_ddot};
            CHECK(r.theta_dot == u.theta_ddot);  // the rate of theta_dot is theta_ddot itself
            for (std::size_t d = 0; d < 4; ++d) error[d] = std::max(error[d], std::abs(got[d] - exact[d]));
        }
        INFO(rows << " rows: errors " << error[0] << ", " << error[1] << ", " << error[2] << ", " << error[3]);
        if (rows > 21)
            for (std::size_t d = 0; d < 4; ++d) CHECK(previous[d] / error[d] > 0.75 * std::pow(2.0, order[d]));
        previous = error;
    }
    // And they are small at 161 rows, against the derivatives' own sizes (about 2, 0.9, 0.4, 0.9 here).
    CHECK(previous[0] < 1e-7);
    CHECK(previous[1] < 1e-5);
    CHECK(previous[2] < 1e-3);
    CHECK(previous[3] < 5e-2);
}

TEST_CASE("a table's acceleration rate is the derivative of its acceleration, piece by piece", "[motion]")
{
    // Uneven rows: rate() must pick the piece at(t) evaluates. Central differences of theta_ddot (linear on each
    // piece, so exact up to round-off) inside each piece are the third derivative.
    std::vector<double> t = {0.0, 0.3, 1.0, 1.2, 2.5, 2.6, 4.0}, v;
    for (double x : t) v.push_back(std::sin(x) + 0.1 * x * x * x);
    const Motion m = table_motion(std::make_shared<const DriveTable>(t, v, DriveTable::Interpolation::cubic_spline));
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        for (double f : {0.1, 0.5, 0.9}) {
            const double x = t[i] + f * (t[i + 1] - t[i]), h = 1e-3 * (t[i + 1] - t[i]);
            INFO("piece " << i << ", t = " << x);
            const double fd = (m.at(x + h).theta_ddot - m.at(x - h).theta_ddot) / (2.0 * h);
            CHECK(m.rate(x).theta_ddot == Approx(fd).epsilon(1e-6).margin(1e-9));
            const double fd1 = (m.at(x + h).theta_dot - m.at(x - h).theta_dot) / (2.0 * h);
            CHECK(m.at(x).theta_ddot == Approx(fd1).epsilon(1e-5).margin(1e-8));
        }
    }
    // The rows themselves, and the natural spline's ends: no acceleration at the first and last rows.
    for (std::size_t i = 0; i < t.size(); ++i) CHECK(m.theta(t[i]) == Approx(v[i]).epsilon(1e-14).margin(1e-15));
    CHECK(std::abs(m.at(0.0).theta_ddot) < 1e-12);
    CHECK(std::abs(m.at(4.0).theta_ddot) < 1e-12);
    // A C2 spline is smooth across its rows: only its end is a breakpoint.
    CHECK(m.breakpoints() == std::vector<double>{4.0});
    CHECK(m.drive() == Drive::prescribed);
    // Just past an end (a finite-difference Jacobian's offsets), the end piece continues: no jump.
    const HubInput end = m.at(4.0), past = m.at(4.0 + 1e-9);
    CHECK(past.theta == Approx(end.theta + 1e-9 * end.theta_dot).epsilon(1e-15));
    CHECK(past.theta_dot == Approx(end.theta_dot + 1e-9 * end.theta_ddot).epsilon(1e-15));
    CHECK(past.theta_ddot == Approx(end.theta_ddot + 1e-9 * m.rate(4.0).theta_ddot).margin(1e-15));
}

TEST_CASE("a torque table is linear between its rows, each row a breakpoint - its impulse the trapezoids", "[motion]")
{
    const std::vector<double> t = {0.0, 1.0, 1.5, 3.0, 4.0}, tau = {0.0, 2.0, 2.0, -1.0, 0.0};
    Motion m = table_motion(std::make_shared<const DriveTable>(t, tau, DriveTable::Interpolation::linear),
                            Motion::Kind::torque_table);
    CHECK(m.drive() == Drive::torque);
    CHECK(m.breakpoints() == t);
    double impulse = 0.0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double slope = (tau[i + 1] - tau[i]) / (t[i + 1] - t[i]);
        for (double f : {0.0, 0.25, 0.5, 0.9}) {
            const double x = t[i] + f * (t[i + 1] - t[i]);
            INFO("t = " << x);
            CHECK(m.at(x).tau == Approx(tau[i] + f * (tau[i + 1] - tau[i])).margin(1e-14));
            CHECK(m.rate(x).tau == Approx(slope).margin(1e-14));
            CHECK(m.torque_impulse(x) ==
                  Approx(impulse + (x - t[i]) * (tau[i] + 0.5 * f * (tau[i + 1] - tau[i]))).margin(1e-14));
            CHECK(m.at(x).theta_dot == 0.0);  // a free hub: nothing prescribed
            CHECK(m.theta(x) == 0.0);
        }
        impulse += 0.5 * (tau[i] + tau[i + 1]) * (t[i + 1] - t[i]);
    }
    CHECK(m.torque_impulse(4.0) == Approx(impulse).epsilon(1e-14));
    m.theta0 = 0.4;
    CHECK(m.initial_theta() == 0.4);
}

TEST_CASE("a held hub: a fixed angle, no rate, no acceleration, no breakpoint", "[motion]")
{
    Motion m;
    m.kind = Motion::Kind::held;
    m.angle = -0.7;
    m.omega0 = 4.0;  // another kind's parameters are not used
    m.tau0 = 3.0;
    CHECK(m.drive() == Drive::prescribed);
    CHECK(m.breakpoints().empty());
    CHECK(m.initial_theta() == -0.7);
    for (double t : {0.0, 0.5, 15.0, 1e6}) {
        const HubInput u = m.at(t), r = m.rate(t);
        CHECK(u.theta == -0.7);
        CHECK(m.theta(t) == -0.7);
        CHECK(u.theta_dot == 0.0);
        CHECK(u.theta_ddot == 0.0);
        CHECK(u.tau == 0.0);
        CHECK(r.theta_dot == 0.0);
        CHECK(r.theta_ddot == 0.0);
        CHECK(r.tau == 0.0);
    }
}

TEST_CASE("theta0 turns the prescribed angle and starts the free hub there, and changes nothing else", "[motion]")
{
    for (const Motion& plain : {spin_up(4.0, 15.0), torque(2.0, 10.0),
                               table_motion(sampled([](double t) { return 0.1 * t * t; }, 0.0, 5.0, 11,
                                                    DriveTable::Interpolation::cubic_spline))}) {
        Motion turned = plain;
        turned.theta0 = 1.25;
        const bool prescribed = plain.drive() == Drive::prescribed;
        CHECK(turned.initial_theta() == Approx(plain.initial_theta() + 1.25).epsilon(1e-15));
        for (double t : {0.0, 0.3, 2.0, 4.9}) {
            INFO("t = " << t);
            const HubInput a = plain.at(t), b = turned.at(t);
            // The gravity kernels read the angle from HubInput::theta: it must carry theta0.
            CHECK(b.theta == Approx(a.theta + (prescribed ? 1.25 : 0.0)).epsilon(1e-15));
            CHECK(turned.theta(t) == Approx(plain.theta(t) + (prescribed ? 1.25 : 0.0)).epsilon(1e-15));
            CHECK(b.theta_dot == a.theta_dot);
            CHECK(b.theta_ddot == a.theta_ddot);
            CHECK(b.tau == a.tau);
        }
    }
}

TEST_CASE("one table evaluated from several threads at once gives what one thread does", "[motion]")
{
    // A sweep runs copies of a scene on threads; the copies share the table (no lookup state may be shared).
    const Motion m = table_motion(sampled([](double t) { return std::sin(t); }, 0.0, 20.0, 400,
                                          DriveTable::Interpolation::cubic_spline));
    const auto sum = [m](int seed) {
        double s = 0.0;
        for (int k = 0; k < 200000; ++k) {
            const double t = std::fmod(0.618033988749895 * (k + seed * 7919), 20.0);
            const HubInput u = m.at(t);
            s += u.theta + u.theta_dot + u.theta_ddot + m.rate(t).theta_ddot;
        }
        return s;
    };
    std::vector<double> serial;
    for (int i = 0; i < 4; ++i) serial.push_back(sum(i));
    std::vector<std::future<double>> parallel;
    for (int i = 0; i < 4; ++i) parallel.push_back(std::async(std::launch::async, sum, i));
    for (int i = 0; i < 4; ++i) CHECK(parallel[static_cast<std::size_t>(i)].get() == serial[static_cast<std::size_t>(i)]);
}

TEST_CASE("a table sampled from the paper's spin-up drives the beam as eq. 58 does, closer as rows are added",
          "[motion][dynamics]")
{
    // The tip is driven by theta_ddot; a cubic spline's acceleration is within (3/8) h^2 max|d^4 theta/dt^4| of
    // the sampled one's, which for eq. 58 is (3/8) h^2 (2 pi/T_s)^2 Omega0/T_s, against its peak 2 Omega0/T_s: a
    // relative error (3/16) (2 pi h/T_s)^2. The tip's error relative to its peak is held to that, and must fall
    // as h^2 when the rows double.
    const Motion exact = spin_up(4.0, 15.0);
    Scene reference = test::paper_scene(Method::amm, 0, 4, exact);
    reference.output.t_end = 30.0;
    reference.output.dt_out = 0.05;
    const std::vector<Row> want = test::run(reference);
    double peak = 0.0;
    for (const Row& r : want) peak = std::max(peak, std::abs(r.tip_uy));
    double previous = 0.0;
    for (double h : {0.5, 0.25}) {
        Scene s = reference;
        s.motion = table_motion(sampled([&](double t) { return exact.theta(t); }, 0.0, 30.0,
                                        static_cast<int>(30.0 / h) + 1, DriveTable::Interpolation::cubic_spline));
        const std::vector<Row> got = test::run(s);
        REQUIRE(got.size() == want.size());
        double error = 0.0, rate_error = 0.0;
        for (std::size_t i = 0; i < got.size(); ++i) {
            error = std::max(error, std::abs(got[i].tip_uy - want[i].tip_uy));
            rate_error = std::max(rate_error, std::abs(got[i].theta_dot - want[i].theta_dot));
        }
        const double bound = 3.0 / 16.0 * std::pow(2.0 * pi * h / 15.0, 2);
        INFO("h = " << h << ": tip error " << error << " of peak " << peak << ", bound " << bound * peak
                    << "; rate error " << rate_error);
        CHECK(error < bound * peak);
        CHECK(rate_error < bound * 4.0);
        if (previous > 0.0) CHECK(previous / error > 3.0);
        previous = error;
    }
}

TEST_CASE("a torque table drives the free hub: its momentum is the table's impulse, and theta0 is where it starts",
          "[motion][dynamics]")
{
    // theta is cyclic without gravity: the hub's angular momentum is the integral of the applied torque (the
    // trapezoids of the rows), whatever the beam does, and starting the hub elsewhere only turns the whole run.
    const std::vector<double> t = {0.0, 1.0, 1.05, 4.0, 6.0, 6.02, 12.0}, tau = {0.0, 5.0, -2.0, -2.0, 3.0, 0.0, 0.0};
    Motion m = table_motion(std::make_shared<const DriveTable>(t, tau, DriveTable::Interpolation::linear),
                            Motion::Kind::torque_table);
    Scene s = test::paper_scene(Method::amm, 0, 4, m);
    s.output.t_end = 12.0;
    s.output.dt_out = 0.05;
    const std::vector<Row> plain = test::run(s);
    s.motion.theta0 = 0.75;
    const std::vector<Row> turned = test::run(s);
    REQUIRE(plain.size() == turned.size());
    double largest = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < plain.size(); ++i) {
        const Row& r = plain[i];
        // The impulse by hand: the trapezoids up to r.t.
        double impulse = 0.0;
        for (std::size_t k = 0; k + 1 < t.size() && t[k] < r.t; ++k) {
            const double end = std::min(r.t, t[k + 1]);
            const double tau_end = tau[k] + (tau[k + 1] - tau[k]) * (end - t[k]) / (t[k + 1] - t[k]);
            impulse += 0.5 * (tau[k] + tau_end) * (end - t[k]);
        }
        largest = std::max(largest, std::abs(impulse));
        worst = std::max(worst, std::abs(r.momentum - impulse));
        INFO("t = " << r.t);
        CHECK(turned[i].theta == Approx(r.theta + 0.75).epsilon(1e-12));
        CHECK(turned[i].tip_uy == Approx(r.tip_uy).epsilon(1e-9).margin(1e-12));
    }
    INFO("|h - impulse| <= " << worst << " of " << largest);
    CHECK(worst <= 1e-7 * largest);
    CHECK(plain.front().theta == 0.0);
    CHECK(turned.front().theta == 0.75);
}

TEST_CASE("cases/held_gravity.toml settles at the cantilever's static deflection q L^4 / (8 E I), on the side the "
          "held angle puts it",
          "[motion][dynamics]")
{
    // Gravity along -j: held at theta = 0 the tip hangs down by q L^4 / (8 E I), q = rho S g; held at theta = pi
    // the beam points the other way and its own transverse axis is -j, so the same deflection reads positive.
    // The weight has no axial part at either angle. The kernels take the angle from HubInput::theta.
    for (const double angle : {0.0, pi}) {
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", angle);
        const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/held_gravity.toml", {{"motion.angle", text}});
        REQUIRE(s.motion.angle == angle);
        const Parameters& p = s.parameters;
        const double q = p.rho * p.S * p.g, expected = q * std::pow(p.L, 4) / (8.0 * p.E * p.I);
        const std::vector<Row> rows = test::run(s);
        INFO("angle " << angle << ": tip " << rows.back().tip_uy << ", expected " << expected);
        CHECK(rows.back().tip_uy == Approx(std::cos(angle) < 0.0 ? expected : -expected).epsilon(1e-6));
        for (const Row& r : rows) {
            CHECK(r.theta == angle);
            CHECK(r.theta_dot == 0.0);
        }
    }
}
