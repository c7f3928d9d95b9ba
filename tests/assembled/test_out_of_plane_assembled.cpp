// The beam out of the plane (docs/model.md section 12: flapwise and twist fields, pitch, pre-twist, precone, section
// offsets, and the tip body, gravity along both axes and damping with them) on two independent paths: the generated
// kernels (symbolic energies, exact integrals, the pre-twist and a table as section integrals) against the
// hand-assembled forms of section 12.3 (runtime/src/models/assembled/quadratic_forms.cpp: quadrature with the chord's
// angle at the nodes) at random states, term by term and all together; the assembled forces against the assembled
// energies; the forms against section 5.2's block form on planar variants; and the assembled path against closed forms
// and published frequencies.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <hubbeam/make_model.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "eigen_oracles.hpp"
#include "model_values.hpp"
#include "models/assembled/assembled.hpp"
#include "random_state.hpp"
#include "shared_oracles.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

using test::energy_of;
using test::forces_of;
using test::forces_theta_of;
using test::mass_of;

Eigen::Matrix<double, 5, 1> tip_of(const Model& model, const test::State& s)
{
    const Tip t = model.tip(s.q.data());
    Eigen::Matrix<double, 5, 1> v;
    v << t.uy, t.ux1, t.ux, t.uz, t.phi;
    return v;
}

/// A parameter change that switches a term off (its values zero), named for the messages.
struct Switch {
    const char* term;
    std::function<void(Parameters&)> off;
};

/// A variant and the terms it is about: each switch must change what the comparison sees (else it proves nothing).
struct Case {
    VariantKey key;
    std::vector<Switch> switches;
};

using test::key_of;

/// Every term switched on, for every method under both drives and both orders (16), then each term alone (8), then a
/// taper of either kind with every term (2), then a blade's profile with every term for each method and alone (5), then
/// a blade's section offsets (3), then the tip body in the blade's axes (3): 37 variants, each compiled once into the
/// test's cache. nx = 0 and nx > 0, nz = 2 and
/// 4, nt = 0, 2 and 3 (BSIM's least), BSIM in both constructions.
std::vector<Case> cases()
{
    const Extras all{.tip = true, .gravity = true, .damping = true, .pitch = true, .twist = true, .cone = true};
    std::vector<Case> c;
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim})
        for (Drive drive : {Drive::torque, Drive::prescribed})
            for (Order order : {Order::first, Order::zero}) {
                const bool bsim = method == Method::bsim, torque = drive == Drive::torque;
                const int nx = torque == (order == Order::first) ? (bsim ? 3 : 2) : 0;
                const int nz = method == Method::fem && order == Order::zero ? 2 : 4, nt = bsim ? 3 : 2;
                c.push_back({key_of(method, nx, nz, nt, drive, order, all,
                                    bsim && !torque ? SplineBasis::open : SplineBasis::paper),
                             {}});
            }
    const auto set = [](auto f) { return std::function<void(Parameters&)>(f); };
    c.push_back({key_of(Method::amm, 2, 4, 0, Drive::torque, Order::first, {}), {}});      // the flapwise field
    c.push_back({key_of(Method::fem, 0, 0, 2, Drive::prescribed, Order::first, {}), {}});  // the twist field
    c.push_back({key_of(Method::bim, 0, 0, 0, Drive::prescribed, Order::zero, {.pitch = true}),
                 {{"pitch", set([](Parameters& p) { p.pitch = 0.0; })}}});  // in-plane bending about a turned chord
    c.push_back({key_of(Method::bsim, 0, 4, 0, Drive::torque, Order::first, {.twist = true}, SplineBasis::open),
                 {{"pre-twist", set([](Parameters& p) { p.twist = 0.0; })}}});
    c.push_back({key_of(Method::fem, 2, 2, 0, Drive::prescribed, Order::first, {.cone = true}),
                 {{"precone", set([](Parameters& p) { p.precone = 0.0; })}}});
    c.push_back({key_of(Method::bim, 2, 4, 2, Drive::torque, Order::zero, {.tip = true}),
                 {{"tip body", set([](Parameters& p) { p.m_tip = p.J_tip = 0.0; })}}});
    c.push_back({key_of(Method::amm, 2, 2, 2, Drive::prescribed, Order::first, {.gravity = true}),
                 {{"gravity in the plane", set([](Parameters& p) { p.g = 0.0; })},
                  {"gravity along the axis", set([](Parameters& p) { p.g_axis = 0.0; })}}});
    c.push_back({key_of(Method::bsim, 3, 4, 3, Drive::torque, Order::first, {.damping = true}),
                 {{"damping", set([](Parameters& p) { p.alpha = p.beta = 0.0; })}}});
    // A blade's profile (section 12.4), its stations where no method's pieces end, with every term but the linear
    // pre-twist (its chord angles are the table's) and with its tabulated angles alone.
    Extras blade = all;
    blade.twist = false;
    blade.tabulated = true;
    const auto untwisted = set([](Parameters& p) {
        for (std::size_t k = 0; k < p.profile.size(); k += max_profile_value_count)
            for (ProfileValue angle : {ProfileValue::twist, ProfileValue::inertia_twist})
                p.profile[k + static_cast<std::size_t>(angle)] = 0.0;
    });
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        const bool bsim = method == Method::bsim;
        c.push_back({key_of(method, bsim ? 3 : 2, 4, bsim ? 3 : 2, Drive::torque, Order::first, blade),
                     {{"the tabulated chord angles", untwisted}}});
    }
    // A taper out of the plane: the width (flapwise thickness) and the depth (chord), every term but the profile.
    Extras width = all, depth = all;
    width.taper = Taper::width;
    depth.taper = Taper::depth;
    depth.twist = false;
    const auto untapered = set([](Parameters& p) { p.tip_ratio = 1.0; });
    c.push_back({key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first, width), {{"the width taper", untapered}}});
    c.push_back(
        {key_of(Method::bsim, 0, 4, 3, Drive::prescribed, Order::zero, depth), {{"the depth taper", untapered}}});
    c.push_back({key_of(Method::fem, 0, 2, 2, Drive::prescribed, Order::zero, Extras{.tabulated = true}),
                 {{"the tabulated chord angles", untwisted}}});
    // A blade's section offsets (sections 12.5 and 12.6, no precone): every field under a torque with the tip body and
    // damping, every field at order zero under a prescribed spin, and a global basis without axial coordinates.
    const auto centred = set([](Parameters& p) { std::fill(p.offsets.begin(), p.offsets.end(), 0.0); });
    const Extras offsets{.tip = true, .damping = true, .pitch = true, .tabulated = true, .offsets = true};
    c.push_back({key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first, offsets), {{"the offsets", centred}}});
    c.push_back(
        {key_of(Method::bim, 2, 4, 2, Drive::prescribed, Order::zero, Extras{.tabulated = true, .offsets = true}),
         {{"the offsets", centred}}});
    c.push_back(
        {key_of(Method::amm, 0, 4, 2, Drive::prescribed, Order::first, Extras{.tabulated = true, .offsets = true}),
         {{"the offsets", centred}}});
    // The tip body in the blade's axes (section 11.1, no precone): with every other term but the precone under a
    // torque, with a table's offsets at order zero, and on a global basis without axial coordinates.
    const auto point_mass = set([](Parameters& p) { p.J_tip_flap = p.J_tip_twist = p.tip_offset = 0.0; });
    const Extras body{.tip = true, .gravity = true, .damping = true, .pitch = true, .twist = true, .tip_body = true};
    c.push_back({key_of(Method::fem, 2, 4, 2, Drive::torque, Order::first, body), {{"the tip body", point_mass}}});
    c.push_back(
        {key_of(Method::bsim, 3, 4, 3, Drive::prescribed, Order::zero,
                {.tip = true, .pitch = true, .tabulated = true, .offsets = true, .tip_body = true}, SplineBasis::open),
         {{"the tip body", point_mass}}});
    c.push_back({key_of(Method::amm, 0, 4, 2, Drive::prescribed, Order::first, {.tip = true, .tip_body = true}),
                 {{"the tip body", point_mass}}});
    return c;
}

/// The largest relative difference of every quantity the two models compute at s (each against its largest entry;
/// the energies' four parts against the largest part, so that a T1 or T0 of zero compares as one).
double difference(const Model& gen, const Model& asm_, const test::State& s)
{
    const auto relative = [](const auto& a, const auto& b) { return test::relative_error(a, b); };
    double worst =
        std::max({relative(mass_of(gen, s).reshaped(), mass_of(asm_, s).reshaped()),
                  relative(forces_of(gen, s), forces_of(asm_, s)), relative(energy_of(gen, s), energy_of(asm_, s)),
                  relative(tip_of(gen, s), tip_of(asm_, s))});
    const double hg = gen.momentum(s.u, s.q.data(), s.qd.data()), ha = asm_.momentum(s.u, s.q.data(), s.qd.data());
    worst = std::max(worst, std::abs(hg - ha) / std::abs(ha));
    const VectorXd dg = forces_theta_of(gen, s), da = forces_theta_of(asm_, s);
    return std::max(worst, da.lpNorm<Eigen::Infinity>() == 0.0 ? dg.lpNorm<Eigen::Infinity>() : relative(dg, da));
}

/// How much the terms a case is about change the assembled M, Q, energies and tip: the largest relative change.
double change(const Model& with, const Model& without, const test::State& s)
{
    return std::max({test::relative_error(mass_of(without, s).reshaped(), mass_of(with, s).reshaped()),
                     test::relative_error(forces_of(without, s), forces_of(with, s)),
                     test::relative_error(energy_of(without, s), energy_of(with, s))});
}

}  // namespace

TEST_CASE("generated and assembled agree out of the plane", "[out_of_plane_assembled][generated][assembled]")
{
    const Parameters every = test::with_every_term();
    std::mt19937 rng(1982);
    for (const Case& c : cases()) {
        SECTION(c.key.name())
        {
            const Parameters p = test::with_profile(c.key, every);
            const auto gen = make_model(c.key, p, ModelSource::generated);
            const auto asm_ = make_model(c.key, p, ModelSource::assembled);
            REQUIRE(std::string(gen->source()) == "generated");
            REQUIRE(std::string(asm_->source()) == "assembled");
            CHECK(gen->mass_is_constant() == asm_->mass_is_constant());
            std::vector<std::unique_ptr<Model>> without;
            for (const Switch& t : c.switches) {
                Parameters off = p;
                t.off(off);
                without.push_back(make_model(c.key, off, ModelSource::assembled));
            }
            std::vector<double> shown(c.switches.size(), 0.0);
            for (int trial = 0; trial < 4; ++trial) {
                const test::State s = test::random_state_with_angle(c.key, rng);
                INFO("trial " << trial << ", theta " << s.u.theta);
                CHECK(difference(*gen, *asm_, s) < 1e-11);
                for (std::size_t k = 0; k < without.size(); ++k)
                    shown[k] = std::max(shown[k], change(*asm_, *without[k], s));
            }
            // The comparison means something only where the term changes what is compared.
            for (std::size_t k = 0; k < shown.size(); ++k) {
                INFO(c.switches[k].term);
                CHECK(shown[k] > 1e-4);
            }
        }
    }
}

TEST_CASE("generated and assembled agree at a propeller's pre-twist, a radian and more", "[out_of_plane_assembled][generated][assembled]")
{
    // The pre-twist's cos 2 twist xi and sin 2 twist xi are section integrals at run time: no bound from a series.
    std::mt19937 rng(1983);
    for (const Case& c : cases()) {
        if (!c.key.extras.twist) continue;
        for (double twist : {2.5, -6.2}) {
            SECTION(c.key.name() + " at twist " + std::to_string(twist))
            {
                Parameters p = test::with_every_term();
                p.twist = twist;
                const auto gen = make_model(c.key, p, ModelSource::generated);
                const auto asm_ = make_model(c.key, p, ModelSource::assembled);
                REQUIRE(std::string(gen->source()) == "generated");
                for (int trial = 0; trial < 3; ++trial) CHECK(difference(*gen, *asm_, test::random_state_with_angle(c.key, rng)) < 1e-11);
            }
        }
    }
}

TEST_CASE("assembled out of the plane: forces from the assembled energies", "[out_of_plane_assembled][assembled]")
{
    // Without damping T, U and U_g say everything: Q is Lagrange's from them, M is T's Hessian in the rates, and
    // dQ/dtheta the difference of Q along the prescribed angle (exact: Q is affine in sin theta and cos theta).
    Parameters every = test::with_every_term();
    every.alpha = every.beta = 0.0;
    std::mt19937 rng(1877);
    for (const Case& c : cases()) {
        SECTION(c.key.name())
        {
            const auto model = make_model(c.key, test::with_profile(c.key, every), ModelSource::assembled);
            const int n = c.key.nq();
            for (int trial = 0; trial < 3; ++trial) {
                const test::State s = test::random_state_with_angle(c.key, rng);
                CHECK(test::relative_error(forces_of(*model, s), test::lagrange_forces(*model, s)) < 1e-9);
                MatrixXd H(n, n);
                const auto T = [&](const VectorXd& qd) { return model->energy(s.u, s.q.data(), qd.data()).kinetic(); };
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        const VectorXd ei = VectorXd::Unit(n, i), ej = VectorXd::Unit(n, j);
                        H(i, j) =
                            0.25 * (T(s.qd + ei + ej) - T(s.qd + ei - ej) - T(s.qd - ei + ej) + T(s.qd - ei - ej));
                    }
                CHECK(test::relative_error(mass_of(*model, s).reshaped(), H.reshaped()) < 1e-9);
                if (c.key.drive == Drive::prescribed && c.key.extras.gravity) {
                    test::State up = s, down = s;
                    up.u.theta += 1.0;
                    down.u.theta -= 1.0;
                    const VectorXd dQ = (forces_of(*model, up) - forces_of(*model, down)) / (2.0 * std::sin(1.0));
                    CHECK(test::relative_error(forces_theta_of(*model, s), dQ) < 1e-9);
                }
            }
        }
    }
}

TEST_CASE("assembled forms equal the block form on planar variants", "[out_of_plane_assembled][assembled]")
{
    // Section 12.3's forms with no flapwise or twist field, pitch or precone are section 5.2's equations: the same
    // matrices placed by another route, so they agree to round-off.
    const Parameters p = test::with_every_term();
    std::mt19937 rng(1987);
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim})
        for (Drive drive : {Drive::prescribed, Drive::torque})
            for (Order order : {Order::zero, Order::first})
                for (int nx : {0, 4}) {
                    const VariantKey key{.method = method,
                                         .nx = nx,
                                         .ny = 4,
                                         .order = order,
                                         .drive = drive,
                                         .extras = {.tip = true, .gravity = true, .damping = true}};
                    INFO(key.name());
                    const auto blocks = make_assembled_model(key, p), forms = make_quadratic_form_model(key, p);
                    CHECK(blocks->mass_pattern() == forms->mass_pattern());
                    for (int trial = 0; trial < 2; ++trial) {
                        const test::State s = test::random_state_with_angle(key, rng);
                        CHECK(difference(*blocks, *forms, s) < 1e-13);
                    }
                }
}

namespace {

/// The stiffness -dQ/dq and mass of a prescribed variant spinning steadily at Omega, straight and at rest in the
/// hub's frame (Q is linear in q there: exact by columns), restricted to one field's block.
struct FieldBlock {
    MatrixXd K, M;
};
FieldBlock spinning(const Model& model, double Omega, FieldKind kind)
{
    const int n = model.nq(), first = model.coordinates().first(kind), count = model.coordinates().count(kind);
    test::State s{VectorXd::Zero(n), VectorXd::Zero(n), HubInput{.theta_dot = Omega}};
    const VectorXd Q0 = forces_of(model, s);
    MatrixXd K(n, n);
    for (int j = 0; j < n; ++j) {
        test::State moved = s;
        moved.q(j) = 1.0;
        K.col(j) = Q0 - forces_of(model, moved);
    }
    return {K.block(first, first, count, count), mass_of(model, s).block(first, first, count, count)};
}

/// The block's natural frequencies, lowest first.
VectorXd frequencies(const FieldBlock& b)
{
    return test::generalized_eigen(b.K, b.M, false).values.cwiseSqrt();
}

}  // namespace

TEST_CASE("assembled out of the plane: closed forms and published frequencies",
          "[out_of_plane_assembled][assembled][physics]")
{
    SECTION("a spinning blade's flap frequencies (Wright et al. 1982) and the lead-lag ones below them")
    {
        // Units sqrt(EI_flap / (m L^4)) = 1, a = 0, no pitch or precone: the flap frequencies at Omega = 0, 6 and 12 as
        // Bir (2009) tabulates them; lead-lag with EI_edge = EI_flap has omega_lag^2 = omega_flap^2 - Omega^2 mode by
        // mode (the spin softens the plane's bending by -Omega^2 M2 and not the flapwise).
        const Parameters p{.L = 1.0, .rho = 1.0, .S = 1.0, .I = 1.0, .E = 1.0, .a = 0.0, .I_flap = 1.0};
        const VariantKey key{.method = Method::bim, .nx = 0, .ny = 12, .nz = 12};
        const auto model = make_model(key, p, ModelSource::assembled);
        const double table[3][4] = {
            {0.0, 3.516, 22.035, 61.697}, {6.0, 7.360, 26.809, 66.684}, {12.0, 13.170, 37.603, 79.615}};
        for (const auto& row : table) {
            INFO("Omega " << row[0]);
            const VectorXd flap = frequencies(spinning(*model, row[0], FieldKind::flap));
            const VectorXd lag = frequencies(spinning(*model, row[0], FieldKind::inplane));
            for (int i = 0; i < 3; ++i) {
                CHECK(std::abs(flap(i) - row[i + 1]) < 6e-4);
                // To the round-off the ill-conditioned degree-13 Bernstein basis leaves in its lowest eigenvalues.
                CHECK(lag(i) * lag(i) == Approx(flap(i) * flap(i) - row[0] * row[0]).epsilon(1e-8));
            }
        }
    }
    SECTION("twist: the bar's frequencies, stiffened or softened by the propeller moment")
    {
        // AMM's axial sines are the twist modes of a uniform bar: omega_i^2 = ((2i - 1) pi / (2L))^2 GJ / j_p +
        // Omega^2 (j_n - j_c) / j_p at pitch 0 (j_c > j_n here: the spin softens the twist).
        const Parameters p = test::with_every_term();
        const VariantKey key{.method = Method::amm, .nx = 0, .ny = 2, .nt = 3};
        const auto model = make_model(key, p, ModelSource::assembled);
        const double j_n = p.rho * p.I, j_c = p.rho * p.I_flap, GJ = p.G * p.J_t, Omega = 30.0;
        const VectorXd twist = frequencies(spinning(*model, Omega, FieldKind::twist));
        for (int i = 0; i < 3; ++i) {
            const double k = (2 * i + 1) * std::numbers::pi / (2.0 * p.L);
            CHECK(twist(i) * twist(i) ==
                  Approx((k * k * GJ + Omega * Omega * (j_n - j_c)) / (j_n + j_c)).epsilon(1e-10));
        }
    }
    SECTION("a pitch of 90 degrees exchanges the edgewise and flapwise bending stiffnesses")
    {
        Parameters p = test::with_every_term();
        const VariantKey key{.method = Method::bsim, .nx = 0, .ny = 5, .nz = 5, .extras = {.pitch = true}};
        p.pitch = 0.0;
        const auto flat = make_model(key, p, ModelSource::assembled);
        p.pitch = std::numbers::pi / 2.0;
        const auto turned = make_model(key, p, ModelSource::assembled);
        const FieldBlock lag = spinning(*turned, 0.0, FieldKind::inplane), flap = spinning(*flat, 0.0, FieldKind::flap);
        CHECK(test::relative_error(lag.K.reshaped(), flap.K.reshaped()) < 1e-12);
        CHECK(test::relative_error(spinning(*turned, 0.0, FieldKind::flap).K.reshaped(),
                                   spinning(*flat, 0.0, FieldKind::inplane).K.reshaped()) < 1e-12);
    }
    SECTION("a held cantilever sags under gravity along the spin axis by m g L^4 / (8 EI_flap)")
    {
        // BIM's degree nz + 1 = 5 holds the quartic deflection exactly.
        Parameters p = test::with_every_term();
        p.g = 0.0;
        const VariantKey key{.method = Method::bim, .nx = 0, .ny = 2, .nz = 4, .extras = {.gravity = true}};
        const auto model = make_model(key, p, ModelSource::assembled);
        const FieldBlock rest = spinning(*model, 0.0, FieldKind::flap);
        const int n = model->nq(), z = model->coordinates().first(FieldKind::flap);
        test::State s{VectorXd::Zero(n), VectorXd::Zero(n), HubInput{}};
        s.q.segment(z, key.nz) = rest.K.ldlt().solve(forces_of(*model, s).segment(z, key.nz));
        const double m = p.rho * p.S, EI_flap = p.E * p.I_flap;
        CHECK(model->tip(s.q.data()).uz == Approx(-m * p.g_axis * std::pow(p.L, 4) / (8.0 * EI_flap)).epsilon(1e-10));
    }
}
