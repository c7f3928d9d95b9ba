// Feedback control of a free hub and the energy balance: a step response against the second-order closed loop of a
// rigid-like beam (its roots from J, kp, kd, with J computed here), saturation, an integral term against gravity's
// constant torque, the balance E + dissipated - work with damping, the Jacobian's control terms against differences,
// and the auxiliary states' interpolation against steps that end at every row.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "eigen_oracles.hpp"
#include "runs.hpp"

using namespace hubbeam;
using hubbeam::test::paper_scene;
using hubbeam::test::rigid_inertia;
using hubbeam::test::stiff_step;

namespace {

/// A PID-controlled spin-up to 1 rad/s of the paper's beam with mass-proportional damping, to t_end: every auxiliary
/// state (the integral, the dissipated energy, the work) at once.
Scene controlled_damped_spin_up(double t_end)
{
    Scene s = paper_scene(Method::amm, 0, 4, test::spin_up(1.0));
    s.control = Control{};
    s.control->kp = 200.0;
    s.control->kd = 150.0;
    s.control->ki = 50.0;
    s.parameters.alpha = 0.1;
    s.output.t_end = t_end;
    return s;
}

/// The rows of a run (which must complete) and its summary.
using Ran = test::Collected;
Ran run_scene(const Scene& s) { return test::completed_run(s); }

/// The free-hub, Rayleigh-damped AMM arm (Ny = 3) the controlled Jacobians are checked on, spinning up to 2 rad/s as
/// its reference. No axial coordinates: their stiffness's entries (1e6) would hide the control's terms in a common
/// margin.
struct DampedArm {
    Motion motion;
    Parameters p;
    std::unique_ptr<Model> model;

    DampedArm()
    {
        motion.kind = Motion::Kind::spin_up;
        motion.omega0 = 2.0;
        p.alpha = 0.05;
        p.beta = 1e-3;
        const VariantKey key{.method = Method::amm, .nx = 0, .ny = 3, .drive = Drive::torque, .extras = {.damping = true}};
        model = make_model(key, p, ModelSource::generated);
        REQUIRE(model->jacobian() != nullptr);
    }

    /// The PID law with tip feedback its Jacobians are checked with, clipped at tau_max (ki = 0: no integral state).
    static Control law(double tau_max, double ki = 7.0)
    {
        Control c;
        c.kp = 40.0;
        c.kd = 30.0;
        c.ki = ki;
        c.k_tip = 25.0;
        c.tau_max = tau_max;
        return c;
    }
};

}  // namespace

TEST_CASE("a controlled step settles to the reference within the rigid closed loop's envelope", "[control]")
{
    // J e'' + kd e' + kp e = 0 for the error e = theta - angle, e(0) = -angle: with damping ratio zeta < 1 its
    // envelope is angle e^(-sigma t) / sqrt(1 - zeta^2), sigma = kd / (2 J).
    const double angle = 0.5;
    Scene s = stiff_step(angle, 0.0, 0.0);
    const double J = rigid_inertia(s.parameters), omega = 1.0, zeta = 0.7;
    s.control->kp = J * omega * omega;
    s.control->kd = 2.0 * zeta * omega * J;
    const Ran r = run_scene(s);
    const double sigma = s.control->kd / (2.0 * J);
    for (const Row& row : r.rows) {
        const double envelope = angle * std::exp(-sigma * row.t) / std::sqrt(1.0 - zeta * zeta);
        INFO("t = " << row.t);
        CHECK(std::abs(row.theta - angle) <= 1.001 * envelope + 1e-7);
        CHECK(row.extras.theta_ref == angle);
    }
    CHECK(std::abs(r.rows.back().theta - angle) < 2e-6 * angle);
}

TEST_CASE("a rigid-like beam's controlled step follows J theta'' + kd theta' + kp (theta - angle) = 0", "[control]")
{
    // The characteristic roots -sigma +- i omega_d, sigma = kd/(2J), omega_d = sqrt(kp/J - sigma^2), give
    // e(t) = -angle e^(-sigma t) (cos omega_d t + sigma/omega_d sin omega_d t); a light damping ratio (0.2) lets
    // the frequency show over several periods.
    const double angle = 0.2;
    Scene s = stiff_step(angle, 0.0, 0.0);
    const double J = rigid_inertia(s.parameters);
    s.control->kp = 1.5 * J;   // omega_n = sqrt(1.5) rad/s
    s.control->kd = 0.5 * J;   // sigma = 0.25 1/s
    const double sigma = s.control->kd / (2.0 * J), wd = std::sqrt(s.control->kp / J - sigma * sigma);
    const Ran r = run_scene(s);
    double worst = 0.0;
    for (const Row& row : r.rows) {
        const double e = -angle * std::exp(-sigma * row.t) * (std::cos(wd * row.t) + sigma / wd * std::sin(wd * row.t));
        worst = std::max(worst, std::abs(row.theta - (angle + e)));
        // The torque column is the law's value at the row's state.
        CHECK(row.extras.tau == Approx(-s.control->kp * (row.theta - angle) - s.control->kd * row.theta_dot).margin(1e-12));
    }
    // The beam's own flexibility shifts the loop by about (1 rad/s / 290 rad/s)^2.
    CHECK(worst < 2e-5 * angle);
}

TEST_CASE("saturation limits the torque column to tau_max - while saturated the hub accelerates at tau_max / J",
          "[control]")
{
    const double angle = 0.5, tau_max = 5.0;
    Scene s = stiff_step(angle, 64.0, 90.0);
    s.control->tau_max = tau_max;
    const Ran r = run_scene(s);
    const double J = rigid_inertia(s.parameters);
    double largest = 0.0;
    bool saturated = true;  // from t = 0: kp angle = 32 N m > tau_max
    int saturated_rows = 0;
    for (const Row& row : r.rows) {
        largest = std::max(largest, std::abs(row.extras.tau));
        saturated = saturated && row.extras.tau == tau_max;
        if (!saturated) continue;
        ++saturated_rows;
        INFO("t = " << row.t);
        // The stiff beam's bending under the sudden torque shifts the hub by about (1 / 290)^2 of the angle.
        CHECK(row.theta == Approx(tau_max * row.t * row.t / (2.0 * J)).margin(1e-5 * angle));
    }
    CHECK(largest == tau_max);
    CHECK(saturated_rows > 5);
    CHECK(std::abs(r.rows.back().theta - angle) < 1e-3);
}

TEST_CASE("an integral term removes the steady error that gravity's torque leaves a PD law", "[control]")
{
    // Held at theta = 0 (a horizontal beam) against the weight's moment m g (a L + L^2/2) cos theta: a PD law settles
    // where kp theta = -m g L^2/2 cos theta (a = 0, the stiff beam nearly straight); the integral removes it.
    Scene s = stiff_step(0.0, 0.0, 0.0);
    s.parameters.g = 9.81;
    const double J = rigid_inertia(s.parameters), m = s.parameters.rho * s.parameters.S, L = s.parameters.L;
    s.control->kp = 10.0 * J;
    s.control->kd = 2.0 * 0.7 * std::sqrt(10.0) * J;
    s.output.t_end = 40.0;
    const double moment = m * s.parameters.g * L * L / 2.0;
    double expected = 0.0;  // kp theta + moment cos theta = 0 by Newton
    for (int i = 0; i < 50; ++i)
        expected -= (s.control->kp * expected + moment * std::cos(expected)) /
                    (s.control->kp - moment * std::sin(expected));
    const Ran pd = run_scene(s);
    CHECK(pd.rows.back().theta == Approx(expected).epsilon(1e-4));
    // J s^3 + kd s^2 + kp s + ki: roots near -1.38 and -1.5 +- 1.9 i (stable: kd kp > J ki), so 40 s decay it
    // by e^-55.
    s.control->ki = 8.0 * J;
    const Ran pid = run_scene(s);
    CHECK(std::abs(pid.rows.back().theta) < 1e-6 * std::abs(expected));
    // The integral holds the moment: ki int theta dt = -(moment) at rest.
    CHECK(-s.control->ki * pid.rows.back().extras.controller_integral == Approx(moment).epsilon(1e-4));
}

TEST_CASE("with damping, E + dissipated - work stays constant, and the run's monitor checks it", "[control]")
{
    // docs/model.md section 11.4: d/dt (T + U) = -2 D + tau theta_dot. The paper's torque pulse on a damped beam (the
    // work an independent trapezoid of tau theta_dot over the rows), and a controlled spin-up.
    SECTION("torque pulse")
    {
        Scene s = paper_scene(Method::amm, 0, 4, test::torque(1.0));
        s.parameters.alpha = 0.5;
        s.parameters.beta = 2e-3;
        s.output.t_end = 20.0;
        const Ran r = run_scene(s);
        double largest = 0.0, trapezoid = 0.0;
        for (const Row& row : r.rows) largest = std::max(largest, row.kinetic + row.potential);
        for (std::size_t i = 0; i < r.rows.size(); ++i) {
            const Row& row = r.rows[i];
            CHECK(std::abs(row.kinetic + row.potential + row.extras.dissipated - row.extras.work) < 1e-7 * largest);
            if (i > 0) {
                const Row& a = r.rows[i - 1];
                CHECK(row.extras.dissipated >= a.extras.dissipated);  // D >= 0
                trapezoid += 0.5 * (row.t - a.t) * (a.extras.tau * a.theta_dot + row.extras.tau * row.theta_dot);
                CHECK(row.extras.work == Approx(trapezoid).margin(1e-4 * largest));
            }
        }
        // The damping did something: a good part of the largest strain energy (much of which is the quasi-static
        // bending while the torque acts, given back when it ends).
        double vibration = 0.0;
        for (const Row& row : r.rows) vibration = std::max(vibration, row.potential);
        CHECK(r.rows.back().extras.dissipated > 0.1 * vibration);
        CHECK(r.summary.energy_balance);
        CHECK(r.summary.jacobi_drift < 1e-7 * r.summary.vibration_energy);
    }
    SECTION("controlled spin-up with damping")
    {
        const Scene s = controlled_damped_spin_up(20.0);
        const Ran r = run_scene(s);
        double largest = 0.0;
        for (const Row& row : r.rows) largest = std::max(largest, row.kinetic + row.potential);
        for (const Row& row : r.rows)
            CHECK(std::abs(row.kinetic + row.potential + row.extras.dissipated - row.extras.work) < 1e-7 * largest);
        // It follows the reference: at a steady rate no torque is needed, so the error and its integral settle at 0
        // (slowly: the loop's real root is near -0.3 1/s, and the beam still rings after the spin-up).
        CHECK(r.rows.back().theta == Approx(r.rows.back().extras.theta_ref).epsilon(1e-3));
        CHECK(std::abs(r.rows.back().extras.controller_integral) < 0.05);
    }
}

TEST_CASE("the exact Jacobian of a controlled, damped system equals central differences, saturated or not",
          "[control][jacobian]")
{
    const DampedArm arm;
    const Motion& m = arm.motion;
    const Parameters& p = arm.p;
    const auto& model = arm.model;
    for (const double tau_max : {std::numeric_limits<double>::infinity(), 1e-3}) {
        const Control c = DampedArm::law(tau_max);
        FirstOrderSystem sys(*model, m, Axial::dynamic, &c, &p);
        const int n = sys.size();
        REQUIRE(n == 2 * model->nq() + 3);  // the integral, the dissipated energy, the work
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-0.3, 0.3);
        for (int trial = 0; trial < 5; ++trial) {
            std::vector<double> y(static_cast<std::size_t>(n));
            for (double& v : y) v = u(rng);
            const double t = 3.0 + trial;
            std::vector<double> exact(static_cast<std::size_t>(n * n)), fd(exact), dt_exact(static_cast<std::size_t>(n)),
                dt_fd(dt_exact);
            REQUIRE(sys.jacobian(t, y.data(), exact.data(), dt_exact.data()) == 0);
            REQUIRE(sys.finite_difference_jacobian(t, y.data(), fd.data(), dt_fd.data()) == 0);
            double scale = 0.0;
            for (double v : fd) scale = std::max(scale, std::abs(v));
            for (int i = 0; i < n * n; ++i) {
                INFO("tau_max " << tau_max << ", entry " << i / n << "," << i % n);
                CHECK(exact[static_cast<std::size_t>(i)] ==
                      Approx(fd[static_cast<std::size_t>(i)]).epsilon(1e-6).margin(1e-8 * scale));
            }
            for (int i = 0; i < n; ++i) {
                INFO("tau_max " << tau_max << ", dfdt " << i);
                CHECK(dt_exact[static_cast<std::size_t>(i)] == Approx(dt_fd[static_cast<std::size_t>(i)]).margin(1e-6 * scale));
            }
        }
    }
}

TEST_CASE("Jacobian products J v + (0, M^-1 g) equal central differences times v, controlled or not, saturated or not",
          "[control][jacobian][sensitivities]")
{
    // The sensitivities' products (jacobian_product) against the central differences' Jacobian and a dense solve with
    // M from the model's kernel: no code in common but the right-hand side the differences evaluate.
    const DampedArm arm;
    const auto& model = arm.model;
    const int nq = model->nq();
    const Control c = DampedArm::law(std::numeric_limits<double>::infinity()), saturating = DampedArm::law(1e-3);
    for (const Control* control : std::initializer_list<const Control*>{nullptr, &c, &saturating}) {
        FirstOrderSystem sys(*model, arm.motion, Axial::dynamic, control, &arm.p);
        REQUIRE(sys.has_exact_jacobian());
        const int n = sys.size(), k = 3;
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-0.3, 0.3);
        std::vector<double> y(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n * k)),
            g(static_cast<std::size_t>(nq * k)), out(v.size()), fd(static_cast<std::size_t>(n * n)),
            dt(static_cast<std::size_t>(n));
        for (double& x : y) x = u(rng);
        for (double& x : v) x = u(rng);
        for (double& x : g) x = u(rng);
        const double t = 4.0;
        REQUIRE(sys.jacobian_product(t, y.data(), k, v.data(), g.data(), out.data()) == 0);
        REQUIRE(sys.finite_difference_jacobian(t, y.data(), fd.data(), dt.data()) == 0);
        HubInput input = arm.motion.at(t);
        if (control != nullptr) input = HubInput{.tau = sys.torque(t, y.data())};
        Eigen::MatrixXd M(nq, nq);
        model->mass(input, y.data(), M.data());  // symmetric: row- or column-major alike
        using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const Eigen::Map<const RowMatrix> J(fd.data(), n, n);
        for (int j = 0; j < k; ++j) {
            Eigen::VectorXd expected = J * Eigen::Map<const Eigen::VectorXd>(v.data() + j * n, n);
            expected.segment(nq, nq) += M.lu().solve(Eigen::Map<const Eigen::VectorXd>(g.data() + j * nq, nq));
            const double scale = expected.lpNorm<Eigen::Infinity>();
            for (int i = 0; i < n; ++i) {
                INFO((control == nullptr ? "no control" : control->tau_max < 1 ? "saturated" : "controlled")
                     << ", vector " << j << ", row " << i);
                CHECK(out[static_cast<std::size_t>(j * n + i)] ==
                      Approx(expected[i]).epsilon(1e-6).margin(1e-7 * scale));
            }
        }
    }
}

TEST_CASE("the mass form of a controlled, damped system: M^-1 K and M^-1 C equal central differences, saturated or not",
          "[control][jacobian]")
{
    // gauss4 keeps a mesh's Newton matrices as I (x) M - h^2 A^2 (x) K - h A (x) C: the control's torque, a law of the
    // hub angle, its rate and the tip deflection, must be in K and C (before M^-1), and nothing of it where it
    // saturates. The oracle: central differences of the accelerations. The work and dissipated energy are quadratures
    // beside them; the controller's integral, which the torque reads, leaves the mass form to the dense Jacobian.
    const DampedArm arm;
    const Motion& m = arm.motion;
    const Parameters& p = arm.p;
    const auto& model = arm.model;
    const int nq = model->nq();
    for (const double tau_max : {std::numeric_limits<double>::infinity(), 1e-3}) {
        const Control c = DampedArm::law(tau_max, 0.0);
        FirstOrderSystem sys(*model, m, Axial::dynamic, &c, &p);
        REQUIRE(sys.has_mass_form());
        REQUIRE(sys.auxiliary_are_quadratures());
        const int n = sys.size();
        REQUIRE(n == 2 * nq + 2);  // the dissipated energy, the work
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-0.3, 0.3);
        for (int trial = 0; trial < 5; ++trial) {
            std::vector<double> y(static_cast<std::size_t>(n));
            for (double& v : y) v = u(rng);
            const double t = 3.0 + trial;
            std::vector<double> fd(static_cast<std::size_t>(n * n)), dt_fd(static_cast<std::size_t>(n));
            REQUIRE(sys.finite_difference_jacobian(t, y.data(), fd.data(), dt_fd.data()) == 0);
            using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
            RowMatrix M(nq, nq), K(nq, nq), C(nq, nq);
            REQUIRE(sys.mass_form_jacobian(t, y.data(), M.data(), K.data(), C.data()) == 0);
            const Eigen::MatrixXd dq = M.llt().solve(Eigen::MatrixXd(K)), dqd = M.llt().solve(Eigen::MatrixXd(C));
            double scale = 0.0;
            for (double v : fd) scale = std::max(scale, std::abs(v));
            for (int i = 0; i < nq; ++i)
                for (int j = 0; j < nq; ++j) {
                    INFO("tau_max " << tau_max << ", acceleration " << i << " by coordinate " << j);
                    const auto at = [&](int col) { return fd[static_cast<std::size_t>((nq + i) * n + col)]; };
                    CHECK(dq(i, j) == Approx(at(j)).epsilon(1e-6).margin(1e-8 * scale));
                    CHECK(dqd(i, j) == Approx(at(nq + j)).epsilon(1e-6).margin(1e-8 * scale));
                }
        }
    }
    Control with_integral;
    with_integral.kp = 40.0;
    with_integral.ki = 7.0;
    const FirstOrderSystem integral(*model, m, Axial::dynamic, &with_integral, &p);
    CHECK_FALSE(integral.has_mass_form());
    CHECK_FALSE(integral.auxiliary_are_quadratures());
}

TEST_CASE("interpolated rows of the auxiliary states agree with steps that end at every row", "[control]")
{
    Scene s = controlled_damped_spin_up(10.0);
    s.output.dt_out = 0.1;
    const Ran free = run_scene(s);
    s.solver.stepping = Stepping::rows;
    const Ran rows = run_scene(s);
    REQUIRE(free.rows.size() == rows.rows.size());
    for (double RowExtras::*c : {&RowExtras::controller_integral, &RowExtras::dissipated, &RowExtras::work}) {
        double peak = 0.0, worst = 0.0;
        for (std::size_t i = 0; i < rows.rows.size(); ++i) {
            peak = std::max(peak, std::abs(rows.rows[i].extras.*c));
            worst = std::max(worst, std::abs(free.rows[i].extras.*c - rows.rows[i].extras.*c));
        }
        CHECK(peak > 0.0);
        CHECK(worst < 1e-6 * peak);
    }
}

TEST_CASE("optional columns: only the scenes that have them, in the CSV header and lines", "[control][output]")
{
    Scene paper = paper_scene(Method::amm, 4, 4, test::spin_up(4.0));
    CHECK(optional_columns_of(paper).bits == 0);
    CHECK(row_header(optional_columns_of(paper)) == std::string(row_header()));
    paper.motion = test::torque(1.0);
    CHECK(optional_columns_of(paper).bits == 0);
    Scene controlled = stiff_step(0.5, 1.0, 1.0);
    CHECK(row_header(optional_columns_of(controlled)) == std::string(row_header()) + ",tau,theta_ref,work");
    controlled.control->ki = 1.0;
    controlled.parameters.alpha = 0.1;
    CHECK(row_header(optional_columns_of(controlled)) ==
          std::string(row_header()) + ",tau,theta_ref,controller_integral,dissipated,work");
    Scene damped = paper_scene(Method::amm, 4, 4, test::spin_up(4.0));
    damped.parameters.beta = 1e-3;
    CHECK(row_header(optional_columns_of(damped)) == std::string(row_header()) + ",dissipated");
}

TEST_CASE("a small controlled step follows the closed loop that modes and linearize give", "[control][modes]")
{
    // The paper's flexible beam (not stiffened) under PD control with tip feedback, a step small enough for the
    // equations to be linear in it: the run's theta(t) and tip_uy(t) are the closed loop's free response
    // x(t) = V exp(Lambda t) V^-1 x0 from x0 = (theta - angle = -angle, all else 0), by the eigen decomposition of
    // closed_loop's A, whose eigenvalues are what hubbeam modes prints for the scene.
    const double angle = 1e-3;
    Motion m;
    m.kind = Motion::Kind::step;
    m.angle = angle;
    Scene s = paper_scene(Method::amm, 0, 4, m);
    s.control = Control{};
    const double J = rigid_inertia(s.parameters);
    s.control->kp = J;
    s.control->kd = 1.4 * J;
    s.control->k_tip = 20.0;
    s.output.t_end = 8.0;
    s.output.dt_out = 0.1;
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-13;
    const Ran r = run_scene(s);

    const auto model = make_model(s.key(), s.parameters, ModelSource::generated);
    const SteadySpin rest = steady_spin(*model, 0.0);
    const StateSpace cl = closed_loop(state_space(*model, rest), *s.control);
    const test::GeneralEigen eig = test::general_eigen(cl.A);
    const Eigen::MatrixXcd& V = eig.vectors;
    Eigen::VectorXcd x0 = Eigen::VectorXcd::Zero(cl.A.rows());
    x0(0) = -angle;  // the error's deviation; everything else starts at the reference's state
    const Eigen::VectorXcd c = V.partialPivLu().solve(x0);
    // The modes hubbeam modes reports are these eigenvalues.
    const std::vector<NaturalMode> modes = closed_loop_modes(*model, rest, *s.control);
    REQUIRE(!modes.empty());
    CHECK(modes.front().kind == "hub");
    for (const NaturalMode& mode : modes) {
        double nearest = INFINITY;
        for (Eigen::Index k = 0; k < eig.values.size(); ++k)
            nearest = std::min(nearest, std::abs(eig.values[k] - std::complex<double>(mode.growth, mode.rad_s)));
        CHECK(nearest < 1e-9 * mode.undamped_rad_s);
    }
    double worst_theta = 0.0, worst_tip = 0.0, largest_tip = 0.0;
    for (const Row& row : r.rows) {
        const Eigen::VectorXcd x = V * (c.array() * (eig.values.array() * row.t).exp()).matrix();
        const Eigen::VectorXd y = (cl.C * x.real());
        worst_theta = std::max(worst_theta, std::abs(row.theta - angle - y(1)));
        worst_tip = std::max(worst_tip, std::abs(row.tip_uy - y(0)));
        largest_tip = std::max(largest_tip, std::abs(row.tip_uy));
    }
    // Nonlinear terms are of the step squared: 1e-6 of the angle's scale, far below the 1e-3 the closed loop
    // without its tip feedback would be off by.
    CHECK(worst_theta < 1e-3 * angle);
    CHECK(worst_tip < 1e-3 * largest_tip);
}
