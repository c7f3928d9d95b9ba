// The paper's load cases integrated end to end: the spin-up's steady frequency and amplitude agree across
// the four discretizations and with the model's rotating-beam frequency; BSIM's two bases give one
// response; under hub torque the angular momentum equals the torque impulse (MODEL.md sections 6-7).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "simulate.hpp"

using namespace hubbeam;

namespace {

Scene paper_scene(Method method, int nx, int ny, Motion motion)
{
    Scene s;
    s.path = "test";
    s.motion = motion;
    s.variant.method = method;
    s.variant.nx = nx;
    s.variant.ny = ny;
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-12;
    return s;
}

Motion spin_up(double omega0) { return {Motion::Kind::spin_up, omega0, 15.0, 0.0, 10.0}; }
Motion torque(double tau0) { return {Motion::Kind::torque, 0.0, 15.0, tau0, 10.0}; }

std::vector<Row> run(const Scene& s)
{
    std::vector<Row> rows;
    const RunSummary summary = simulate(s, [&](const Row& r) { rows.push_back(r); });
    INFO(summary.failure);
    REQUIRE(summary.completed);
    return rows;
}

/// Frequency (Hz) and half peak-to-peak amplitude of tip_uy after t0, from upward zero crossings of the
/// signal about its mean, located by linear interpolation.
struct Oscillation {
    double frequency, amplitude;
};
Oscillation steady_oscillation(const std::vector<Row>& rows, double t0)
{
    double mean = 0.0, lo = 1e300, hi = -1e300;
    int count = 0;
    for (const Row& r : rows)
        if (r.t >= t0) {
            mean += r.tip_uy;
            lo = std::min(lo, r.tip_uy);
            hi = std::max(hi, r.tip_uy);
            ++count;
        }
    mean /= count;
    std::vector<double> crossings;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const double a = rows[i - 1].tip_uy - mean, b = rows[i].tip_uy - mean;
        if (rows[i - 1].t >= t0 && a < 0.0 && b >= 0.0)
            crossings.push_back(rows[i - 1].t + (rows[i].t - rows[i - 1].t) * a / (a - b));
    }
    REQUIRE(crossings.size() >= 5);
    return {(crossings.size() - 1) / (crossings.back() - crossings.front()), (hi - lo) / 2.0};
}

}  // namespace

TEST_CASE("spin-up to 4 rad/s: every method oscillates at the rotating beam's frequency", "[dynamics]")
{
    // Paper Table 1: about 0.532 Hz for all four methods (MODEL.md section 6); the in-plane first-order
    // frequency at 4 rad/s follows from the rotating-cantilever frequency (section 7).
    for (int nx : {0, 4}) {
        std::vector<Oscillation> found;
        for (Method m : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
            Scene s = paper_scene(m, nx, 4, spin_up(4.0));
            s.output.t_end = 45.0;
            s.output.dt_out = 0.005;
            const Oscillation o = steady_oscillation(run(s), 20.0);
            INFO(to_string(m) << " nx=" << nx << ": " << o.frequency << " Hz, amplitude " << o.amplitude << " m");
            CHECK(std::abs(o.frequency / 0.532 - 1.0) < 0.01);
            found.push_back(o);
        }
        for (const Oscillation& o : found) {
            CHECK(std::abs(o.frequency / found[0].frequency - 1.0) < 0.01);
            CHECK(std::abs(o.amplitude / found[0].amplitude - 1.0) < 0.01);
        }
    }
}

TEST_CASE("BSIM: the paper's basis and the open-knot basis give the same response", "[dynamics]")
{
    for (int ny : {4, 6}) {
        Scene paper = paper_scene(Method::bsim, 0, ny, spin_up(4.0));
        paper.output.t_end = 25.0;
        Scene open = paper;
        open.variant.spline = SplineBasis::open;
        const std::vector<Row> a = run(paper), b = run(open);
        REQUIRE(a.size() == b.size());
        double diff = 0.0, peak = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            diff = std::max(diff, std::abs(a[i].tip_uy - b[i].tip_uy));
            peak = std::max(peak, std::abs(a[i].tip_uy));
        }
        INFO("ny=" << ny << ": max difference " << diff << " m of peak " << peak << " m");
        // Same spline space, so the same exact solution; what remains is integration error at rtol 1e-10.
        CHECK(diff < 1e-6 * peak);
    }
}

TEST_CASE("hub torque: angular momentum equals the torque impulse", "[dynamics]")
{
    // d/dt (dT/dtheta_dot) = tau since theta is cyclic: the momentum is the torque's integral, and it stays
    // at zero after the full sine period.
    for (double tau0 : {1.0, 10.0})
        for (Method m : {Method::amm, Method::fem, Method::bim, Method::bsim})
            for (int nx : {0, 4}) {
                Scene s = paper_scene(m, nx, 4, torque(tau0));
                s.output.t_end = 20.0;
                s.output.dt_out = 0.05;
                s.solver.rtol = 1e-11;
                s.solver.atol = 1e-13;
                const std::vector<Row> rows = run(s);
                const double largest = tau0 * s.motion.torque_time / std::numbers::pi;  // impulse at T_t / 2
                double worst = 0.0, drift = 0.0, after = 0.0;
                bool have_after = false;
                for (const Row& r : rows) {
                    worst = std::max(worst, std::abs(r.momentum - s.motion.torque_impulse(r.t)));
                    if (r.t >= s.motion.torque_time) {
                        if (!have_after) after = r.momentum, have_after = true;
                        drift = std::max(drift, std::abs(r.momentum - after));
                    }
                }
                INFO(to_string(m) << " nx=" << nx << " tau0=" << tau0 << ": |h - impulse| <= " << worst
                                  << ", drift after the torque " << drift);
                CHECK(worst <= 1e-8 * largest);
                CHECK(drift <= 1e-8 * largest);
            }
}

TEST_CASE("steady drive: the Jacobi integral is constant", "[dynamics]")
{
    // MODEL.md section 7: at constant prescribed spin T2 - T0 + U is conserved; with theta a coordinate and
    // no torque, T + U is. Its drift is measured against the energy of the beam's vibration (the largest
    // strain energy U in the window), the part of the integral that the flexible motion exchanges.
    struct Case {
        Method method;
        int nx;
        Motion motion;
        double t_steady;
    };
    for (const Case& c : {Case{Method::amm, 4, spin_up(4.0), 15.0}, Case{Method::bsim, 0, spin_up(10.0), 15.0},
                          Case{Method::fem, 4, torque(10.0), 10.0}, Case{Method::bim, 0, torque(1.0), 10.0}}) {
        Scene s = paper_scene(c.method, c.nx, 4, c.motion);
        s.output.t_end = 30.0;
        s.output.dt_out = 0.05;
        const std::vector<Row> rows = run(s);
        double j0 = 0.0, drift = 0.0, vibration = 0.0;
        bool first = true;
        for (const Row& r : rows) {
            if (r.t < c.t_steady) continue;
            if (first) j0 = r.jacobi, first = false;
            drift = std::max(drift, std::abs(r.jacobi - j0));
            vibration = std::max(vibration, r.potential);
        }
        INFO(to_string(c.method) << " nx=" << c.nx << ": drift " << drift << " J, vibration energy " << vibration);
        CHECK(drift <= 1e-6 * vibration);
    }
}
