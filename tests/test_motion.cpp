// The drive profiles of runtime/include/hubbeam/motion.hpp on their own (docs/model.md section 6, paper eqs. 58-59):
// each profile's rate, angle and impulse are the integrals of its acceleration, rate and torque, checked against an
// independent composite Gauss-Legendre quadrature, and the end values section 6 states.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "gauss_legendre.hpp"
#include "motion.hpp"

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
    for (const Motion m : {spin_up(4.0, 15.0), spin_up(10.0, 15.0), spin_up(2.5, 7.0)}) {
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
    for (const Motion m : {torque(1.0, 10.0), torque(10.0, 10.0), torque(-3.0, 4.0)}) {
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
