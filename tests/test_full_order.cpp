// Order full (docs/model.md section 3), end to end: its generated M and Q against the independent quadrature of
// the position (kinetic_oracle.hpp), and its invariants in runs. The variants are compiled on demand.
#include <catch2/catch.hpp>
#include <random>
#include <string>
#include <vector>

#include "kinetic_oracle.hpp"
#include "make_model.hpp"
#include "model.hpp"
#include "random_state.hpp"
#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

namespace {

/// Every method with axial coordinates (the u_x1 u_x2 coupling of order full), both drives.
std::vector<VariantKey> full_variants()
{
    std::vector<VariantKey> keys;
    for (const char* name : {"amm_nx2_ny3", "fem_nx2_ny4", "bim_nx2_ny3", "bsim_nx3_ny4"})
        for (const char* drive : {"prescribed", "torque"})
            keys.push_back(VariantKey::parse(std::string(name) + "_" + drive + "_full"));
    keys.push_back(VariantKey::parse("bsim_nx0_ny4_torque_full_open"));
    return keys;
}

}  // namespace

TEST_CASE("order full: generated M and Q equal Lagrange's equations of the quadrature of |r_dot|^2", "[full]")
{
    Parameters p;
    p.a = 0.35;  // the hub-radius terms too
    std::mt19937 rng(7);
    for (const VariantKey& key : full_variants()) {
        SECTION(key.name())
        {
            const auto model = make_model(key, p, ModelSource::generated);
            const KineticOracle oracle(key, p);
            VariantKey first = key;
            first.order = Order::first;
            const auto truncated = make_model(first, p, ModelSource::assembled);
            const int n = key.nq();
            for (int trial = 0; trial < 3; ++trial) {
                State s = random_state(key, rng);
                // Deflections of a metre on the 8 m beam, so that the terms order first drops (u_x2 ~ B^2 / L)
                // are far above round-off.
                s.q.tail(key.ny) *= 10.0;
                s.qd.tail(key.ny) *= 10.0;
                Eigen::MatrixXd M(n, n), M_first(n, n);
                model->mass(s.u, s.q.data(), M.data());
                truncated->mass(s.u, s.q.data(), M_first.data());
                Eigen::VectorXd Q(n), Q_first(n);
                model->forces(s.u, s.q.data(), s.qd.data(), Q.data());
                truncated->forces(s.u, s.q.data(), s.qd.data(), Q_first.data());
                const Eigen::MatrixXd M_ref = oracle.mass(s.q, s.u);
                const Eigen::VectorXd Q_ref = oracle.forces(s.q, s.qd, s.u);
                INFO("trial " << trial << ": |M - M_ref| " << relative_error(M, M_ref) << ", |Q - Q_ref| "
                              << relative_error(Q, Q_ref) << "; order first: " << relative_error(M_first, M_ref)
                              << ", " << relative_error(Q_first, Q_ref));
                CHECK(relative_error(M, M_ref) < 1e-10);
                CHECK(relative_error(Q, Q_ref) < 1e-9);
                // The comparison can tell the orders apart: order first misses by far more than the tolerance.
                CHECK(std::max(relative_error(M_first, M_ref), relative_error(Q_first, Q_ref)) > 1e-4);

                const Energy e = model->energy(s.u, s.q.data(), s.qd.data());
                const double T_ref = oracle.kinetic<double>(s.q.data(), s.qd.data(), s.u.theta_dot);
                CHECK(std::abs(e.kinetic() - T_ref) < 1e-11 * std::abs(T_ref));
                CHECK(std::abs(e.U - oracle.potential<double>(s.q.data())) < 1e-11 * e.U);
            }
        }
    }
}

TEST_CASE("order full: the Jacobi integral is constant under a steady drive", "[full][dynamics]")
{
    // As for order first (test_dynamics.cpp): T2 - T0 + U at constant spin, T + U after the torque ends.
    struct Case {
        Method method;
        int nx, ny;
        Motion motion;
        double t_steady;
    };
    for (const Case& c : {Case{Method::amm, 0, 4, spin_up(4.0), 15.0}, Case{Method::fem, 2, 4, torque(10.0), 10.0},
                          Case{Method::bim, 0, 4, torque(10.0), 10.0}}) {
        Scene s = paper_scene(c.method, c.nx, c.ny, c.motion);
        s.variant.order = Order::full;
        s.source = ModelSource::generated;
        s.output.t_end = 25.0;
        s.output.dt_out = 0.05;
        const auto [drift, vibration] = jacobi_drift(run(s), c.t_steady);
        INFO(to_string(c.method) << " nx=" << c.nx << ": drift " << drift << " J, vibration energy " << vibration);
        CHECK(vibration > 0.0);
        CHECK(drift <= 1e-6 * vibration);
    }
}
