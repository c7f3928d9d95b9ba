// Free stepping (solver.stepping = "free"): rows interpolated between step ends by the quintic Hermite interpolant
// of positions, rates and accelerations, with its error estimated at each step's middle; against polynomials it
// must reproduce, its convergence order, and runs of every stepper against a tight reference. The right-hand-side
// strategies (acceleration.hpp), each against the plain dense solve of M qdd = Q at random states, and the factory's
// choice among them.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gsl/gsl_errno.h>

#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include "dynamics/acceleration.hpp"
#include "dynamics/integrate.hpp"
#include "forwarding_model.hpp"
#include "models/generated_model.hpp"
#include "random_state.hpp"
#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

namespace {

/// y = (p, v) and f = (v, a) at t for p(t) = sin(w t) and p(t) = t^5 - 2 t^3 + t.
struct Sample {
    std::vector<double> y, f;
};
Sample sample(double t, double w)
{
    const double p1 = std::sin(w * t), v1 = w * std::cos(w * t), a1 = -w * w * std::sin(w * t);
    const double p2 = std::pow(t, 5) - 2 * std::pow(t, 3) + t, v2 = 5 * std::pow(t, 4) - 6 * t * t + 1,
                 a2 = 20 * std::pow(t, 3) - 12 * t;
    return {{p1, p2, v1, v2}, {v1, v2, a1, a2}};
}

}  // namespace

TEST_CASE("interpolate_state reproduces quintics and converges as h^6 (positions) and h^5 (rates)", "[stepping]")
{
    const double w = 3.0, t0 = 0.4;
    double previous_p = 0.0, previous_v = 0.0;
    for (const double h : {0.4, 0.2, 0.1, 0.05}) {
        const Sample a = sample(t0, w), b = sample(t0 + h, w);
        double error_p = 0.0, error_v = 0.0;
        for (const double s : {0.1, 0.3, 0.5, 0.77}) {
            const double t = t0 + s * h;
            std::vector<double> y(4);
            interpolate_state(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(), t, 4, y.data());
            const Sample exact = sample(t, w);
            // The quintic polynomial (second position) exactly, to round-off.
            CHECK(std::abs(y[1] - exact.y[1]) <= 1e-13);
            CHECK(std::abs(y[3] - exact.y[3]) <= 1e-12);
            error_p = std::max(error_p, std::abs(y[0] - exact.y[0]));
            error_v = std::max(error_v, std::abs(y[2] - exact.y[2]));
        }
        if (previous_p > 0.0) {
            INFO("h = " << h << ": position error " << error_p << " (was " << previous_p << "), rate error " << error_v
                        << " (was " << previous_v << ")");
            CHECK(previous_p / error_p > 0.8 * 64.0);
            CHECK(previous_v / error_v > 0.8 * 32.0);
        }
        previous_p = error_p;
        previous_v = error_v;
    }
}

TEST_CASE("interpolation_error estimates the interpolant's error at the step's middle", "[stepping]")
{
    const double w = 3.0, t0 = 0.4;
    for (const double h : {0.2, 0.1, 0.05}) {
        const Sample a = sample(t0, w), b = sample(t0 + h, w);
        std::vector<double> y_mid(4);
        interpolate_state(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(), t0 + h / 2, 4, y_mid.data());
        // The equations' acceleration at the interpolated state: p'' = -w^2 p (sine) and the quintic's own.
        const Sample exact = sample(t0 + h / 2, w);
        std::vector<double> f_mid = {y_mid[2], y_mid[3], -w * w * y_mid[0], exact.f[3]};
        const double estimate = interpolation_error(t0, a.y.data(), a.f.data(), t0 + h, b.y.data(), b.f.data(),
                                                    y_mid.data(), f_mid.data(), 4, 1.0, 0.0);
        const double actual = std::abs(y_mid[0] - exact.y[0]);
        INFO("h = " << h << ": estimate " << estimate << ", actual " << actual);
        CHECK(estimate > 0.5 * actual);
        CHECK(estimate < 2.0 * actual);
    }
}

TEST_CASE("free stepping: every stepper's interpolated rows are as accurate as a step at every row", "[stepping]")
{
    // The spin-up without axial coordinates, 3 s into the drive; a tight reference with a step at every row.
    Scene reference = paper_scene(Method::amm, 0, 4, spin_up(4.0));
    reference.output.t_end = 3.0;
    reference.solver.stepper = "rk8pd";
    reference.solver.rtol = reference.solver.atol = 1e-14;
    reference.solver.stepping = Stepping::rows;
    const std::vector<Row> exact = run(reference);
    double scale = 0.0;
    for (const Row& r : exact) scale = std::max(scale, std::abs(r.tip_uy));
    const auto error = [&](const std::vector<Row>& rows) {
        REQUIRE(rows.size() == exact.size());
        double e = 0.0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            CHECK(rows[i].t == exact[i].t);
            e = std::max(e, std::abs(rows[i].tip_uy - exact[i].tip_uy));
        }
        return e;
    };
    for (const std::string& stepper : stepper_names()) {
        const bool low_order = stepper == "rk2" || stepper == "rk2imp" || stepper == "rk1imp";
        Scene s = reference;
        s.solver.stepper = stepper;
        s.solver.rtol = s.solver.atol = low_order ? 1e-6 : 1e-9;
        s.solver.stepping = Stepping::rows;
        const double at_rows = error(run(s));
        s.solver.stepping = Stepping::free;
        const double free = error(run(s));
        INFO(stepper << ": free " << free << " m, a step at every row " << at_rows << " m, scale " << scale << " m");
        CHECK(free <= std::max(2.0 * at_rows, 50.0 * s.solver.rtol * scale));
    }
}

namespace {

/// qdd of the plain dense solve of M(q) qdd = Q(u, q, qd).
Eigen::VectorXd dense_accelerations(const Model& model, const HubInput& u, const Eigen::VectorXd& q, const Eigen::VectorXd& qd)
{
    const int n = model.nq();
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd Q(n);
    model.mass(u, q.data(), M.data());
    model.forces(u, q.data(), qd.data(), Q.data());
    return M.selfadjointView<Eigen::Upper>().llt().solve(Q);
}

/// The strategy's accelerations against the dense solve at random states, within 1e-9 of the largest.
void check_against_dense(RightHandSide& rhs, const Model& model, int seed)
{
    std::mt19937 rng(static_cast<unsigned>(seed));
    const int n = model.nq();
    for (int trial = 0; trial < 5; ++trial) {
        const test::State s = test::random_state(model.key(), rng);
        Eigen::VectorXd y(2 * n), dydt(2 * n);
        y << s.q, s.qd;
        REQUIRE(rhs.derivative(s.u, y.data(), dydt.data()) == GSL_SUCCESS);
        const Eigen::VectorXd qdd = dense_accelerations(model, s.u, s.q, s.qd);
        INFO(model.key().name() << " " << rhs.describe() << " trial " << trial);
        CHECK(dydt.head(n) == s.qd);
        CHECK((dydt.tail(n) - qdd).cwiseAbs().maxCoeff() <= 1e-9 * qdd.cwiseAbs().maxCoeff());
    }
}

VariantKey key_of(Method method, int nx, int ny, Drive drive) { return {.method = method, .nx = nx, .ny = ny, .drive = drive, .extras = {}}; }

/// A model that reports some of its hub couplings as varying although they are constant: varying and constant
/// couplings at once, which no generated variant has. Like a generated model, it writes only the entries its
/// pattern marks varying where asked for those.
class SomeCouplingsVary final : public test::ForwardingModel {
public:
    SomeCouplingsVary(std::unique_ptr<Model> inner, std::vector<int> varying)
        : ForwardingModel(std::move(inner)), varying_(std::move(varying))
    {
    }
    bool mass_is_constant() const override { return false; }
    std::string mass_pattern() const override
    {
        std::string p = inner().mass_pattern();
        for (const int j : varying_) p[static_cast<std::size_t>(j)] = p[static_cast<std::size_t>(j * nq())] = 'v';
        return p;
    }
    void mass_varying(const HubInput& u, const double* q, double* M) const override
    {
        std::vector<double> all(static_cast<std::size_t>(nq() * nq()));
        inner().mass(u, q, all.data());
        const std::string p = mass_pattern();
        for (std::size_t e = 0; e < all.size(); ++e)
            if (p[e] == 'v') M[e] = all[e];
    }
    const TermForces* term_forces() const override { return inner().term_forces(); }

private:
    std::vector<int> varying_;
};

}  // namespace

TEST_CASE("after rows that each ended a step, the steps grow back to what the tolerance asks", "[stepping]")
{
    // FEM at Nx = Ny = 32 on gauss4 spinning up (cases/spinup_omega4.toml): a stiff mode ringing at the tolerance
    // fails the interpolant's test at some steps, which bounds the next ones below a quarter of the rows' spacing, so
    // that each step ends at a row. How many steps the motion needs does not depend on how densely its rows are
    // written: rows five times as dense as the steps (dt_out = 0.002 s) are interpolated inside free steps all along,
    // and rows at 0.005 s must cost about as many steps once the ringing is gone. A bound that is never lifted holds
    // the steps short until the end (four times as many).
    const auto steps = [](const char* dt_out) {
        const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/spinup_omega4.toml",
                                   {{"discretization.method", "fem"},
                                    {"discretization.nx", "32"},
                                    {"discretization.ny", "32"},
                                    {"solver.stepper", "gauss4"},
                                    {"output.t_end", "20"},
                                    {"output.dt_out", dt_out}});
        const RunSummary r = completed_run(s).summary;
        REQUIRE(r.stepper.rfind("gauss4", 0) == 0);
        return r.steps;
    };
    const long dense = steps("0.002"), sparse = steps("0.005");
    INFO("steps with rows every 0.002 s: " << dense << ", every 0.005 s: " << sparse);
    // The rows at 0.005 s end some steps early and bound others while the ringing lasts: a tenth more is room.
    CHECK(sparse < 1.1 * static_cast<double>(dense));
    // And fewer steps than rows (4,000): rows are interpolated inside steps.
    CHECK(sparse < 4000);
}

TEST_CASE("every right-hand-side strategy solves M qdd = Q", "[stepping][strategy]")
{
    const Parameters p;
    const HubInput rest;
    SECTION("constant M folded into the forces: by the kernel, dense and by rows")
    {
        for (const Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
            const auto model = make_model(key_of(method, 4, 4, Drive::prescribed), p, ModelSource::generated);
            REQUIRE(model->folded_kernel() != nullptr);
            REQUIRE(model->term_forces() != nullptr);
            const TermForces& terms = *model->term_forces();
            const Eigen::MatrixXd W = folded_forces(*model, terms, rest);
            Folded kernel(*model, terms, model->folded_kernel(), W);
            FoldedDense dense(*model, terms, W);
            Folded sparse(*model, terms, nullptr, W);
            check_against_dense(kernel, *model, 1);
            check_against_dense(dense, *model, 2);
            check_against_dense(sparse, *model, 3);
        }
    }
    SECTION("the hub's row by its Schur complement, with constant couplings (no axial coordinates) and varying ones")
    {
        for (const int nx : {0, 4})
            for (const Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
                const auto model = make_model(key_of(method, nx, 4, Drive::torque), p, ModelSource::generated);
                REQUIRE(model->term_forces() != nullptr);
                HubSchur hub(*model, *model->term_forces(), rest);
                check_against_dense(hub, *model, 4);
            }
    }
    SECTION("the hub's row by its Schur complement, with varying and constant couplings at once")
    {
        // Without axial coordinates every coupling is constant; two of them reported as varying take the path of
        // varying couplings beside the constant ones (the constant ones must stay in the hub's row it reads).
        SomeCouplingsVary model(make_model(key_of(Method::fem, 0, 4, Drive::torque), p, ModelSource::generated),
                                {1, 3});
        HubSchur hub(model, *model.term_forces(), rest);
        REQUIRE(hub.coupling_nonzeros() > 0);
        check_against_dense(hub, model, 10);
    }
    SECTION("the mass solver, for constant and varying M, generated and assembled")
    {
        for (const Drive drive : {Drive::prescribed, Drive::torque})
            for (const ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
                const auto model = make_model(key_of(Method::fem, 4, 4, drive), p, source);
                MassSolved solved(*model);
                check_against_dense(solved, *model, 5);
            }
    }
    SECTION("quasi-static axial coordinates: the axial rows in equilibrium, the others solved densely")
    {
        for (const Drive drive : {Drive::prescribed, Drive::torque}) {
            const auto model = make_model(key_of(Method::amm, 4, 4, drive), p, ModelSource::generated);
            const VariantKey& key = model->key();
            QuasiStaticAxial quasi(*model);
            std::mt19937 rng(6);
            const int n = model->nq(), r = n - key.nx;
            for (int trial = 0; trial < 5; ++trial) {
                const test::State s = test::random_state(key, rng);
                Eigen::VectorXd y(2 * r), dydt(2 * r), q(n), qd(n);
                for (int i = 0, k = 0; i < n; ++i)
                    if (coordinate_layout(key).field_of(i).kind != FieldKind::axial) {
                        y[k] = s.q[i];
                        y[r + k] = s.qd[i];
                        ++k;
                    }
                REQUIRE(quasi.derivative(s.u, y.data(), dydt.data()) == GSL_SUCCESS);
                REQUIRE(quasi.full_state(s.u, y.data(), q.data(), qd.data()));
                INFO(key.name() << " trial " << trial);
                // The axial rows of Q vanish with A_dot = 0 and the hub acceleration's axial term dropped.
                HubInput ua = s.u;
                ua.theta_ddot = 0.0;
                Eigen::VectorXd Q(n);
                model->forces(ua, q.data(), qd.data(), Q.data());
                Eigen::VectorXd Q0(n);
                model->forces(ua, Eigen::VectorXd::Zero(n).eval().data(), qd.data(), Q0.data());
                const int a = coordinate_layout(key).first(FieldKind::axial);
                CHECK(Q.segment(a, key.nx).cwiseAbs().maxCoeff() <= 1e-9 * Q0.segment(a, key.nx).cwiseAbs().maxCoeff() + 1e-12);
                CHECK(qd.segment(a, key.nx).cwiseAbs().maxCoeff() == 0.0);
                // The other rows: M_rr qdd_r = Q_r by a dense solve.
                Eigen::MatrixXd M(n, n);
                model->mass(s.u, q.data(), M.data());
                model->forces(s.u, q.data(), qd.data(), Q.data());
                std::vector<int> kept;
                for (int i = 0; i < n; ++i)
                    if (coordinate_layout(key).field_of(i).kind != FieldKind::axial) kept.push_back(i);
                Eigen::MatrixXd Mr(r, r);
                Eigen::VectorXd Qr(r);
                for (int i = 0; i < r; ++i) {
                    Qr[i] = Q[kept[static_cast<std::size_t>(i)]];
                    for (int j = 0; j < r; ++j) Mr(i, j) = M(kept[static_cast<std::size_t>(i)], kept[static_cast<std::size_t>(j)]);
                }
                const Eigen::VectorXd qdd = Mr.selfadjointView<Eigen::Upper>().llt().solve(Qr);
                CHECK((dydt.tail(r) - qdd).cwiseAbs().maxCoeff() <= 1e-9 * qdd.cwiseAbs().maxCoeff());
                CHECK(dydt.head(r) == y.tail(r));
            }
        }
    }
}

TEST_CASE("a right-hand side whose accelerations are not finite says so, whichever strategy computes them",
          "[stepping][strategy]")
{
    // GSL_EBADFUNC is what makes a step fail instead of carrying NaN into the state (the run then stops with its
    // message). A rate of 1e200 overflows the velocity terms to infinity; NaN propagates from any coordinate.
    const Parameters p;
    const Motion spin = spin_up(4.0), hub_torque = torque(1.0);
    struct Case {
        VariantKey key;
        const Motion& motion;
        ModelSource source;
    };
    for (const Case& c : {Case{key_of(Method::amm, 4, 4, Drive::prescribed), spin, ModelSource::generated},
                          Case{key_of(Method::fem, 0, 4, Drive::torque), hub_torque, ModelSource::generated},
                          Case{key_of(Method::amm, 4, 4, Drive::torque), hub_torque, ModelSource::generated},
                          Case{key_of(Method::fem, 4, 4, Drive::torque), hub_torque, ModelSource::assembled}}) {
        const auto model = make_model(c.key, p, c.source);
        const auto rhs = make_right_hand_side(*model, c.motion, Axial::dynamic);
        INFO(c.key.name() << ": " << rhs->describe());
        const int n = model->nq();
        const HubInput u = c.motion.at(1.0);
        for (int i = 0; i < 2 * n; ++i)
            for (const double bad : {std::numeric_limits<double>::quiet_NaN(), 1e200}) {
                std::vector<double> y(2 * static_cast<std::size_t>(n), 1e-3), dydt(y.size());
                REQUIRE(rhs->derivative(u, y.data(), dydt.data()) == GSL_SUCCESS);
                y[static_cast<std::size_t>(i)] = bad;
                const int status = rhs->derivative(u, y.data(), dydt.data());
                bool finite = true;
                for (int k = n; k < 2 * n; ++k) finite = finite && std::isfinite(dydt[static_cast<std::size_t>(k)]);
                INFO("entry " << i << " of y set to " << bad);
                // Success only with finite accelerations. A bad entry may leave them all finite (the hub's angle
                // enters no equation without gravity, some are linear in a huge coordinate), or make M indefinite
                // first, which fails the same way.
                CHECK((status == GSL_SUCCESS ? finite : status == GSL_EBADFUNC));
            }
    }
}

TEST_CASE("the factory picks the strategy from the model's structure", "[stepping][strategy]")
{
    const Parameters p;
    const Motion spin = spin_up(4.0), hub_torque = torque(1.0);
    const auto picks = [&](const VariantKey& key, const Motion& motion, Axial axial, ModelSource source) {
        const auto model = make_model(key, p, source);
        return std::shared_ptr<RightHandSide>(make_right_hand_side(*model, motion, axial).release());
    };
    // The paper's spin-up, with and without axial coordinates: the generated kernel holds W's structural nonzeros.
    for (const int nx : {4, 0}) {
        const auto folded = picks(key_of(Method::amm, nx, 4, Drive::prescribed), spin, Axial::dynamic, ModelSource::generated);
        CHECK(dynamic_cast<Folded*>(folded.get()));
        CHECK(folded->describe().find("by the generated kernel") != std::string::npos);
    }
    // A free hub: M varies in the hub's row only (its entry, and with axial coordinates its couplings).
    CHECK(dynamic_cast<HubSchur*>(picks(key_of(Method::bim, 0, 4, Drive::torque), hub_torque, Axial::dynamic, ModelSource::generated).get()));
    CHECK(dynamic_cast<HubSchur*>(picks(key_of(Method::amm, 4, 4, Drive::torque), hub_torque, Axial::dynamic, ModelSource::generated).get()));
    // The assembled path has no term form.
    CHECK(dynamic_cast<MassSolved*>(picks(key_of(Method::amm, 4, 4, Drive::torque), hub_torque, Axial::dynamic, ModelSource::assembled).get()));
    CHECK(dynamic_cast<MassSolved*>(picks(key_of(Method::amm, 4, 4, Drive::prescribed), spin, Axial::dynamic, ModelSource::assembled).get()));
    CHECK(dynamic_cast<QuasiStaticAxial*>(picks(key_of(Method::amm, 4, 4, Drive::torque), hub_torque, Axial::quasi_static, ModelSource::generated).get()));
    CHECK_THROWS_AS(picks(key_of(Method::amm, 0, 4, Drive::torque), hub_torque, Axial::quasi_static, ModelSource::generated), std::invalid_argument);
}

TEST_CASE("every generated folded kernel reads every entry of the folded product that can be nonzero", "[stepping][strategy]")
{
    // The kernels skip the entries their generator proved structurally zero. Against the walk over every nonzero of
    // the same P at random states (the same sums in the same order) and against a dense solve of M qdd = Q: a
    // pattern that missed an entry would differ, and the start-up check would hand the work to the walk, which the
    // describe() line gives away. Extra terms switched on, so that their entries are nonzero.
    Parameters base;
    base.a = 0.2, base.m_tip = 0.3, base.J_tip = 0.02, base.g = 9.81, base.alpha = 0.05, base.beta = 2e-4;
    base.tip_ratio = 0.6;
    std::mt19937 rng(7);
    int kernels = 0;
    for (const std::string& name : generated_variant_names()) {
        const VariantKey key = VariantKey::parse(name);
        const auto model = make_model(key, test::with_profile(key, base), ModelSource::generated);
        if (model->folded_kernel() == nullptr) continue;
        REQUIRE(model->term_forces() != nullptr);
        const TermForces& terms = *model->term_forces();
        const int n = model->nq();
        INFO(name);
        if (model->mass_is_constant()) {
            const Eigen::MatrixXd W = folded_forces(*model, terms, HubInput{});
            FoldedProduct by_kernel(terms, model->folded_kernel(), W), by_walk(terms, nullptr, W);
            REQUIRE(by_kernel.by_kernel());
            Eigen::VectorXd m(terms.term_count()), y_kernel(n), y_walk(n);
            for (int trial = 0; trial < 3; ++trial) {
                const test::State s = test::random_state_with_angle(key, rng);
                by_kernel.apply(s.u, s.q.data(), s.qd.data(), y_kernel.data());
                by_walk.apply(s.u, s.q.data(), s.qd.data(), y_walk.data());
                terms.terms(s.u, s.q.data(), s.qd.data(), m.data());
                const Eigen::VectorXd scale = W.cwiseAbs() * m.cwiseAbs();
                for (int i = 0; i < n; ++i) CHECK(std::abs(y_kernel[i] - y_walk[i]) <= 1e-13 * scale[i]);
            }
            Folded folded(*model, terms, model->folded_kernel(), W);
            check_against_dense(folded, *model, 8);
        } else {
            HubSchur hub(*model, terms, HubInput{});
            CHECK(hub.describe().find("by the generated kernel") != std::string::npos);
            check_against_dense(hub, *model, 9);
        }
        ++kernels;
    }
    CHECK(kernels >= 40);
}
