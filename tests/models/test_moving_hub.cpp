// A hub that translates on a support (docs/model.md section 13), checked against rigid-body mechanics that shares
// nothing with the generator: a stiff rotor on a soft support swings at sqrt(k / total mass) under a suddenly applied
// weight, and a blade spun on a free-floating hub keeps the system's centre of mass still, the hub moving against the
// blade's own centre of mass.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "gauss_legendre.hpp"
#include "model_values.hpp"
#include "random_state.hpp"

#include "runs.hpp"

using namespace hubbeam;
using hubbeam::test::run_columns;

namespace {

/// A stiff uniform blade (its first bending frequency about 220 rad/s) on a hub that may translate, under a torque.
const char* stiff_scene = R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 4e-5
youngs_modulus = 1e12

[hub]
radius = 0.5
inertia = 1e6
mass = 56.0

[support]
stiffness_x = 2e4
stiffness_y = 2e4

[motion]
kind = "torque"
tau0 = 0.0
duration = 1.0

[discretization]
method = "amm"
ny = 2
nx = 0

[solver]
stepper = "rk8pd"
rtol = 1e-10
atol = 1e-12
error_check = "off"

[output]
t_end = 2.0
dt_out = 0.01
)";

/// stiff_scene with its torque drive's [motion] lines replaced by motion's (a prescribed drive).
std::string stiff_scene_with(const std::string& motion)
{
    std::string text = stiff_scene;
    const std::string torque = "kind = \"torque\"\ntau0 = 0.0\nduration = 1.0";
    return text.replace(text.find(torque), torque.size(), motion);
}


}  // namespace

TEST_CASE("a stiff rotor on a soft support swings at sqrt(k / total mass) under its weight", "[moving_hub]")
{
    // Three blades of 48 kg each with 2 kg tip masses and a 56 kg hub: 206 kg on k_y = 2e4 N/m, omega = 9.9 rad/s,
    // 20 times below the blades' own. Gravity switched on at rest: y_h = -(g M / k)(1 - cos omega t), the blades'
    // weights' moments cancelling about the axis (three blades at 120 degrees).
    // The hub turning freely (its inertia large) or held (a parked rotor: the angle prescribed).
    const bool held = GENERATE(false, true);
    const std::string text = held ? stiff_scene_with("kind = \"held\"\nangle = 0.0") : std::string(stiff_scene);
    const Scene s =
        parse_scene(text, "hub.toml", {{"rotor.blades", "3"}, {"rotor.tip_masses", "2, 2, 2"}, {"gravity.g", "9.81"}});
    INFO(s.key().name());
    auto rows = run_columns(s);
    REQUIRE(rows.count("hub_y") == 1);
    const double M = 56.0 + 3 * (1600.0 * 0.005 * 6.0 + 2.0), k = 2e4, g = 9.81, omega = std::sqrt(k / M);
    const double amplitude = g * M / k;
    double worst = 0.0;
    for (std::size_t i = 0; i < rows["t"].size(); ++i) {
        const double t = rows["t"][i], rigid = -amplitude * (1.0 - std::cos(omega * t));
        worst = std::max(worst, std::abs(rows["hub_y"][i] - rigid));
        // The support's force is its spring's (no damping here).
        CHECK(rows["hub_fy"][i] == Approx(-k * rows["hub_y"][i]).margin(1e-9 * k * amplitude));
    }
    CHECK(worst < 0.01 * amplitude);
    // Nothing pushes the hub sideways.
    for (double x : rows["hub_x"]) CHECK(std::abs(x) < 1e-3 * amplitude);
}

TEST_CASE("a stiff rotor of two or three blades spinning on an anisotropic support: Floquet gives the rigid rotor's "
          "sqrt(k_x / M) and sqrt(k_y / M)", "[moving_hub][floquet]")
{
    // A balanced rotor whose blades are 20 times stiffer than the support moves on it as one rigid body of the total
    // mass, whatever it spins at: its hub modes at sqrt(k / M) along each axis. The linearization is periodic (the
    // blades turn over the fixed support), so these come from the Floquet analysis; for three blades the periodic
    // motion is the hub at rest, which the harmonic balance must find as such.
    const int blades = GENERATE(2, 3);
    const Scene s = parse_scene(stiff_scene, "hub.toml",
                                {{"rotor.blades", std::to_string(blades)},
                                 {"support.stiffness_y", "3e4"},
                                 {"beam.youngs_modulus", "1e12"}});
    const std::unique_ptr<Model> model = make_scene_model(s);
    const double M = 56.0 + blades * 1600.0 * 0.005 * 6.0;
    const std::vector<NaturalMode> modes = floquet_modes(*model, 3.0);
    REQUIRE(modes.size() >= 2);
    INFO(blades << " blades: " << modes[0].rad_s << ", " << modes[1].rad_s << " rad/s");
    CHECK(std::abs(modes[0].rad_s / std::sqrt(2e4 / M) - 1.0) < 1e-3);
    CHECK(std::abs(modes[1].rad_s / std::sqrt(3e4 / M) - 1.0) < 1e-3);
    // Conservative (the support's damping 0): neither grows nor decays beyond round-off of the exponents.
    for (int k : {0, 1}) CHECK(std::abs(modes[static_cast<std::size_t>(k)].growth) < 1e-8 * modes[static_cast<std::size_t>(k)].rad_s);
}

TEST_CASE("cases/two_blade_rotor.toml: the heavy blade whirls the hub once per revolution on its support's ellipse",
          "[moving_hub]")
{
    // At the steady 3 rad/s (the spin-up ends at 8 s) the tip mass's centrifugal force m_t Omega^2 (a + L) turns with
    // the rotor; the stiff rotor moves on the support as one body of M = m_hub + 2 m L + m_t, so each axis answers
    // as a forced oscillator: amplitude F / |k - M Omega^2 + i c Omega|. The blades' bending (1e-5 of a + L) and the
    // start-up transient, damped at 5 % for 3 s and more, stay below 1 % of it.
    const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/two_blade_rotor.toml");
    auto rows = run_columns(s);
    const double Omega = 3.0, M = 100.0 + 2 * 48.0 + 5.0, F = 5.0 * Omega * Omega * (0.3 + 6.0);
    const double expected_x = F / std::hypot(2e5 - M * Omega * Omega, 700.0 * Omega),
                 expected_y = F / std::hypot(8e4 - M * Omega * Omega, 700.0 * Omega);
    double x = 0.0, y = 0.0;
    for (std::size_t i = 0; i < rows["t"].size(); ++i)
        if (rows["t"][i] > 11.0) {
            x = std::max(x, std::abs(rows["hub_x"][i]));
            y = std::max(y, std::abs(rows["hub_y"][i]));
        }
    CHECK(std::abs(x / expected_x - 1.0) < 0.01);
    CHECK(std::abs(y / expected_y - 1.0) < 0.01);
}

TEST_CASE("a blade spun on a free-floating hub keeps the centre of mass still", "[moving_hub]")
{
    // No support stiffness, no gravity: the system's centre of mass stays where it was, so the hub moves against the
    // blade's own centre of mass, at r_c = a + L/2 from the hub: x_h = -(m_b r_c / M)(cos theta - cos theta0), and
    // y_h likewise with sin; the stiff blade bends by a few parts in 1e3 of that.
    const Scene s = parse_scene(stiff_scene, "hub.toml",
                                {{"support.stiffness_x", "0"},
                                 {"support.stiffness_y", "0"},
                                 {"hub.inertia", "5"},
                                 {"motion.tau0", "10000"},
                                 {"motion.theta0", "0.4"}});
    auto rows = run_columns(s);
    const double m_b = 1600.0 * 0.005 * 6.0, M = 56.0 + m_b, r_c = 0.5 + 3.0, scale = m_b * r_c / M;
    double worst = 0.0, turned = 0.0;
    for (std::size_t i = 0; i < rows["t"].size(); ++i) {
        const double th = rows["theta"][i];
        turned = std::max(turned, std::abs(th - 0.4));
        worst = std::max(worst, std::hypot(rows["hub_x"][i] + scale * (std::cos(th) - std::cos(0.4)),
                                           rows["hub_y"][i] + scale * (std::sin(th) - std::sin(0.4))));
    }
    CHECK(turned > 0.5);  // the blade swept a good part of a turn
    CHECK(worst < 0.01 * scale);
    // No damping and no support: the energy is the torque's work at every row (the pulse turns the rotor and stops it).
    double work = 0.0;
    for (double w : rows["work"]) work = std::max(work, std::abs(w));
    REQUIRE(work > 100.0);
    for (std::size_t i = 0; i < rows["t"].size(); ++i)
        CHECK(std::abs(rows["jacobi"][i] - rows["work"][i]) < 1e-8 * work);
}

TEST_CASE("a flexible blade on a free-floating hub keeps the linear momentum of its order exactly", "[moving_hub]")
{
    // Under either drive: a torque, or a prescribed spin-up, whose drive is a couple on the hub as well (its sine and
    // cosine then inputs of the kinetic energy, turned with time).
    const bool torque = GENERATE(true, false);
    const std::string text =
        torque ? std::string(stiff_scene) : stiff_scene_with("kind = \"spin-up\"\nomega0 = 3.0\nduration = 1.5");
    // The order-first kinetic energy does not depend on x_h, y_h: p_x, p_y are conserved, and with the blade's points
    // at (a + x + u_x1, u_y) in its frame to first order, p = d/dt [M x_h + R(theta) int m (a + x + u_x1, u_y) dx]
    // exactly. So from rest that sum stays at its start: the hub's translation, the blade's turn, its stretch and its
    // bending balance to round-off. A softer blade (first bending about 22 rad/s) with axial coordinates, spun by a strong
    // torque, bends and stretches by centimetres; the integrals are the test's own Gauss sums of the fields.
    Overrides o = {{"support.stiffness_x", "0"},     {"support.stiffness_y", "0"},   {"beam.youngs_modulus", "1e10"},
                   {"discretization.method", "fem"}, {"discretization.ny", "4"},     {"discretization.nx", "2"},
                   {"hub.inertia", "5"},             {"motion.theta0", "0.4"}};
    if (torque) o.emplace_back("motion.tau0", "3000");
    const Scene s = parse_scene(text, "hub.toml", o);
    INFO(s.key().name());
    Simulation sim(s);
    const Parameters& p = s.parameters;
    const BeamFields fields(s.key(), p);
    const auto& layout = sim.model().coordinates();
    const int ia = layout.first(FieldKind::axial), ib = layout.first(FieldKind::inplane);
    const int ix = layout.first(FieldKind::hub_x), iy = layout.first(FieldKind::hub_y);
    const double m = p.rho * p.S, M = p.m_hub + m * p.L;
    const test::GaussRule rule = test::gauss_legendre(12);
    double worst_x = 0.0, worst_y = 0.0, bent = 0.0, moved = 0.0, start_x = NAN, start_y = NAN;
    sim.observe_states([&](double t, const double* q) {
        // int m (a + x + u_x1) dx and int m u_y dx over four panels (the FEM elements' nodes among their ends).
        double along = 0.0, across = 0.0;
        for (int panel = 0; panel < 4; ++panel)
            for (std::size_t k = 0; k < rule.x.size(); ++k) {
                const double x = p.L * (panel + 0.5 * (rule.x[k] + 1.0)) / 4.0, w = 0.5 * rule.w[k] * p.L / 4.0;
                along += w * m * (p.a + x + fields.ux1(q + ia, x));
                across += w * m * fields.uy(q + ib, x);
                bent = std::max(bent, std::abs(fields.uy(q + ib, x)));
            }
        const double th = torque ? q[0] : s.motion.theta(t), cx = M * q[ix] + std::cos(th) * along - std::sin(th) * across,
                     cy = M * q[iy] + std::sin(th) * along + std::cos(th) * across;
        if (std::isnan(start_x)) start_x = cx, start_y = cy;
        worst_x = std::max(worst_x, std::abs(cx - start_x));
        worst_y = std::max(worst_y, std::abs(cy - start_y));
        moved = std::max(moved, std::hypot(q[ix], q[iy]));
    });
    const RunSummary r = sim.run([](const Row&) {});
    REQUIRE(r.failure.empty());
    CHECK(bent > 0.01);
    CHECK(moved > 0.1);
    const double scale = m * p.L * (p.a + p.L / 2);
    CHECK(worst_x < 1e-7 * scale);
    CHECK(worst_y < 1e-7 * scale);
}

TEST_CASE("a moving hub's scene keys are checked", "[moving_hub]")
{
    const auto refused = [](const char* text_key, const Overrides& o) {
        try {
            parse_scene(stiff_scene, "hub.toml", o);
        } catch (const SceneError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(text_key) != std::string::npos);
            return true;
        }
        return false;
    };
    CHECK(refused("support.stiffness_x", {{"support.stiffness_x", "-1"}}));
    CHECK(refused("hub.mass", {{"hub.mass", "-2"}}));
}

TEST_CASE("a rotor on a moving hub: its exact Jacobian equals central differences of its forces and mass", "[moving_hub]")
{
    // Three blades out of the plane on a support, at a random state: dQ/dq, dQ/dqd and (dM/dq) v of the rotor (each
    // blade's generated derivatives, scattered) against fourth-order differences of the rotor's own Q and M.
    const Scene s = parse_scene(stiff_scene, "hub.toml",
                                {{"rotor.blades", "3"},
                                 {"rotor.pitch_offsets", "0.1, -0.2, 0.3"},
                                 {"beam.youngs_modulus", "1e10"},
                                 {"discretization.method", "fem"},
                                 {"discretization.ny", "2"},
                                 {"discretization.nz", "2"},
                                 {"discretization.nx", "2"},
                                 {"support.damping_x", "30"},
                                 {"gravity.g", "9.81"}});
    Simulation sim(s);
    const Model& model = sim.model();
    REQUIRE(model.jacobian() != nullptr);
    const int n = model.nq();
    std::vector<double> q(static_cast<std::size_t>(n)), qd(q.size()), v(q.size());
    for (int i = 0; i < n; ++i) {
        q[static_cast<std::size_t>(i)] = 0.01 * std::sin(1.7 * i + 0.3);
        qd[static_cast<std::size_t>(i)] = 0.2 * std::cos(2.3 * i + 0.1);
        v[static_cast<std::size_t>(i)] = std::sin(0.9 * i + 1.1);
    }
    q[0] = 0.7;
    qd[0] = 2.0;
    HubInput u;
    u.tau = 50.0;
    const auto nn = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    std::vector<double> dq(nn), dqd(nn), du(static_cast<std::size_t>(n) * drive_value_count), dMv(nn);
    model.jacobian()->force_derivatives(u, q.data(), qd.data(), dq.data(), dqd.data(), du.data());
    model.jacobian()->mass_q_product(u, q.data(), v.data(), dMv.data());
    const auto forces = [&](const std::vector<double>& x, const std::vector<double>& xd) {
        std::vector<double> Q(static_cast<std::size_t>(n));
        model.forces(u, x.data(), xd.data(), Q.data());
        return Q;
    };
    const auto mass_v = [&](const std::vector<double>& x) {
        std::vector<double> M(nn), Mv(static_cast<std::size_t>(n), 0.0);
        model.mass(u, x.data(), M.data());
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                Mv[static_cast<std::size_t>(i)] += M[static_cast<std::size_t>(i * n + j)] * v[static_cast<std::size_t>(j)];
        return Mv;
    };
    const double h = 1e-4;
    double worst = 0.0, scale = 0.0;
    for (int k = 0; k < n; ++k) {
        const auto moved = [&](std::vector<double> x, double step) {
            x[static_cast<std::size_t>(k)] += step;
            return x;
        };
        const auto d4 = [&](const auto& f) {  // (8 (f(+h) - f(-h)) - (f(+2h) - f(-2h))) / 12h
            const auto a = f(h), b = f(-h), c = f(2 * h), d = f(-2 * h);
            std::vector<double> r(a.size());
            for (std::size_t i = 0; i < a.size(); ++i) r[i] = (8 * (a[i] - b[i]) - (c[i] - d[i])) / (12 * h);
            return r;
        };
        const auto by_q = d4([&](double e) { return forces(moved(q, e), qd); });
        const auto by_qd = d4([&](double e) { return forces(q, moved(qd, e)); });
        const auto mass_by_q = d4([&](double e) { return mass_v(moved(q, e)); });
        for (int i = 0; i < n; ++i) {
            const auto at = static_cast<std::size_t>(i * n + k);
            worst = std::max({worst, std::abs(dq[at] - by_q[static_cast<std::size_t>(i)]),
                              std::abs(dqd[at] - by_qd[static_cast<std::size_t>(i)]),
                              std::abs(dMv[at] - mass_by_q[static_cast<std::size_t>(i)])});
            scale = std::max({scale, std::abs(dq[at]), std::abs(dqd[at]), std::abs(dMv[at])});
        }
    }
    CHECK(worst < 1e-7 * scale);
}

TEST_CASE("a moving hub: generated and hand-assembled agree, alone and with every other term, under both drives",
          "[moving_hub][assembled]")
{
    // The assembled path writes the hub's energy on the forms' first moments (docs/model.md section 13.1); the
    // generator derives it from |v_h + r_dot|^2. Every method, both drives, orders zero and first, in the plane and
    // out of it, with a tip body, gravity, damping, a taper, pitch, pre-twist and precone.
    const char* names[] = {"fem_nx2_ny4_torque_first_hub",
                           "bim_nx2_ny3_prescribed_zero_hub",
                           "bsim_nx3_ny4_prescribed_first_tip_gravity_damped_depth_hub",
                           "amm_nx2_ny3_torque_first_tip_gravity_damped_width_hub",
                           "amm_nx0_ny3_nz3_nt2_torque_first_tip_gravity_damped_pitched_twisted_coned_hub",
                           "fem_nx2_ny4_nz4_nt2_prescribed_first_tip_gravity_damped_pitched_coned_hub"};
    std::mt19937 rng(1958);
    for (const char* name : names) {
        const VariantKey key = VariantKey::parse(name);
        SECTION(name)
        {
            const Parameters p = test::with_every_term();
            const auto gen = make_model(key, p, ModelSource::generated);
            const auto asm_ = make_model(key, p, ModelSource::assembled);
            REQUIRE(std::string(asm_->source()) == "assembled");
            CHECK(gen->mass_is_constant() == asm_->mass_is_constant());
            const int hx = asm_->coordinates().first(FieldKind::hub_x), e = asm_->coordinates().first_beam();
            for (int trial = 0; trial < 4; ++trial) {
                const test::State st = test::random_state_with_angle(key, rng);
                INFO("trial " << trial << ", theta " << st.u.theta);
                const Eigen::MatrixXd Mg = test::mass_of(*gen, st), Ma = test::mass_of(*asm_, st);
                // The hub couples to the beam: the comparison covers the term.
                REQUIRE(Ma.block(hx, e, 2, Ma.cols() - e).norm() > 0.0);
                CHECK(test::relative_error(Mg.reshaped(), Ma.reshaped()) < 1e-12);
                CHECK(test::relative_error(test::forces_of(*gen, st), test::forces_of(*asm_, st)) < 1e-12);
                const Eigen::Vector4d eg = test::energy_of(*gen, st), ea = test::energy_of(*asm_, st);
                CHECK((eg - ea).lpNorm<Eigen::Infinity>() < 1e-12 * ea.lpNorm<Eigen::Infinity>());
                const double hg = gen->momentum(st.u, st.q.data(), st.qd.data());
                const double ha = asm_->momentum(st.u, st.q.data(), st.qd.data());
                CHECK(std::abs(hg - ha) <= 1e-12 * std::abs(ha));
                if (key.drive == Drive::prescribed)
                    CHECK(test::relative_error(test::forces_theta_of(*gen, st), test::forces_theta_of(*asm_, st)) <
                          1e-12);
            }
        }
    }
}
