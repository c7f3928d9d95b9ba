// Rayleigh damping as linearize and the sensitivities see it (damping_matrix) against the model's own damping
// forces: C = -dQ/dqd at rest by central differences, axial and bending coordinates alike, both drives.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include "models/model_operations.hpp"

using namespace hubbeam;

TEST_CASE("damping_matrix is -dQ/dqd at rest, on the axial coordinates too", "[linearize]")
{
    // At rest (q = 0, qd = 0, no drive) the velocity forces other than damping (Coriolis, centrifugal) are
    // quadratic in qd: their derivative vanishes and -dQ/dqd is the damping matrix alone. Gravity's term is in the
    // variant at g = 0, where it adds no force.
    struct Case {
        Method method;
        int nx, ny;
        Drive drive;
        Order order;
        Taper taper;
        ModelSource source;
    };
    // Built-in variants, and the hand-assembled model at another Nx.
    const Case cases[] = {
        {Method::amm, 4, 4, Drive::torque, Order::first, Taper::width, ModelSource::generated},
        {Method::bim, 4, 4, Drive::prescribed, Order::zero, Taper::width, ModelSource::generated},
        {Method::fem, 4, 4, Drive::torque, Order::first, Taper::depth, ModelSource::generated},
        {Method::bsim, 4, 4, Drive::prescribed, Order::zero, Taper::depth, ModelSource::generated},
        {Method::fem, 2, 4, Drive::prescribed, Order::first, Taper::uniform, ModelSource::assembled},
    };
    for (const Case& c : cases) {
        VariantKey key;
        key.method = c.method;
        key.nx = c.nx;
        key.ny = c.ny;
        key.drive = c.drive;
        key.order = c.order;
        key.extras.tip = true;
        key.extras.gravity = true;
        key.extras.damping = true;
        key.extras.taper = c.taper;
        Parameters p;
        p.alpha = 0.3;
        p.beta = 2e-3;
        p.m_tip = 0.4;
        p.J_tip = 0.01;
        p.tip_ratio = 0.8;
        const auto model = make_model(key, p, c.source);
        const int n = model->nq();
        const HubInput rest;
        const std::vector<double> q(static_cast<std::size_t>(n), 0.0);
        std::vector<double> qd(q), up(q), down(q);
        Eigen::MatrixXd expected(n, n);
        const double h = 1e-3;  // Q is linear in qd at qd = 0 up to quadratic terms, which central differences cancel
        for (int j = 0; j < n; ++j) {
            qd[static_cast<std::size_t>(j)] = h;
            model->forces(rest, q.data(), qd.data(), up.data());
            qd[static_cast<std::size_t>(j)] = -h;
            model->forces(rest, q.data(), qd.data(), down.data());
            qd[static_cast<std::size_t>(j)] = 0.0;
            for (int i = 0; i < n; ++i)
                expected(i, j) = -(up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2.0 * h);
        }
        const Eigen::MatrixXd C = damping_matrix(*model, p);
        INFO(key.name() << "\nC =\n" << C << "\n-dQ/dqd =\n" << expected);
        REQUIRE(C.rows() == n);
        // The axial block is damped (the check this test exists for), and everything agrees.
        const int a = coordinate_layout(key).first(FieldKind::axial);
        CHECK(expected.block(a, a, c.nx, c.nx).norm() > 0.0);
        CHECK((C - expected).norm() < 1e-8 * expected.norm());
    }
}
