// Order full (docs/model.md section 3), end to end: its generated M and Q against the independent quadrature of
// the position (kinetic_oracle.hpp) and against the expanded form, and its invariants in runs. The variants are
// compiled on demand.
#include <catch2/catch.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/model.hpp>
#include <random>
#include <string>
#include <vector>

#include "kinetic_oracle.hpp"
#include "random_state.hpp"
#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

namespace {

/// Every method with axial coordinates (the u_x1 u_x2 coupling of order full), both drives: expanded (Ny < 8) and
/// with the foreshortening terms at quadrature points (Ny >= 8); then blades.
std::vector<VariantKey> full_variants()
{
    std::vector<VariantKey> keys;
    for (const char* name : {"amm_nx2_ny3", "fem_nx2_ny4", "bim_nx2_ny3", "bsim_nx3_ny4", "amm_nx2_ny8", "fem_nx2_ny8",
                             "bim_nx2_ny8", "bsim_nx3_ny8"})
        for (const char* drive : {"prescribed", "torque"})
            keys.push_back(VariantKey::parse(std::string(name) + "_" + drive + "_full"));
    keys.push_back(VariantKey::parse("bsim_nx0_ny4_torque_full_open"));
    // A blade's flapwise field and precone (docs/model.md section 12); at Ny = 8 its foreshortening stays expanded.
    for (const char* name : {"fem_nx2_ny4_nz4_torque_full_coned", "amm_nx0_ny3_nz3_prescribed_full",
                             "fem_nx0_ny8_nz4_prescribed_full_coned", "bim_nx2_ny3_nz3_prescribed_full_coned",
                             "bsim_nx3_ny4_nz4_torque_full_coned"})
        keys.push_back(VariantKey::parse(name));
    return keys;
}

}  // namespace

TEST_CASE("order full: generated M and Q equal Lagrange's equations of the quadrature of |r_dot|^2", "[full]")
{
    Parameters p;
    p.a = 0.35;  // the hub-radius terms too
    p.I_flap = 0.4 * p.I, p.precone = 0.1;  // read by the blades only
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
                // Deflections of a metre on the 8 m beam, both ways for a blade, so that the terms order first drops
                // (u_x2 ~ B^2 / L) are far above round-off.
                for (const CoordinateField& f : coordinate_layout(key).fields)
                    if (f.kind == FieldKind::inplane || f.kind == FieldKind::flap) {
                        s.q.segment(f.first, f.count) *= 10.0;
                        s.qd.segment(f.first, f.count) *= 10.0;
                    }
                Eigen::MatrixXd M(n, n), M_first(n, n);
                model->mass(s.u, s.q.data(), M.data());
                truncated->mass(s.u, s.q.data(), M_first.data());
                Eigen::VectorXd Q(n), Q_first(n);
                model->forces(s.u, s.q.data(), s.qd.data(), Q.data());
                truncated->forces(s.u, s.q.data(), s.qd.data(), Q_first.data());
                const Eigen::MatrixXd M_ref = oracle.mass(s.q, s.u);
                const Eigen::VectorXd Q_ref = oracle.forces(s.q, s.qd, s.u);
                INFO("trial " << trial << ": |M - M_ref| " << relative_error(M, M_ref) << ", |Q - Q_ref| "
                              << relative_error(Q, Q_ref) << "; order first: " << relative_error(M_first, M_ref) << ", "
                              << relative_error(Q_first, Q_ref));
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

TEST_CASE("order full at quadrature points equals the expanded form, the Jacobian pieces included", "[full]")
{
    // A width taper keeps order full expanded into polynomials of the coordinates; at tip_ratio 1 its beam is the
    // uniform one, whose foreshortening terms are summed at quadrature points: two derivations of the same equations.
    Parameters p;
    p.a = 0.35;
    p.tip_ratio = 1.0;
    std::mt19937 rng(11);
    for (const char* name : {"amm_nx2_ny8_torque_full", "bim_nx2_ny8_prescribed_full", "fem_nx0_ny8_torque_full"}) {
        SECTION(name)
        {
            const VariantKey key = VariantKey::parse(name);
            VariantKey expanded_key = key;
            expanded_key.extras.taper = Taper::width;
            const auto points = make_model(key, p, ModelSource::generated);
            const auto expanded = make_model(expanded_key, p, ModelSource::generated);
            REQUIRE(points->jacobian() != nullptr);
            REQUIRE(expanded->jacobian() != nullptr);
            // Two forms indeed: only the expanded one writes Q as F m.
            CHECK(points->term_forces() == nullptr);
            CHECK(expanded->term_forces() != nullptr);
            const int n = key.nq();
            for (int trial = 0; trial < 3; ++trial) {
                State s = random_state(key, rng);
                s.q.tail(key.ny) *= 10.0;  // deflections of a metre: the point terms far above round-off
                s.qd.tail(key.ny) *= 10.0;
                Eigen::MatrixXd M(n, n), M_x(n, n), dQdq(n, n), dQdq_x(n, n), dQdqd(n, n), dQdqd_x(n, n), dMv(n, n),
                    dMv_x(n, n);
                Eigen::MatrixXd dQdu(3, n), dQdu_x(3, n);
                Eigen::VectorXd Q(n), Q_x(n);
                points->mass(s.u, s.q.data(), M.data());
                expanded->mass(s.u, s.q.data(), M_x.data());
                points->forces(s.u, s.q.data(), s.qd.data(), Q.data());
                expanded->forces(s.u, s.q.data(), s.qd.data(), Q_x.data());
                points->jacobian()->force_derivatives(s.u, s.q.data(), s.qd.data(), dQdq.data(), dQdqd.data(),
                                                      dQdu.data());
                expanded->jacobian()->force_derivatives(s.u, s.q.data(), s.qd.data(), dQdq_x.data(), dQdqd_x.data(),
                                                        dQdu_x.data());
                points->jacobian()->mass_q_product(s.u, s.q.data(), s.qd.data(), dMv.data());
                expanded->jacobian()->mass_q_product(s.u, s.q.data(), s.qd.data(), dMv_x.data());
                const Energy e = points->energy(s.u, s.q.data(), s.qd.data()),
                             e_x = expanded->energy(s.u, s.q.data(), s.qd.data());
                INFO("trial " << trial << ": M " << relative_error(M, M_x) << ", Q " << relative_error(Q, Q_x)
                              << ", dQ/dq " << relative_error(dQdq, dQdq_x) << ", dQ/dqd "
                              << relative_error(dQdqd, dQdqd_x) << ", dQ/du " << relative_error(dQdu, dQdu_x)
                              << ", dM/dq v " << relative_error(dMv, dMv_x));
                CHECK(relative_error(M, M_x) < 1e-12);
                CHECK(relative_error(Q, Q_x) < 1e-12);
                CHECK(relative_error(dQdq, dQdq_x) < 1e-12);
                CHECK(relative_error(dQdqd, dQdqd_x) < 1e-12);
                CHECK(relative_error(dQdu, dQdu_x) < 1e-12);
                CHECK(relative_error(dMv, dMv_x) < 1e-12);
                CHECK(std::abs(e.kinetic() - e_x.kinetic()) < 1e-12 * std::abs(e_x.kinetic()));
                CHECK(std::abs(e.T2 - e_x.T2) < 1e-12 * std::abs(e_x.T2));
                CHECK(std::abs(points->momentum(s.u, s.q.data(), s.qd.data()) -
                               expanded->momentum(s.u, s.q.data(), s.qd.data())) <
                      1e-12 * std::abs(expanded->momentum(s.u, s.q.data(), s.qd.data())) + 1e-300);
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
                          Case{Method::bim, 0, 4, torque(10.0), 10.0}, Case{Method::amm, 0, 8, torque(10.0), 10.0}}) {
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
