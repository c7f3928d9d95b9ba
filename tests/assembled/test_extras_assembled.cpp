// The terms beyond the paper's beam (docs/model.md section 11: tip body, taper, gravity, Rayleigh damping) on two
// independent paths: the generated kernels (symbolic energies and dissipation function, exact integrals) against the
// hand-assembled matrices (runtime/src/models/assembled/assembled.cpp: quadrature with the profile as a weight, point values at
// the tip) at random states, term by term; and the assembled forces against the assembled energies (Lagrange's
// equations by exact differences) and against the damping matrices that section 11 states.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <hubbeam/make_model.hpp>
#include "eigen_oracles.hpp"
#include "gauss_legendre.hpp"
#include "models/generated_model.hpp"
#include "model_values.hpp"
#include "random_state.hpp"
#include "shared_oracles.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

/// One extra term switched on by its values, the others at the values that switch them off; or all of them.
enum class Term { tip, taper, gravity, damping, all };
const char* term_name(Term t)
{
    switch (t) {
    case Term::tip: return "tip body";
    case Term::taper: return "taper";
    case Term::gravity: return "gravity";
    case Term::damping: return "damping";
    case Term::all: return "all terms";
    }
    return "";
}
constexpr Term extra_terms[] = {Term::tip, Term::taper, Term::gravity, Term::damping, Term::all};

/// The paper's beam on a hub of radius 0.35 m (so the terms in a show), with the values of `on` at sizes where
/// each term is a sizeable part of what it adds to: a payload of a third of the beam's mass, a section halved at
/// the tip, Earth's gravity, damping ratios of a few percent in the first bending mode.
Parameters parameters_with(Term on)
{
    Parameters p;
    p.a = 0.35;
    if (on == Term::tip || on == Term::all) {
        p.m_tip = 0.55;
        p.J_tip = 0.35;
    }
    if (on == Term::taper || on == Term::all) p.tip_ratio = 0.45;
    if (on == Term::gravity || on == Term::all) p.g = 9.81;
    if (on == Term::damping || on == Term::all) {
        p.alpha = 0.15;
        p.beta = 2.5e-3;
    }
    return p;
}

using test::energy_of;
using test::forces_of;
using test::forces_theta_of;
using test::mass_of;

/// The generated variants of this build that carry extra terms, but a profile (whose terms with a table
/// tests/test_profile.cpp checks the same way).
std::vector<VariantKey> extras_variants()
{
    std::vector<VariantKey> keys;
    for (const std::string& name : generated_variant_names())
        if (VariantKey k = VariantKey::parse(name); k.extras.any() && !k.extras.profile()) keys.push_back(k);
    return keys;
}

/// Every assembled variant the Lagrange checks cover: each method (BSIM in both constructions), both drives, orders
/// zero and first, Nx in {0, 4}, with a tip body, gravity, damping and a width or a depth taper.
std::vector<VariantKey> assembled_variants()
{
    std::vector<VariantKey> keys;
    const std::pair<Method, SplineBasis> methods[] = {{Method::amm, SplineBasis::paper},
                                                      {Method::fem, SplineBasis::paper},
                                                      {Method::bim, SplineBasis::paper},
                                                      {Method::bsim, SplineBasis::paper},
                                                      {Method::bsim, SplineBasis::open}};
    for (const auto& [method, spline] : methods)
        for (Drive drive : {Drive::prescribed, Drive::torque})
            for (Order order : {Order::zero, Order::first})
                for (int nx : {0, 4})
                    for (Taper taper : {Taper::width, Taper::depth})
                        keys.push_back({.method = method, .nx = nx, .ny = 4, .order = order, .drive = drive,
                                        .spline = spline,
                                        .extras = {.tip = true, .gravity = true, .damping = true, .taper = taper}});
    return keys;
}

}  // namespace

TEST_CASE("generated and assembled agree on every extra term", "[extras][generated][assembled]")
{
    const std::vector<VariantKey> keys = extras_variants();
    // Each method under both drives and both orders is in the build (generator/variants.txt).
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim})
        for (Drive drive : {Drive::prescribed, Drive::torque})
            for (Order order : {Order::zero, Order::first}) {
                const bool built = std::any_of(keys.begin(), keys.end(), [&](const VariantKey& k) {
                    return k.method == method && k.drive == drive && k.order == order && k.extras.tip &&
                           k.extras.gravity && k.extras.damping && k.extras.taper != Taper::uniform;
                });
                INFO(to_string(method) << " " << to_string(drive) << " " << to_string(order));
                CHECK(built);
            }
    std::mt19937 rng(1877);
    for (const VariantKey& key : keys)
        for (Term term : extra_terms) {
            SECTION(key.name() + ", " + term_name(term))
            {
                const Parameters p = parameters_with(term);
                const auto gen = make_model(key, p, ModelSource::generated);
                const auto asm_ = make_model(key, p, ModelSource::assembled);
                const auto plain = make_model(key, Parameters{.a = 0.35}, ModelSource::assembled);  // no extra term
                REQUIRE(std::string(gen->source()) == "generated");
                REQUIRE(std::string(asm_->source()) == "assembled");
                CHECK(gen->mass_is_constant() == asm_->mass_is_constant());
                double shown = 0.0;  // the largest relative change the term makes to M, Q or the energies
                for (int trial = 0; trial < 4; ++trial) {
                    const test::State s = test::random_state_with_angle(key, rng);
                    INFO("trial " << trial << ", theta " << s.u.theta);
                    const MatrixXd Mg = mass_of(*gen, s), Ma = mass_of(*asm_, s);
                    CHECK(test::relative_error(Mg.reshaped(), Ma.reshaped()) < 1e-12);
                    const VectorXd Qg = forces_of(*gen, s), Qa = forces_of(*asm_, s);
                    CHECK(test::relative_error(Qg, Qa) < 1e-12);
                    const Eigen::Vector4d eg = energy_of(*gen, s), ea = energy_of(*asm_, s);
                    // Each part against the largest, so that a T1 or T0 of zero compares as one.
                    CHECK((eg - ea).lpNorm<Eigen::Infinity>() < 1e-12 * ea.lpNorm<Eigen::Infinity>());
                    const double hg = gen->momentum(s.u, s.q.data(), s.qd.data());
                    const double ha = asm_->momentum(s.u, s.q.data(), s.qd.data());
                    CHECK(std::abs(hg - ha) <= 1e-12 * std::abs(ha));
                    const VectorXd dg = forces_theta_of(*gen, s), da = forces_theta_of(*asm_, s);
                    if (p.g != 0.0 && key.drive == Drive::prescribed) {
                        REQUIRE(da.lpNorm<Eigen::Infinity>() > 0.0);
                        CHECK(test::relative_error(dg, da) < 1e-12);
                    } else {
                        CHECK(dg.lpNorm<Eigen::Infinity>() == 0.0);
                        CHECK(da.lpNorm<Eigen::Infinity>() == 0.0);
                    }
                    shown = std::max({shown, test::relative_error(mass_of(*plain, s).reshaped(), Ma.reshaped()),
                                      test::relative_error(forces_of(*plain, s), Qa),
                                      test::relative_error(energy_of(*plain, s), ea)});
                }
                // The comparison means something only where the term changes what is compared.
                CHECK(shown > 1e-4);
            }
        }
}

TEST_CASE("assembled extra terms: forces from the assembled energies and dissipation", "[extras][assembled]")
{
    std::mt19937 rng(1945);
    for (const VariantKey& key : assembled_variants()) {
        SECTION(key.name())
        {
            Parameters conservative = parameters_with(Term::all);
            conservative.alpha = conservative.beta = 0.0;
            const auto model = make_model(key, conservative, ModelSource::assembled);
            const int n = key.nq(), o = coordinate_layout(key).first(FieldKind::axial);
            for (int trial = 0; trial < 3; ++trial) {
                const test::State s = test::random_state_with_angle(key, rng);
                INFO("trial " << trial);
                // Tip body, taper and gravity are conservative: Q is Lagrange's from T and U alone.
                const VectorXd Q = forces_of(*model, s), QL = test::lagrange_forces(*model, s);
                CHECK(test::relative_error(Q, QL) < 1e-9);
                // The mass matrix is T's Hessian in the rates (T is quadratic in them: exact differences).
                MatrixXd H(n, n);
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        const VectorXd ei = VectorXd::Unit(n, i), ej = VectorXd::Unit(n, j);
                        const auto T = [&](const VectorXd& qd) { return model->energy(s.u, s.q.data(), qd.data()).kinetic(); };
                        H(i, j) = 0.25 * (T(s.qd + ei + ej) - T(s.qd + ei - ej) - T(s.qd - ei + ej) + T(s.qd - ei - ej));
                    }
                CHECK(test::relative_error(mass_of(*model, s).reshaped(), H.reshaped()) < 1e-9);
                if (key.drive == Drive::prescribed) {
                    // dQ/dtheta: Q is affine in (sin theta, cos theta), so the difference over 2 sin(h) is exact.
                    test::State up = s, down = s;
                    up.u.theta += 1.0;
                    down.u.theta -= 1.0;
                    const VectorXd dQ = (forces_of(*model, up) - forces_of(*model, down)) / (2.0 * std::sin(1.0));
                    CHECK(test::relative_error(forces_theta_of(*model, s), dQ) < 1e-9);
                }
            }

            // Rayleigh damping: the forces it adds are -(alpha M_ee + beta K_e) qd_e with M_ee the elastic block of
            // the model's own mass matrix and K_e = -dQ/dq_e at rest (no spin, no weight; exact by columns).
            const Parameters damped = parameters_with(Term::all);
            const auto with = make_model(key, damped, ModelSource::assembled);
            Parameters still = conservative;
            still.g = 0.0;
            const auto rest = make_model(key, still, ModelSource::assembled);
            const int ne = n - o;
            test::State zero{VectorXd::Zero(n), VectorXd::Zero(n), HubInput{}};
            const MatrixXd M_ee = mass_of(*rest, zero).bottomRightCorner(ne, ne);
            MatrixXd K_e(ne, ne);
            for (int j = 0; j < ne; ++j) {
                test::State moved = zero;
                moved.q(o + j) = 1.0;
                K_e.col(j) = -forces_of(*rest, moved).tail(ne);
            }
            for (int trial = 0; trial < 3; ++trial) {
                const test::State s = test::random_state_with_angle(key, rng);
                const VectorXd added = forces_of(*with, s) - forces_of(*model, s);
                const VectorXd expected = -(damped.alpha * M_ee + damped.beta * K_e) * s.qd.tail(ne);
                CHECK(test::relative_error(added.tail(ne), expected) < 1e-9);
                CHECK(added.head(o).lpNorm<Eigen::Infinity>() == 0.0);  // the hub's rate is not damped
                // D = -1/2 qd . Q_damping >= 0: damping only dissipates.
                CHECK(-s.qd.tail(ne).dot(added.tail(ne)) > 0.0);
            }
        }
    }
}

namespace {

/// Non-rotating, no gravity, prescribed form without axial coordinates: M and K = -dQ/dq (exact by columns, Q is
/// linear in q) and C = -dQ/dqd of a model at rest.
struct Linear {
    MatrixXd M, K, C;
};
Linear at_rest(const Model& model)
{
    const int n = model.nq();
    test::State s{VectorXd::Zero(n), VectorXd::Zero(n), HubInput{}};
    Linear l{mass_of(model, s), MatrixXd(n, n), MatrixXd(n, n)};
    const VectorXd Q0 = forces_of(model, s);
    for (int j = 0; j < n; ++j) {
        test::State moved = s, moving = s;
        moved.q(j) = 1.0;
        moving.qd(j) = 1.0;
        l.K.col(j) = Q0 - forces_of(model, moved);
        l.C.col(j) = Q0 - forces_of(model, moving);
    }
    return l;
}

VariantKey still_key(Method method, int nx, int ny, Extras extras)
{
    return {.method = method, .nx = nx, .ny = ny, .order = Order::first, .drive = Drive::prescribed, .extras = extras};
}

}  // namespace

TEST_CASE("assembled tip mass: the cantilever's frequency equation", "[extras][assembled][physics]")
{
    // A tip mass of half the beam's (Laura, Pombo & Susemihl 1974): omega = z^2 sqrt(EI / (m L^4)).
    Parameters p;
    const double m = p.rho * p.S, mu = 0.5;
    p.m_tip = mu * m * p.L;
    const std::vector<double> z = test::tip_mass_roots(mu, 3);
    REQUIRE(z[0] < 1.8751);  // a tip mass lowers the first root below the bare cantilever's
    // Rayleigh-Ritz from above, to each method's convergence at these counts (AMM's clamped-free modes miss the
    // tip's shear force, so converge slowest; BIM spectrally).
    for (auto [method, ny, tolerance] : {std::tuple{Method::bim, 12, 1e-9}, std::tuple{Method::fem, 32, 1e-4},
                                         std::tuple{Method::bsim, 24, 2e-5}, std::tuple{Method::amm, 16, 3e-4}}) {
        INFO(to_string(method) << " ny " << ny);
        const Linear l = at_rest(*make_model(still_key(method, 0, ny, {.tip = true}), p, ModelSource::assembled));
        const test::SymmetricEigen es = test::generalized_eigen(l.K, l.M, false);
        REQUIRE(es.converged);
        for (int i = 0; i < 3; ++i) {
            const double exact = z[i] * z[i] * std::sqrt(p.E * p.I / (m * std::pow(p.L, 4)));
            CHECK(std::sqrt(es.values(i)) == Approx(exact).epsilon(tolerance));
        }
    }
}

TEST_CASE("assembled weight, taper and tip mass: the static deflection of a horizontal cantilever", "[extras][assembled][physics]")
{
    // Held horizontal (theta = 0, no spin), a cantilever under its own weight q(x) = g m s(x/L) and a tip weight
    // g m_tip: M(x) = int_x^L q(t) (t - x) dt + g m_tip (L - x), and by the unit-load method
    // u_y(L) = -int_0^L M(x) (L - x) / EI(x) dx. Gauss-Legendre on [0, L] converged (the integrand is smooth).
    Parameters p;
    p.g = 9.81;
    p.m_tip = 0.4;
    p.tip_ratio = 0.5;
    const double m = p.rho * p.S, EI = p.E * p.I, L = p.L;
    for (Taper taper : {Taper::width, Taper::depth}) {
        const auto s = [&](double x) { return 1.0 + (p.tip_ratio - 1.0) * x / L; };
        const auto ei = [&](double x) { return EI * (taper == Taper::depth ? std::pow(s(x), 3) : s(x)); };
        const test::GaussRule rule = test::gauss_legendre(40);  // on [-1, 1]: node (1 + x)/2, weight w/2 on [0, 1]
        const auto moment = [&](double x) {
            double M = p.g * p.m_tip * (L - x);
            for (std::size_t k = 0; k < rule.x.size(); ++k) {
                const double t = x + (L - x) * 0.5 * (1.0 + rule.x[k]);
                M += (L - x) * 0.5 * rule.w[k] * p.g * m * s(t) * (t - x);
            }
            return M;
        };
        double exact = 0.0;
        for (std::size_t k = 0; k < rule.x.size(); ++k) {
            const double x = L * 0.5 * (1.0 + rule.x[k]);
            exact -= L * 0.5 * rule.w[k] * moment(x) * (L - x) / ei(x);
        }
        for (auto [method, ny, tolerance] : {std::tuple{Method::bim, 14, 1e-9}, std::tuple{Method::fem, 32, 1e-6},
                                             std::tuple{Method::bsim, 32, 1e-6}, std::tuple{Method::amm, 16, 1e-3}}) {
            INFO(to_string(taper) << " taper, " << to_string(method) << " ny " << ny);
            const auto model = make_model(still_key(method, 0, ny, {.tip = true, .gravity = true, .taper = taper}), p,
                                          ModelSource::assembled);
            // theta = 0: Q = -K2 B - g W_y^T, linear in B; the deflection solves Q = 0.
            const Linear l = at_rest(*model);
            test::State rest{VectorXd::Zero(ny), VectorXd::Zero(ny), HubInput{}};
            const VectorXd B = l.K.ldlt().solve(forces_of(*model, rest));
            CHECK(model->tip(B.data()).uy == Approx(exact).epsilon(tolerance));
        }
    }
}

TEST_CASE("assembled Rayleigh damping: each mode decays at alpha/2 + beta omega^2/2", "[extras][assembled][physics]")
{
    // At rest the damped modes are those of (K, M), each pair the roots of lambda^2 + (alpha + beta omega^2) lambda +
    // omega^2 = 0: zeta = alpha/(2 omega) + beta omega/2, the axial modes overdamped above omega = 2/beta.
    Parameters p;
    p.alpha = 0.2;
    p.beta = 1e-3;
    p.m_tip = 0.3;
    p.J_tip = 0.05;
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        INFO(to_string(method));
        const auto model =
            make_model(still_key(method, 4, 4, {.tip = true, .damping = true}), p, ModelSource::assembled);
        const Linear l = at_rest(*model);
        const int n = model->nq();
        const Eigen::VectorXd w2s = test::generalized_eigen(l.K, l.M, false).values;
        std::vector<std::complex<double>> expected;
        for (int i = 0; i < n; ++i) {
            const double w2 = w2s(i), c = p.alpha + p.beta * w2;
            const std::complex<double> root = std::sqrt(std::complex<double>(c * c / 4.0 - w2, 0.0));
            expected.push_back(-c / 2.0 + root);
            expected.push_back(-c / 2.0 - root);
        }
        MatrixXd A = MatrixXd::Zero(2 * n, 2 * n);
        A.topRightCorner(n, n) = MatrixXd::Identity(n, n);
        A.bottomLeftCorner(n, n) = -l.M.ldlt().solve(l.K);
        A.bottomRightCorner(n, n) = -l.M.ldlt().solve(l.C);
        const Eigen::VectorXcd lambda = A.eigenvalues();
        int overdamped = 0;
        for (const std::complex<double>& e : expected) {
            double nearest = 1e300;
            for (int k = 0; k < 2 * n; ++k) nearest = std::min(nearest, std::abs(lambda(k) - e));
            CHECK(nearest < 1e-8 * std::abs(e));
            overdamped += e.imag() == 0.0 ? 1 : 0;
        }
        CHECK(overdamped > 0);  // the stiff axial modes (beta omega > 2) decay without oscillating
    }
}
