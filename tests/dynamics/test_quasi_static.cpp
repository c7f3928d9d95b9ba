// Quasi-static axial coordinates (runtime/src/dynamics/integrate.cpp, docs/model.md section 9): A from the axial equilibrium
// against the rotating bar's closed-form stretch, and the bending response against full axial dynamics.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <hubbeam/fields.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "runs.hpp"

using namespace hubbeam;
using test::run;

namespace {

/// test::paper_scene with the axial model chosen, 20 s, rows every 0.05 s.
Scene paper_scene(Method method, int nx, int ny, Motion motion, Axial axial)
{
    Scene s = test::paper_scene(method, nx, ny, motion);
    s.axial = axial;
    s.output.t_end = 20.0;
    s.output.dt_out = 0.05;
    return s;
}

}  // namespace

TEST_CASE("quasi-static axial coordinates: the rotating bar's centrifugal stretch", "[quasi-static][physics]")
{
    // Steady spin Omega, straight beam (B = 0), a = 0: ES u'' + m Omega^2 (x + u) = 0, u(0) = 0, u'(L) = 0, so
    // u(L) = tan(k L)/k - L with k^2 = m Omega^2 / ES. Linear elements are nodally exact for this bar up to the
    // O((k h)^2) reaction term: about 1e-7 relative here.
    const Parameters p;
    const double m = p.rho * p.S, ES = p.E * p.S;
    for (const ModelSource source : {ModelSource::generated, ModelSource::assembled})
        for (const double omega : {4.0, 10.0}) {
            VariantKey key;
            key.method = Method::fem;
            key.nx = 8;
            key.ny = 8;
            const auto model = make_model(key, p, source);
            const Motion motion{Motion::Kind::spin_up, omega, 15.0, 0.0, 10.0};
            FirstOrderSystem system(*model, motion, Axial::quasi_static);
            REQUIRE(system.size() == 2 * key.ny);
            const std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0);
            std::vector<double> q(static_cast<std::size_t>(key.nq())), qd(q);
            system.full_state(20.0, y.data(), q.data(), qd.data());  // after T_s: steady spin
            const double tip = BeamFields(key, p).tip(q.data(), q.data() + key.nx).ux1;
            const double k = omega * std::sqrt(m / ES);
            const double exact = std::tan(k * p.L) / k - p.L;
            INFO(model->source() << " Omega = " << omega << ": tip u_x1 " << tip << " m, exact " << exact << " m");
            CHECK(std::abs(tip / exact - 1.0) < 1e-6);
            CHECK(std::all_of(qd.begin(), qd.begin() + key.nx, [](double v) { return v == 0.0; }));
        }
}

TEST_CASE("quasi-static axial coordinates follow the bending response of full axial dynamics", "[quasi-static]")
{
    // The axial modes (980 rad/s and up) are three orders above the bending ones: dropping their inertia
    // changes the tip deflection by about (omega_bending / omega_axial)^2 of its size. Measured: 3e-5 of the
    // peak for the 4 rad/s spin-up, 6e-7 under the 10 N m torque; the bounds leave a factor of about 10.
    struct Case {
        Motion motion;
        double bound;
    };
    for (const Case& c : {Case{{Motion::Kind::spin_up, 4.0, 15.0, 0.0, 10.0}, 3e-4},
                          Case{{Motion::Kind::torque, 0.0, 15.0, 10.0, 10.0}, 1e-5}}) {
        const std::vector<Row> qs = run(paper_scene(Method::amm, 4, 4, c.motion, Axial::quasi_static));
        const std::vector<Row> dyn = run(paper_scene(Method::amm, 4, 4, c.motion, Axial::dynamic));
        REQUIRE(qs.size() == dyn.size());
        double diff = 0.0, peak = 0.0;
        for (std::size_t i = 0; i < qs.size(); ++i) {
            diff = std::max(diff, std::abs(qs[i].tip_uy - dyn[i].tip_uy));
            peak = std::max(peak, std::abs(dyn[i].tip_uy));
        }
        INFO("max |tip_uy| difference " << diff << " m of peak " << peak << " m");
        CHECK(diff < c.bound * peak);
        CHECK(diff > 0.0);  // the two models do differ
    }
}

TEST_CASE("quasi-static axial coordinates run with every stepper family", "[quasi-static]")
{
    // Explicit Runge-Kutta (whose stages start from an exactly zero state, where the axial Newton iteration
    // must stop at round-off, not loop), multistep Adams and BDF, and implicit Runge-Kutta (whose Jacobian is
    // the finite-difference one of the reduced system): each agrees with rk8pd at tight tolerance.
    Scene reference = paper_scene(Method::amm, 4, 4, {Motion::Kind::spin_up, 4.0, 15.0, 0.0, 10.0}, Axial::quasi_static);
    reference.output.t_end = 3.0;
    reference.solver.stepper = "rk8pd";
    const std::vector<Row> ref = run(reference);
    for (const char* stepper : {"rkck", "msadams", "msbdf", "rk4imp"}) {
        Scene s = reference;
        s.solver.stepper = stepper;
        s.solver.rtol = 1e-9;
        s.solver.atol = 1e-11;
        const std::vector<Row> rows = run(s);
        REQUIRE(rows.size() == ref.size());
        double diff = 0.0, peak = 0.0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            diff = std::max(diff, std::abs(rows[i].tip_uy - ref[i].tip_uy));
            peak = std::max(peak, std::abs(ref[i].tip_uy));
        }
        INFO(stepper << ": max |tip_uy - rk8pd| " << diff << " m of peak " << peak << " m");
        CHECK(diff < 1e-5 * peak);
    }
}
