// The implicit steppers' Jacobian: the exact one assembled from the generated derivative kernels against
// central differences of the right-hand side, for every generated variant; and du/dt of the drive profiles
// (docs/model.md section 6) against central differences of Motion::at.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <gsl/gsl_errno.h>
#include <memory>
#include <random>
#include <utility>

#include <hubbeam/make_model.hpp>
#include "dynamics/integrate.hpp"
#include "forwarding_model.hpp"
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// y = (q, qd) of a random state (random_state.hpp).
Eigen::VectorXd random_y(const VariantKey& key, std::mt19937& rng)
{
    const test::State s = test::random_state(key, rng);
    Eigen::VectorXd y(2 * key.nq());
    y << s.q, s.qd;
    return y;
}

/// The paper's stronger load cases (docs/model.md section 6), so that the drive terms are large.
Motion motion_for(Drive drive)
{
    Motion m;
    m.kind = drive == Drive::torque ? Motion::Kind::torque : Motion::Kind::spin_up;
    m.omega0 = 10.0;
    m.tau0 = 10.0;
    return m;
}

/// The reference for the columns of dfdy in qd and for dfdt, where the runtime's central differences
/// (h = eps^(1/3) |y|) lose about eps |qdd| / h to rounding: the axial rows of an nx > 0 variant have |qdd| ~ 1e5
/// and more (stiff stretch, docs/model.md section 7) against entries ~ 10, i.e. relative errors up to 1e-4 in the
/// oracle itself. Central differences of a quadratic are exact for any step, and Q is quadratic in qd (T is
/// quadratic in the rates, docs/model.md section 3; M does not depend on qd), so the qd columns take h = 1.
/// f depends on t only through the drive u, and Q is at most quadratic in u (tau and theta_ddot enter linearly,
/// theta_dot quadratically): dfdt = M^-1 (Q(u + r) - Q(u - r)) / 2 along the drive's rate r = du/dt exactly,
/// with M^-1 by a dense LU of the model's M. (The rate itself is checked against Motion::at below.)
void rate_and_time_reference(FirstOrderSystem& sys, const Model& model, const Motion& motion, double t,
                             const Eigen::VectorXd& y, RowMatrix& J, Eigen::VectorXd& dfdt)
{
    const int m = sys.size(), n = m / 2;
    Eigen::VectorXd yp = y, ym = y, fp(m), fm(m);
    for (int j = n; j < m; ++j) {
        const double h = 1.0;
        yp[j] = y[j] + h;
        ym[j] = y[j] - h;
        REQUIRE(sys.rhs(t, yp.data(), fp.data()) == GSL_SUCCESS);
        REQUIRE(sys.rhs(t, ym.data(), fm.data()) == GSL_SUCCESS);
        J.col(j) = (fp - fm) / (2.0 * h);
        yp[j] = ym[j] = y[j];
    }
    const HubInput u = motion.at(t), r = motion.rate(t);
    const HubInput up{u.tau + r.tau, u.theta_dot + r.theta_dot, u.theta_ddot + r.theta_ddot, u.theta};
    const HubInput down{u.tau - r.tau, u.theta_dot - r.theta_dot, u.theta_ddot - r.theta_ddot, u.theta};
    Eigen::VectorXd Qp(n), Qm(n);
    model.forces(up, y.data(), y.data() + n, Qp.data());
    model.forces(down, y.data(), y.data() + n, Qm.data());
    Eigen::VectorXd dQdt = (Qp - Qm) / 2.0;
    // A prescribed variant with gravity also reads the angle, through sin and cos: its part dQ/dtheta theta_dot by
    // a small central difference (Q is not polynomial in theta).
    if (model.key().extras.gravity && model.key().drive == Drive::prescribed) {
        const double h = 1e-5;
        HubInput ahead = u, behind = u;
        ahead.theta += h;
        behind.theta -= h;
        model.forces(ahead, y.data(), y.data() + n, Qp.data());
        model.forces(behind, y.data(), y.data() + n, Qm.data());
        dQdt += u.theta_dot * (Qp - Qm) / (2.0 * h);
    }
    Eigen::MatrixXd M(n, n);
    model.mass(u, y.data(), M.data());
    dfdt.head(n).setZero();
    dfdt.tail(n) = M.partialPivLu().solve(dQdt);
    // A moving hub's M turns with the prescribed angle too: d/dt (M^-1 Q) by fourth-order central differences of the
    // right-hand side in t (M and Q are smooth in t through the drive; the step's truncation 1e-12 of their scale).
    if (model.key().extras.hub && model.key().drive == Drive::prescribed) {
        const double h = 1e-3;
        std::vector<Eigen::VectorXd> f(4, Eigen::VectorXd(m));
        const double at[] = {t - 2.0 * h, t - h, t + h, t + 2.0 * h};
        for (int k = 0; k < 4; ++k) REQUIRE(sys.rhs(at[k], y.data(), f[static_cast<std::size_t>(k)].data()) == GSL_SUCCESS);
        dfdt = (8.0 * (f[2] - f[1]) - (f[3] - f[0])) / (12.0 * h);
    }
}

/// The four nq x nq blocks of a row-major 2nq x 2nq Jacobian, as (row block, column block).
Eigen::MatrixXd block(const RowMatrix& J, int n, int r, int c) { return J.block(r * n, c * n, n, n); }

}  // namespace

TEST_CASE("generated Jacobian equals central differences of the right-hand side", "[jacobian]")
{
    // the hub-radius terms (the paper's cases have a = 0) and every extra term exercised
    const Parameters p = test::with_every_term();
    std::mt19937 rng(58);
    std::vector<std::string> names = generated_variant_names();
    REQUIRE(!names.empty());
    // and order full, compiled on demand, where M depends on B under either drive (the mass_q_product kernel); from
    // Ny = 8 with its foreshortening terms at quadrature points, a tip body's at the tip
    for (const char* full : {"amm_nx2_ny3_prescribed_full", "fem_nx2_ny4_torque_full", "bsim_nx3_ny4_prescribed_full",
                             "amm_nx2_ny8_prescribed_full", "bsim_nx0_ny8_torque_full_tip_gravity"})
        names.emplace_back(full);
    // and the extra terms (docs/model.md section 11) under both drives, where gravity brings the angle into Q: under
    // torque through the coordinate theta (the generator's chain rule through sin and cos), prescribed through the
    // drive's angle (Model::forces_theta in dfdt)
    for (const char* extra : {"amm_nx0_ny3_torque_first_tip_gravity_damped_width", "bim_nx2_ny3_prescribed_first_tip_gravity_damped_depth",
                              "fem_nx2_ny4_torque_full_tip_gravity"})
        names.emplace_back(extra);
    // and a moving hub under a prescribed drive, where M itself turns with the drive's angle (dM/dtheta qdd in dfdt)
    for (const char* hub : {"fem_nx2_ny4_prescribed_first_tip_gravity_damped_hub",
                            "amm_nx0_ny3_nz3_nt2_prescribed_first_pitched_coned_hub"})
        names.emplace_back(hub);
    // and out of the plane (docs/model.md section 12): flap and twist fields with every term, under both drives
    for (const char* blade : {"fem_nx2_ny4_nz4_nt2_torque_first_tip_gravity_damped_pitched_twisted_coned",
                              "amm_nx0_ny3_nz3_nt2_prescribed_first_tip_gravity_damped_pitched_coned",
                              "bsim_nx3_ny4_nz4_nt3_torque_zero_gravity_pitched_twisted",
                              "bim_nx0_ny3_nz3_prescribed_first_coned",
                              "bim_nx2_ny3_nz3_nt2_torque_full_tip_gravity_damped_pitched_coned"})
        names.emplace_back(blade);
    for (const std::string& name : names) {
        const VariantKey key = VariantKey::parse(name);
        SECTION(key.name())
        {
            const auto model = make_model(key, test::with_profile(key, p), ModelSource::generated);
            REQUIRE(model->jacobian() != nullptr);
            const Motion motion = motion_for(key.drive);
            // Inside the spin-up (T_s = 15 s) or torque (T_t = 10 s) window, away from its ends.
            std::uniform_real_distribution<double> time(0.5, (key.drive == Drive::torque ? 10.0 : 15.0) - 0.5);
            FirstOrderSystem sys(*model, motion);
            const int n = key.nq(), m = sys.size();
            for (int trial = 0; trial < 4; ++trial) {
                const Eigen::VectorXd y = random_y(key, rng);
                const double t = time(rng);
                RowMatrix J(m, m), Jfd(m, m);
                Eigen::VectorXd dfdt(m), dfdt_fd(m);
                REQUIRE(sys.jacobian(t, y.data(), J.data(), dfdt.data()) == GSL_SUCCESS);
                REQUIRE(sys.finite_difference_jacobian(t, y.data(), Jfd.data(), dfdt_fd.data()) == GSL_SUCCESS);
                CHECK(dfdt_fd.head(n).lpNorm<Eigen::Infinity>() == 0.0);
                rate_and_time_reference(sys, *model, motion, t, y, Jfd, dfdt_fd);
                INFO("t = " << t << ", trial " << trial);
                // d qd / dq is exactly zero in both; the other blocks to 1e-7 of their size (the kernels are exact
                // to round-off; the q columns are the runtime's central differences, accurate to ~1e-9 here).
                CHECK(block(J, n, 0, 0).lpNorm<Eigen::Infinity>() == 0.0);
                CHECK(block(Jfd, n, 0, 0).lpNorm<Eigen::Infinity>() == 0.0);
                CHECK(test::relative_error(block(J, n, 0, 1), block(Jfd, n, 0, 1)) < 1e-7);
                CHECK(test::relative_error(block(J, n, 1, 0), block(Jfd, n, 1, 0)) < 1e-7);
                CHECK(test::relative_error(block(J, n, 1, 1), block(Jfd, n, 1, 1)) < 1e-7);
                CHECK(dfdt.head(n).lpNorm<Eigen::Infinity>() == 0.0);
                CHECK(test::relative_error(dfdt.tail(n), dfdt_fd.tail(n)) < 1e-7);
            }
        }
    }
}

namespace {

/// A model's equations without its derivatives (Model::jacobian() null): what a model of a test, or of a user, may be.
class WithoutDerivatives final : public test::ForwardingModel {
public:
    using ForwardingModel::ForwardingModel;
};

}  // namespace

TEST_CASE("a model without derivatives gets the finite-difference Jacobian", "[jacobian]")
{
    const VariantKey key = VariantKey::parse("bim_nx4_ny4_torque_first");
    const auto model = std::make_unique<WithoutDerivatives>(make_model(key, Parameters{}, ModelSource::assembled));
    REQUIRE(model->jacobian() == nullptr);
    const Motion motion = motion_for(key.drive);
    FirstOrderSystem sys(*model, motion);
    std::mt19937 rng(59);
    const Eigen::VectorXd y = random_y(key, rng);
    const int m = sys.size();
    RowMatrix J(m, m), Jfd(m, m);
    Eigen::VectorXd dfdt(m), dfdt_fd(m);
    REQUIRE(sys.jacobian(2.0, y.data(), J.data(), dfdt.data()) == GSL_SUCCESS);
    REQUIRE(sys.finite_difference_jacobian(2.0, y.data(), Jfd.data(), dfdt_fd.data()) == GSL_SUCCESS);
    CHECK((J - Jfd).lpNorm<Eigen::Infinity>() == 0.0);
    CHECK((dfdt - dfdt_fd).lpNorm<Eigen::Infinity>() == 0.0);
}

TEST_CASE("du/dt of the drive equals central differences of the drive", "[jacobian][motion]")
{
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        const Motion motion = motion_for(drive);
        const double end = drive == Drive::torque ? motion.torque_time : motion.spin_time;
        // Inside the window (both ends excluded: the profiles are restarted there) and after it (du/dt = 0).
        for (const double t : {0.3, 0.17 * end, 0.5 * end, 0.71 * end, 0.93 * end, end + 2.0}) {
            const double h = 1e-5;
            const auto up = motion.at(t + h).packed(), down = motion.at(t - h).packed(), rate = motion.rate(t).packed();
            Eigen::Vector3d fd, exact;
            for (int j = 0; j < 3; ++j) {
                fd[j] = (up[static_cast<std::size_t>(j)] - down[static_cast<std::size_t>(j)]) / (2.0 * h);
                exact[j] = rate[static_cast<std::size_t>(j)];
            }
            INFO(to_string(drive) << " at t = " << t << ": exact " << exact.transpose() << ", fd " << fd.transpose());
            if (t > end) CHECK(exact.lpNorm<Eigen::Infinity>() == 0.0);
            else CHECK(test::relative_error(exact, fd) < 1e-7);
        }
    }
}
