// The automatic stepper (stiffness.hpp): the highest frequency at rest against the cantilever's exact values
// (docs/model.md section 7), and the choice it makes for each kind of scene.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/stiffness.hpp"
#include "models/model_operations.hpp"

using namespace hubbeam;

namespace {

/// cases/controlled_gravity.toml's hub (PD with tip feedback, a torque limit, gravity) with stiffness-proportional
/// damping 1e-5 on a FEM or BSIM mesh, 10 s, no error check; one step alone where only the choice matters.
Scene damped_controlled_hub(const char* method, int nx, int ny, bool choice_only = false)
{
    std::vector<std::pair<std::string, std::string>> overrides = {{"discretization.method", method},
                                                                   {"discretization.nx", std::to_string(nx)},
                                                                   {"discretization.ny", std::to_string(ny)},
                                                                   {"damping.stiffness_proportional", "1e-5"},
                                                                   {"output.t_end", "10"},
                                                                   {"solver.error_check", "off"}};
    if (choice_only) overrides.emplace_back("solver.max_steps", "1");
    return load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/controlled_gravity.toml", overrides);
}

VariantKey amm_key(int nx, int ny, Drive drive)
{
    return {.method = Method::amm, .nx = nx, .ny = ny, .drive = drive, .extras = {}};
}

}  // namespace

TEST_CASE("the highest frequency at rest is the cantilever's highest mode in the basis", "[stiffness]")
{
    const Parameters p;
    const double m = p.rho * p.S, EI = p.E * p.I, ES = p.E * p.S;
    // AMM's bases are the exact modes: bending beta_4 L = 10.9955407349 (1 + cos cosh = 0), axial (2i - 1) pi/2.
    const double bending4 = std::pow(10.9955407349, 2) * std::sqrt(EI / (m * std::pow(p.L, 4)));
    const double axial4 = 7.0 * std::numbers::pi / 2.0 * std::sqrt(ES / m) / p.L;
    for (const ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
        const auto bending = make_model(amm_key(0, 4, Drive::prescribed), p, source);
        CHECK(highest_frequency(*bending, Axial::dynamic) == Approx(bending4).epsilon(1e-8));
        const auto both = make_model(amm_key(4, 4, Drive::prescribed), p, source);
        CHECK(highest_frequency(*both, Axial::dynamic) == Approx(axial4).epsilon(1e-8));
        // Quasi-static axial coordinates are not integrated: the bending modes are left.
        CHECK(highest_frequency(*both, Axial::quasi_static) == Approx(bending4).epsilon(1e-8));
    }
}

TEST_CASE("the automatic stepper follows the predicted cost", "[stiffness]")
{
    const Parameters p;
    const auto choice = [&](int nx, int ny, Drive drive, Axial axial = Axial::dynamic) {
        return automatic_stepper(*make_model(amm_key(nx, ny, drive), p), axial, 1e-8, 30.0).stepper;
    };
    // Without axial coordinates accuracy and stability ask for steps alike: explicit. With them the stiff axial
    // modes hold an explicit step some 60 times below what accuracy needs: implicit.
    CHECK(choice(0, 4, Drive::prescribed) == "rk8pd");
    CHECK(choice(4, 4, Drive::prescribed) == "gauss4");
    CHECK(choice(4, 4, Drive::prescribed, Axial::quasi_static) == "rk8pd");
    CHECK(choice(4, 4, Drive::torque) == "gauss4");
    CHECK(choice(0, 4, Drive::torque) == "rk8pd");
    // The reason names the highest rate it judged by: here AMM's fourth axial mode, exactly
    // 7 pi / 2 sqrt(E / rho) / L, printed to the nearest 1/s, and the lowest frequency, the first bending mode
    // 1.8751^2 sqrt(EI / (m L^4)).
    const StepperChoice stiff =
        automatic_stepper(*make_model(amm_key(4, 4, Drive::prescribed), p), Axial::dynamic, 1e-8, 30.0);
    const auto number_after = [&](const std::string& said) {
        const std::size_t at = stiff.why.find(said);
        REQUIRE(at != std::string::npos);
        return std::stod(stiff.why.substr(at + said.size()));
    };
    CHECK(std::abs(number_after("highest rate ") - 7.0 * std::numbers::pi / 2.0 * std::sqrt(p.E / p.rho) / p.L) <= 0.5);
    const double first = std::pow(1.87510407, 2) * std::sqrt(p.E * p.I / (p.rho * p.S * std::pow(p.L, 4)));
    CHECK(number_after("lowest frequency ") == Approx(first).epsilon(1e-3));
}

TEST_CASE("a long run's progress line names a faster stepper only when the scene chose a slower one", "[stiffness]")
{
    Scene s;
    s.path = "test";
    s.variant = amm_key(4, 4, Drive::prescribed);
    s.solver.stepper = "msadams";
    CHECK(Simulation(s).faster_stepper_hint().find("--stepper gauss4 suits this scene (predicted ") == 0);
    s.solver.stepper = "gauss4";
    CHECK(Simulation(s).faster_stepper_hint().empty());
    s.solver.stepper = "auto";
    CHECK(Simulation(s).faster_stepper_hint().empty());
}

TEST_CASE("the critical spin is the first frequency that the centrifugal softening cancels", "[stiffness]")
{
    // docs/model.md section 7: order zero's straight beam is unstable above the first bending frequency; orders
    // first and full keep the geometric stiffening, and only the axial mode (softened by theta_dot^2 u_x1^2)
    // goes at the first axial frequency. AMM's bases are the exact modes, so the values are exact.
    const Parameters p;
    const double m = p.rho * p.S, EI = p.E * p.I, ES = p.E * p.S;
    const double bending1 = std::pow(1.8751040687, 2) * std::sqrt(EI / (m * std::pow(p.L, 4)));
    const double axial1 = std::numbers::pi / 2.0 * std::sqrt(ES / m) / p.L;
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        VariantKey zero = amm_key(0, 4, drive);
        zero.order = Order::zero;
        CHECK(critical_spin(*make_model(zero, p)) == Approx(bending1).epsilon(1e-7));
        CHECK(std::isinf(critical_spin(*make_model(amm_key(0, 4, drive), p))));
        CHECK(critical_spin(*make_model(amm_key(4, 4, drive), p)) == Approx(axial1).epsilon(1e-7));
    }
}

TEST_CASE("the critical spin from one eigenproblem is the bisection's on positive definiteness", "[stiffness]")
{
    // critical_spin takes K(omega) = K0 + omega^2 D; a bisection that only asks whether -dQ/dq is positive definite
    // at each rate checks the eigenproblem's setup (its D, its sign, its square root) with no such assumption.
    Parameters p;
    p.a = 0.4;
    p.m_tip = 0.3;
    p.J_tip = 0.002;
    const auto both_ways = [](const Model& model) {
        const auto stable = [&](double omega) {
            const int n = model.nq(), first = model.coordinates().first_elastic(), m = n - first;
            HubInput u;
            std::vector<double> q(static_cast<std::size_t>(n), 0.0), qd(q);
            (model.key().drive == Drive::torque ? qd[0] : u.theta_dot) = omega;
            const Eigen::MatrixXd K = -force_q_jacobian(model, u, q, qd).bottomRightCorner(m, m);
            return Eigen::LLT<Eigen::MatrixXd>(0.5 * (K + K.transpose())).info() == Eigen::Success;
        };
        double lo = 0.0, hi = 1000.0;
        REQUIRE(stable(lo));
        REQUIRE(!stable(hi));
        while (hi - lo > 1e-10 * hi) (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
        CHECK(critical_spin(model) == Approx(lo).epsilon(1e-8));
    };
    for (const Drive drive : {Drive::prescribed, Drive::torque}) {
        VariantKey zero{.method = Method::fem, .nx = 0, .ny = 6, .drive = drive, .extras = {}};
        zero.order = Order::zero;
        zero.extras.tip = true;
        both_ways(*make_model(zero, p));
        for (const Method method : {Method::amm, Method::bim, Method::bsim}) {
            VariantKey axial{.method = method, .nx = 3, .ny = 4, .drive = drive, .extras = {}};
            axial.extras.tip = true;
            both_ways(*make_model(axial, p));
        }
        // A blade out of the plane, coned and pitched: the flap and twist fields' centrifugal terms.
        Parameters blade = p;
        blade.G = 2.6e10;
        blade.J_t = 2.0 * p.I;
        blade.precone = 0.05;
        blade.pitch = 0.1;
        VariantKey coned{.method = Method::amm, .nx = 3, .ny = 4, .nz = 3, .nt = 2, .drive = drive, .extras = {}};
        coned.extras.cone = true;
        coned.extras.pitch = true;
        both_ways(*make_model(coned, blade));
    }
}

TEST_CASE("a pilot that factored banded Newton matrices prices gauss4's solves and factorizations by their flops",
          "[stiffness]")
{
    // gauss4's price per step: 15 right-hand sides, 10 solves and, every fourth step, two factorizations of its
    // Newton matrices (stiffness.cpp). Dense, the condensed stage system of m = 2 nq unknowns costs 2 m^2 a solve and
    // 2/3 m^3 a factorization; a pilot that ran them banded (the mass form of a mesh) brings its own flops instead.
    const Parameters p;
    const auto model = make_model({.method = Method::fem, .nx = 0, .ny = 32, .drive = Drive::torque, .extras = {}}, p,
                                  ModelSource::assembled);
    const double m = 2.0 * model->nq();
    Pilot dense{.t = 1.0, .steps = 1000, .rtol = 1e-8};
    Pilot banded = dense;
    banded.band_factor_flops = 1.0e5;
    banded.band_solve_flops = 2.0e4;
    const StepperCosts a = predicted_costs(*model, Axial::dynamic, 1e-8, 10.0, 0, &dense);
    const StepperCosts b = predicted_costs(*model, Axial::dynamic, 1e-8, 10.0, 0, &banded);
    CHECK(a.steps_gauss4 == b.steps_gauss4);
    CHECK(a.gauss4_step - b.gauss4_step ==
          Approx(10.0 * (2.0 * m * m - 2.0e4) + 2.0 * (2.0 / 3.0 * m * m * m - 1.0e5) / 4.0).epsilon(1e-12));
}

TEST_CASE("a pilot's steps extrapolate at its second half's rate", "[stiffness]")
{
    // At a steady rate the second half's rate is the mean rate: the extrapolation is the pilot's steps times t_end
    // over its window, whatever the window.
    for (const double t : {0.25, 1.0, 3.0}) {
        const Pilot steady{.t = t, .steps = 4000, .steps_to_half = 2000, .rtol = 1e-8};
        CHECK(pilot_extrapolated_steps(steady, 30.0) == Approx(4000.0 * 30.0 / t).epsilon(1e-14));
    }
    // A start whose steps thin out (3000 in the first half-second, 1000 in the second): the rest of a 10 s run at
    // 2000 steps a second, not at the mean 4000.
    const Pilot thinning{.t = 1.0, .steps = 4000, .steps_to_half = 3000, .rtol = 1e-8};
    CHECK(pilot_extrapolated_steps(thinning, 10.0) == Approx(4000.0 + 2000.0 * 9.0).epsilon(1e-14));
}

TEST_CASE(
    "a damped start thins gauss4's steps: its pilot runs on past its budget and prices the rest at its later rate",
    "[stiffness]")
{
    // The controlled hub of cases/controlled_gravity.toml, FEM at Nx = 16, Ny = 32, with stiffness-proportional damping
    // 1e-5: the start excites the mesh's highest modes and the damping takes them, so gauss4's steps thin out through
    // the run. Its pilot's budget (the break-even steps of its 0.75 s window, priced as a dense LU) ended it at
    // t = 0.09 s, whose steps, extrapolated linearly, were 8 times the run's, and auto took rk8pd (2.8 s against
    // gauss4's 1.0 s, docs/performance.md). Past the budget the pilot runs on while its steps, priced by its banded
    // Newton matrices and extrapolated at its second half's rate, still win; over its whole window that rate still
    // overestimates the run's (the steps thin out further), but by less than twice.
    const RunSummary r = Simulation(damped_controlled_hub("fem", 16, 32)).run([](const Row&) {});
    INFO(r.stepper_why << "; " << r.steps << " steps");
    REQUIRE(r.stepper == "gauss4");
    const std::string said = "gauss4 about ";
    const double predicted = std::stod(r.stepper_why.substr(r.stepper_why.find(said) + said.size()));
    CHECK(predicted > static_cast<double>(r.steps));
    CHECK(predicted < 2.0 * static_cast<double>(r.steps));
}

TEST_CASE("a pilot whose steps thin out fast runs on past its budget", "[stiffness]")
{
    // BSIM at Nx = 0, Ny = 32 under the damped, controlled hub. The plan's budget, gauss4's steps priced as dense LUs
    // before the pilot has factored a band, is 838 steps, which the start's ringing takes by t = 0.1 s; its second
    // half's rate then still predicts 57,000 steps, which lose, but it is 0.55 of its first half's. The pilot runs on
    // (up to the 3,500 break-even steps of its window at the band's price), to its window's end, where its steps have
    // thinned out: auto takes gauss4 (0.60 s against rk8pd's 1.5 s, docs/performance.md, fine meshes).
    const RunSummary r = Simulation(damped_controlled_hub("bsim", 0, 32, true)).run([](const Row&) {});
    INFO(r.stepper_why);
    CHECK(r.stepper == "gauss4");
    CHECK(r.newton.find("band") != std::string::npos);
}

TEST_CASE("auto takes gauss4 for a damped, controlled fine mesh, whose banded Newton matrices its pilot prices",
          "[stiffness]")
{
    // FEM at Ny = 64 under a saturating PD hub with gravity and a little stiffness-proportional damping: the start's
    // ringing decays, and gauss4 takes 16,837 steps over 10 s where rk8pd, bound by stability, takes 231,228
    // (docs/performance.md, fine meshes). Its Newton matrices are a band of half-width 7 to 9 in 130 unknowns: priced
    // as dense LUs (2/3 130^3 a factorization) gauss4 lost to rk8pd, priced by the pilot's band it wins.
    Simulation sim(damped_controlled_hub("fem", 0, 64, true));
    const RunSummary r = sim.run([](const Row&) {});
    INFO(r.stepper_why);
    CHECK(r.stepper == "gauss4");
}
