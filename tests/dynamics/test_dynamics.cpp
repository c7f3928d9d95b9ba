// The paper's load cases integrated end to end: the spin-up's steady frequency and amplitude agree across
// the four discretizations and with the model's rotating-beam frequency; BSIM's two bases give one
// response; under hub torque the angular momentum equals the torque impulse (docs/model.md sections 6-7).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "oscillation.hpp"
#include "runs.hpp"

using namespace hubbeam;
using test::paper_scene;
using test::run;
using test::spin_up;
using test::torque;

namespace {

/// The steady oscillation of tip_uy after t0 (oscillation.hpp), which must have at least five periods.
Oscillation steady(const std::vector<Row>& rows, double t0)
{
    const Oscillation o = steady_oscillation(rows, t0);
    REQUIRE(o.crossings >= 5);
    return o;
}

}  // namespace

TEST_CASE("spin-up to 4 rad/s: every method oscillates at the rotating beam's frequency", "[dynamics]")
{
    // Paper Table 1: about 0.532 Hz for all four methods (docs/model.md section 6); the in-plane first-order
    // frequency at 4 rad/s follows from the rotating-cantilever frequency (section 7).
    for (int nx : {0, 4}) {
        std::vector<Oscillation> found;
        for (Method m : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
            Scene s = paper_scene(m, nx, 4, spin_up(4.0));
            s.output.t_end = 45.0;
            s.output.dt_out = 0.005;
            const Oscillation o = steady(run(s), 20.0);
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
    // docs/model.md section 7: at constant prescribed spin T2 - T0 + U is conserved; with theta a coordinate and
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
        const auto [drift, vibration] = test::jacobi_drift(test::run(s), c.t_steady);
        INFO(to_string(c.method) << " nx=" << c.nx << ": drift " << drift << " J, vibration energy " << vibration);
        CHECK(drift <= 1e-6 * vibration);
    }
}

TEST_CASE("the implicit stepper msbdf agrees with msadams", "[dynamics][stepper]")
{
    // msbdf is the stepper the runtime suggests for stiff runs (axial coordinates make the equations stiff,
    // docs/model.md section 7), and it runs on the finite-difference Jacobian of runtime/src/dynamics/integrate.cpp. Both
    // steppers at rtol 1e-10 must give one response, through the spin-up's breakpoint at T_s. What separates
    // them is the global error of two independent integrations, the tolerance grown over the window's ten or
    // so oscillations: measured 3e-8 (spin-up) and 4e-9 (torque) of the peak, so 1e-6 of the peak leaves a
    // factor 30. A wrong Jacobian does not show here (msbdf's error control still converges, with more steps);
    // the next test checks the Jacobian itself. The torque case runs without axial coordinates: with them
    // msadams, held to small steps by the 980 rad/s axial mode, takes seconds under torque.
    struct Case {
        const char* name;
        Motion motion;
        int nx;
    };
    for (const Case& c : {Case{"spin-up to 4 rad/s, AMM nx=4 ny=4", spin_up(4.0), 4},
                          Case{"hub torque tau0 = 10, AMM nx=0 ny=4", torque(10.0), 0}}) {
        Scene adams = paper_scene(Method::amm, c.nx, 4, c.motion);
        adams.output.t_end = 20.0;
        adams.output.dt_out = 0.05;
        Scene bdf = adams;
        bdf.solver.stepper = "msbdf";
        const std::vector<Row> a = run(adams), b = run(bdf);
        REQUIRE(a.size() == b.size());
        double diff = 0.0, peak = 0.0, theta_diff = 0.0, theta_peak = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            diff = std::max(diff, std::abs(a[i].tip_uy - b[i].tip_uy));
            peak = std::max(peak, std::abs(a[i].tip_uy));
            theta_diff = std::max(theta_diff, std::abs(a[i].theta - b[i].theta));
            theta_peak = std::max(theta_peak, std::abs(a[i].theta));
        }
        INFO(c.name << ": tip_uy differs by " << diff << " m of peak " << peak << " m, theta by " << theta_diff
                    << " rad of " << theta_peak << " rad");
        CHECK(diff < 1e-6 * peak);
        // Under torque theta is integrated too (under spin-up it is the prescribed theta(t) in both runs).
        if (c.motion.kind == Motion::Kind::torque) CHECK(theta_diff < 1e-6 * theta_peak);
    }
}

TEST_CASE("the finite-difference Jacobian of the first-order system", "[dynamics][stepper]")
{
    // The implicit steppers (msbdf, bsimp, rk*imp) need df/dy and df/dt of y' = f(t, y) = (qd, M^-1 Q)
    // (docs/model.md section 5), row-major as GSL wants. A wrong one does not change msbdf's response, only
    // its cost, so it is checked here directly, against references formed without it. It is the fallback for
    // models without generated derivatives and the oracle of test_jacobian.cpp.
    using Eigen::MatrixXd;
    using Eigen::VectorXd;
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Parameters p;
    struct Case {
        const char* name;
        Motion motion;
        double t;
    };
    // t inside the drive, where theta_dot, theta_ddot (spin-up) or tau (torque) and their rates are all nonzero.
    for (const Case& c : {Case{"spin-up, prescribed", spin_up(4.0), 6.3}, Case{"hub torque", torque(10.0), 3.1}}) {
        INFO(c.name);
        VariantKey key;
        key.method = Method::amm;
        key.nx = 4;
        key.ny = 4;
        key.drive = c.motion.drive();
        const auto model = make_model(key, p, ModelSource::automatic);
        FirstOrderSystem system(*model, c.motion);
        const int n = key.nq(), m = system.size();
        // A deformed, moving state of the size the paper's cases reach: B ~ 0.1 m, A ~ 0.1 mm, theta ~ 1 rad.
        VectorXd y(m);
        for (int i = 0; i < n; ++i) {
            const FieldKind kind = coordinate_layout(key).field_of(i).kind;
            const double size = kind == FieldKind::hub_angle ? 1.0 : kind == FieldKind::axial ? 1e-4 : 0.1;
            y(i) = size * std::sin(1.3 * i + 0.4);
            y(n + i) = 2.0 * size * std::cos(0.7 * i + 0.2);
        }
        RowMajor J(m, m);
        VectorXd dfdt(m);
        REQUIRE(system.finite_difference_jacobian(c.t, y.data(), J.data(), dfdt.data()) == 0);

        // d(qd)/dq = 0 and d(qd)/dqd = I.
        CHECK(J.topLeftCorner(n, n).lpNorm<Eigen::Infinity>() < 1e-9);
        CHECK((J.topRightCorner(n, n) - MatrixXd::Identity(n, n)).lpNorm<Eigen::Infinity>() < 1e-9);

        // d(qdd)/dy. Prescribed: M is constant and Q linear in (q, qd), so d(M^-1 Q)/dy_j = M^-1 (Q(y + e_j) -
        // Q(y)) exactly, from the model's mass and forces alone. Torque: M(q) and Q are not linear, so the
        // reference is a central difference of f with a step about 30 times the Jacobian's.
        const HubInput u = c.motion.at(c.t);
        const auto f = [&](double t, const VectorXd& z) {
            VectorXd r(m);
            REQUIRE(system.rhs(t, z.data(), r.data()) == 0);
            return VectorXd(r.tail(n));
        };
        MatrixXd ref(n, m);
        if (key.drive == Drive::prescribed) {
            RowMajor M(n, n);
            model->mass(u, y.data(), M.data());
            const auto Q = [&](const VectorXd& z) {
                VectorXd r(n);
                model->forces(u, z.data(), z.data() + n, r.data());
                return r;
            };
            for (int j = 0; j < m; ++j) ref.col(j) = MatrixXd(M).llt().solve(Q(y + VectorXd::Unit(m, j)) - Q(y));
        } else {
            for (int j = 0; j < m; ++j) {
                const double h = 2e-4 * std::max(std::abs(y(j)), 1e-3);
                ref.col(j) = (f(c.t, y + h * VectorXd::Unit(m, j)) - f(c.t, y - h * VectorXd::Unit(m, j))) / (2 * h);
            }
        }
        // Row by row: the axial rows hold entries ~1e7 s^-2 (the axial frequencies squared) beside small
        // couplings, and each row is held to its own scale. Measured agreement: 3e-9 or better.
        for (int i = 0; i < n; ++i) {
            const VectorXd err = J.row(n + i).transpose() - ref.row(i).transpose();
            INFO("row qdd_" << i << ": Jacobian " << J.row(n + i) << "\nreference " << ref.row(i));
            CHECK(err.lpNorm<Eigen::Infinity>() <= 1e-6 * ref.row(i).lpNorm<Eigen::Infinity>());
        }

        // df/dt: the drive's time dependence (theta_dot(t), theta_ddot(t) or tau(t)), against a central
        // difference of f in t with a step of 1e-3 s, small beside the drive's 10-15 s. Measured agreement: 7e-8.
        const double dt = 1e-3;
        const VectorXd ref_t = (f(c.t + dt, y) - f(c.t - dt, y)) / (2 * dt);
        INFO("df/dt " << dfdt.tail(n).transpose() << "\nreference " << ref_t.transpose());
        CHECK(dfdt.head(n).lpNorm<Eigen::Infinity>() == 0.0);
        CHECK((dfdt.tail(n) - ref_t).lpNorm<Eigen::Infinity>() <= 1e-6 * ref_t.lpNorm<Eigen::Infinity>());
        CHECK(ref_t.lpNorm<Eigen::Infinity>() > 0.0);
    }
}
