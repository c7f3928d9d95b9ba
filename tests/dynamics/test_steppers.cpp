// The stepper families beside GSL's (stepper.hpp): gauss4 and CVODE against a tight reference on stiff and non-stiff
// scenes, gauss4's reuse of its Jacobian, and the automatic choice against the work each candidate measurably does.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <hubbeam/make_model.hpp>
#include <gsl/gsl_errno.h>
#include "dynamics/stepper.hpp"
#include "dynamics/stiffness.hpp"
#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

namespace {

/// The largest |tip_uy| difference of rows from a reference's, and the reference's largest |tip_uy|.
std::pair<double, double> tip_error(const std::vector<Row>& rows, const std::vector<Row>& reference)
{
    REQUIRE(rows.size() == reference.size());
    double error = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        CHECK(rows[i].t == reference[i].t);
        error = std::max(error, std::abs(rows[i].tip_uy - reference[i].tip_uy));
        scale = std::max(scale, std::abs(reference[i].tip_uy));
    }
    return {error, scale};
}

/// A stepper alone (gauss4 unless named), stepped by hand from rest: AMM at Ny = 4 at the cases' tolerances (rtol
/// 1e-8, atol 1e-10).
struct LoneStepper {
    LoneStepper(int nx, const Motion& drive, const std::string& name = "gauss4", double h0 = 1e-4)
        : motion(drive),
          model(make_model({.method = Method::amm, .nx = nx, .ny = 4, .drive = drive.drive(), .extras = {}},
                           Parameters{}, ModelSource::automatic)),
          system(*model, motion),
          y(static_cast<std::size_t>(system.size()), 0.0),
          stepper(make_stepper(system, name, t, y.data(), h0, 1e-10, 1e-8))
    {
    }
    /// One step toward target, no longer than h_max: its length.
    double step(double target, double h_max = INFINITY)
    {
        const double t0 = t;
        REQUIRE(stepper->step(t, target, y.data(), h_max) == StepStatus::success);
        return t - t0;
    }

    Motion motion;  // the system keeps a reference to it
    std::unique_ptr<Model> model;
    FirstOrderSystem system;
    std::vector<double> y;
    double t = 0.0;
    std::unique_ptr<Stepper> stepper;
};

Scene spin_up_scene(int nx, double t_end)
{
    Scene s = paper_scene(Method::amm, nx, 4, spin_up(4.0));
    s.output.t_end = t_end;
    return s;
}

/// A run with a step at every row by rk8pd at rtol (atol rtol / 100), without the error check's re-runs: the reference
/// (at 1e-13 resolving even the axial modes).
std::vector<Row> reference_run(Scene s, double rtol = 1e-13)
{
    s.solver.stepper = "rk8pd";
    s.solver.rtol = rtol;
    s.solver.atol = rtol / 100.0;
    s.solver.stepping = Stepping::rows;
    s.solver.error_check = ErrorCheck::off;
    return run(s);
}

/// A run of s by gauss4 at rtol (atol rtol / 100), without the run's own error check: the tests compare it with their
/// own reference.
Collected gauss4_run(Scene s, double rtol)
{
    s.solver.stepper = "gauss4";
    s.solver.rtol = rtol;
    s.solver.atol = rtol / 100.0;
    s.solver.error_check = ErrorCheck::off;
    return completed_run(s);
}

}  // namespace

TEST_CASE("gauss4 and cvode agree with a tight reference, with and without the stiff axial modes", "[steppers]")
{
    for (const int nx : {0, 4}) {
        const Scene scene = spin_up_scene(nx, 4.0);
        const std::vector<Row> reference = reference_run(scene);
        for (const char* stepper : {"gauss4", "cvode"}) {
            // CVODE's BDF of orders 3 to 5 is unstable for undamped oscillations it does not resolve: with the axial
            // modes it resolves them, slowly, and is left to damped or non-stiff scenes.
            if (nx > 0 && std::string(stepper) == "cvode") continue;
            for (const double rtol : {1e-7, 1e-10}) {
                Scene s = scene;
                s.solver.stepper = stepper;
                s.solver.rtol = rtol;
                s.solver.atol = rtol / 100.0;
                const Collected c = completed_run(s);
                const auto [error, scale] = tip_error(c.rows, reference);
                INFO(stepper << " Nx = " << nx << " rtol " << rtol << ": tip error " << error << " m of " << scale
                             << " m, " << c.summary.steps << " steps");
                // The local tolerance accumulates over the run's steps: within a few hundred rtol of the tip's scale.
                CHECK(error <= 300.0 * rtol * scale);
            }
        }
    }
}

TEST_CASE("gauss4 reuses its Jacobian and Newton matrices across steps", "[steppers]")
{
    // After the spin-up the equations are linear with constant coefficients: one Jacobian serves every step. During
    // it the centrifugal stiffening changes slowly and the simplified Newton iteration still converges fast.
    Scene s = spin_up_scene(4, 30.0);
    s.solver.stepper = "gauss4";
    s.solver.error_check = ErrorCheck::off;
    const Collected c = completed_run(s);
    INFO(c.summary.jacobian_evals << " Jacobians over " << c.summary.steps << " steps");
    CHECK(c.summary.jacobian_evals * 3 <= c.summary.steps);
}

TEST_CASE("the automatic choice is the candidate that does less work", "[steppers]")
{
    // A small grid of clear cases, whose systems are small enough that right-hand sides are the work: the chosen
    // stepper must take fewer of them than the other candidate (measured, not predicted), and the choice must differ
    // across the grid. Near-ties, where the linear algebra decides, are measured by hubbeam bench
    // (docs/performance.md).
    // Order full at Ny = 8 is a clear case by its right-hand side's cost (its foreshortening at Gauss points, 35
    // times order first's), where order first's is a near-tie that rk8pd takes.
    struct Point {
        Method method;
        int nx, ny;
        Motion motion;
        Order order = Order::first;
    };
    const Point grid[] = {{Method::amm, 0, 4, torque(1.0)},
                          {Method::amm, 4, 4, spin_up(4.0)},
                          {Method::fem, 0, 4, torque(1.0)},
                          {Method::amm, 4, 4, torque(1.0)},
                          {Method::amm, 0, 8, spin_up(4.0), Order::full}};
    int implicit = 0;
    for (const Point& p : grid) {
        Scene s = paper_scene(p.method, p.nx, p.ny, p.motion);
        s.variant.order = p.order;
        s.output.t_end = 5.0;
        s.solver.rtol = 1e-8;  // the cases' tolerances, where both candidates are in the running
        s.solver.atol = 1e-10;
        s.solver.error_check = ErrorCheck::off;
        const RunSummary automatic = Simulation(s).run([](const Row&) {});
        const std::string chosen = automatic.stepper;
        long evaluations[2] = {};
        const char* candidates[2] = {"rk8pd", "gauss4"};
        for (int i = 0; i < 2; ++i) {
            s.solver.stepper = candidates[i];
            evaluations[i] = completed_run(s).summary.rhs_evals;
        }
        const std::string fewer = evaluations[0] <= evaluations[1] ? "rk8pd" : "gauss4";
        INFO(to_string(p.method) << " Nx = " << p.nx << " Ny = " << p.ny << " " << to_string(p.order) << ": chose "
                                 << chosen << "; rk8pd "
                                 << evaluations[0] << ", gauss4 " << evaluations[1] << " right-hand sides; "
                                 << automatic.stepper_why);
        CHECK(chosen == fewer);
        implicit += chosen == "gauss4";
    }
    CHECK(implicit > 0);
    CHECK(implicit < static_cast<int>(std::size(grid)));
}

TEST_CASE("under a hub torque the automatic choice measures gauss4's steps with a pilot run", "[steppers]")
{
    // The torque's start excites the mesh's highest modes, and how many steps gauss4 needs depends on how far above
    // the tolerance they ring: the pilot measures the start of the run and extrapolates. Its premise is that the
    // start is representative: the whole run's steps are its steps, and the rest of the run at its second half's rate.
    const auto automatic = [](Scene s) {
        s.solver.error_check = ErrorCheck::off;
        return Simulation(s).run([](const Row&) {});
    };
    const auto number_after = [](const std::string& why, const std::string& said) {
        const std::size_t at = why.find(said);
        REQUIRE(at != std::string::npos);
        return std::stod(why.substr(at + said.size()));
    };
    Scene s = paper_scene(Method::fem, 8, 8, torque(1.0));
    s.output.t_end = 10.0;
    const RunSummary stiff = automatic(s);
    INFO(stiff.stepper_why);
    CHECK(stiff.stepper == "gauss4");
    const double pilot_steps = number_after(stiff.stepper_why, ", from ");
    const double window = number_after(stiff.stepper_why, "in a pilot to t = ");
    const double planned =
        std::max(s.output.t_end / 30.0, std::numbers::pi / number_after(stiff.stepper_why, "lowest frequency "));
    CHECK(window == Approx(planned).epsilon(5e-3));
    const std::string& why = stiff.stepper_why;  // "... in a pilot to t = 1.08 s, 604 in its second half; ..."
    const double second_half = std::stod(why.substr(why.find(" s, ", why.find("in a pilot to t = ")) + 4));
    const double extrapolated = pilot_steps + second_half / (0.5 * window) * (s.output.t_end - window);
    CHECK(number_after(stiff.stepper_why, "gauss4 about ") == Approx(extrapolated).epsilon(1e-3));
    INFO("whole run: " << stiff.steps << " steps");
    CHECK(extrapolated == Approx(static_cast<double>(stiff.steps)).epsilon(0.25));
    // Without the axial modes rk8pd's steps are few: the pilot stops once gauss4 has taken more than would let it
    // win, before its window ends.
    s.variant.nx = 0;
    const RunSummary explicit_run = automatic(s);
    INFO(explicit_run.stepper_why);
    CHECK(explicit_run.stepper == "rk8pd");
    CHECK(number_after(explicit_run.stepper_why, "in a pilot to t = ") < 0.5 * planned);
    // A prescribed rotation starts and ends smoothly: the rule predicts it, no pilot runs.
    s = paper_scene(Method::fem, 0, 8, spin_up(4.0));
    s.output.t_end = 10.0;
    CHECK(automatic(s).stepper_why.find("pilot") == std::string::npos);
}

TEST_CASE("gauss4 shares a target's distance evenly and resumes its step after one the target shortened", "[steppers]")
{
    // Steps end at rows and breakpoints. A last step clipped to reach one needed its own Newton matrix, and the next
    // step grew from it by at most 4 times a step, refactoring each time: a sliver before a row cost a dozen
    // refactorizations, and on BSIM's paper basis at Ny = 32 the steps never grew back (598,706 steps over 30 s).
    LoneStepper g(0, spin_up(4.0));
    const auto step = [&](double target, double h_max = INFINITY) { return g.step(target, h_max); };
    double& t = g.t;
    double h = 0.0;
    for (int i = 0; i < 40; ++i) h = step(5.0);  // grown to what the tolerance allows at t of a second or so
    INFO("step " << h << " at t = " << t);
    REQUIRE(h > 1e-3);
    // A target 1.5 steps ahead: two steps of 0.75, not a step and a half-step.
    const double target = t + 1.5 * h;
    const double first = step(target);
    CHECK(first == Approx(0.75 * h).epsilon(1e-9));
    CHECK(step(target) == Approx(0.75 * h).epsilon(1e-9));
    CHECK(t == target);
    // A sliver to a target, then a free step: as long as before the sliver (the error allows it), not 4 slivers.
    const double h_before = step(5.0);
    CHECK(step(t + 1e-3 * h_before) == Approx(1e-3 * h_before).epsilon(1e-9));
    CHECK(step(5.0) >= 0.8 * h_before);
    // Steps an interpolation bound h_max shortened: the step follows them, and grows from them (at most 4 times a
    // step) once the bound lets go, rather than trying the longer step of before, to have it rejected.
    const double h_free = step(5.0), bound = 0.1 * h_free;
    for (int i = 0; i < 3; ++i) {
        const double bounded = step(5.0, bound);  // the distance to 5 s shared evenly: a little under the bound
        CHECK(bounded <= bound);
        CHECK(bounded >= 0.99 * bound);
    }
    CHECK(step(5.0) <= 4.0 * bound * (1.0 + 1e-9));
}

TEST_CASE("gauss4 keeps its step after passing steps once they are calm", "[steppers]")
{
    // Small decreases after steps that passed drifted the step until its Newton matrices had to be refactored, and
    // the next growth refactored them again. Once five steps in a row have passed the error test, a step may not be
    // shorter than the one before; after a rejection it may, until five pass again.
    LoneStepper g(4, torque(1.0));  // the torque excites the axial modes: steps bound by accuracy, hundreds of them
    const Stepper& stepper = *g.stepper;
    int calm = 0, calm_decreases = 0, other_decreases = 0;
    double h_last = 0.0;
    while (g.t < 5.0) {
        const long rejected = stepper.rejected();
        const double h = g.step(5.0);
        const bool shorter = h < h_last * (1.0 - 1e-9) && g.t < 5.0;  // the last step shares the distance to 5 s
        if (stepper.rejected() > rejected) calm = 0;
        if (shorter) ++(calm >= 5 ? calm_decreases : other_decreases);
        ++calm;
        h_last = h;
    }
    INFO(stepper.steps() << " steps, " << stepper.rejected() << " rejected");
    CHECK(stepper.rejected() > 0);
    CHECK(other_decreases > 0);  // decreases happen, after rejections
    CHECK(calm_decreases == 0);
}

TEST_CASE("every stepper family counts the steps its error test rejected, through restarts", "[steppers]")
{
    // The summary reports them beside the steps. A first step of 0.05 s from rest under torque cannot meet rtol 1e-8:
    // it is rejected and shortened before any step is accepted. After a restart the counts go on (GSL and CVODE
    // start theirs again), and steps bounded to 1e-6 s pass the test, so the count must not fall.
    for (const std::string name : {"rk8pd", "msadams", "rk4imp", "cvode", "gauss4"}) {  // GSL's share one evolve
        INFO(name);
        LoneStepper g(4, torque(1.0), name, 0.05);
        g.step(1.0);
        const long rejected = g.stepper->rejected();
        CHECK(rejected >= 1);
        g.stepper->restart(g.t, g.y.data());
        for (int i = 0; i < 3; ++i) g.step(1.0, 1e-6);
        CHECK(g.stepper->rejected() == rejected);
    }
}

TEST_CASE("a stiff mode ringing at the tolerance does not trap gauss4 in short steps", "[steppers]")
{
    // BSIM's paper basis and the open one span the same space (the same solution), but at Ny = 32 the paper basis
    // with its end slope in units of xi had a mass matrix of condition number 3e5 against 27, and round-off rang in
    // its tip modes (22,092 rad/s) at the tolerance of the tip coordinate's rate. (With the slope per knot interval,
    // model/basis/bsim.hpp, its condition number is 326 and it takes the open basis's steps, 1,068 against 1,006
    // here: the check below then holds whatever the stepping; what follows is why the stepping is as it is.) The interpolated rows then failed at every step that did not resolve
    // the mode, the shortened steps met gauss4's error test where an unresolved mode's is largest, and the steps
    // stayed short: 24 times the open basis's steps over 10 s (333,242 against 1,509 over 30 s with generated
    // code). Where interpolation would need steps under a quarter of the rows' spacing, steps end at the rows. Over
    // 20 s, across the spin-up's end (15 s): a row ending a step once counted as the breakpoint reached, the stepper
    // restarted there and then stepped across the kink, and the steps stayed short again (298,424 over 30 s).
    Scene s = paper_scene(Method::bsim, 0, 32, spin_up(4.0));
    s.output.t_end = 20.0;
    s.source = ModelSource::assembled;  // no compilation; it rings alike
    s.solver.stepper = "gauss4";
    s.solver.rtol = 1e-8;  // cases/spinup_omega4.toml's tolerances
    s.solver.atol = 1e-10;
    s.solver.error_check = ErrorCheck::off;
    const Collected paper = completed_run(s);
    s.variant.spline = SplineBasis::open;
    const Collected open = completed_run(s);
    INFO("paper basis " << paper.summary.steps << " steps, open basis " << open.summary.steps);
    CHECK(paper.summary.steps <= 10 * open.summary.steps);
    // The same solution: the tip within the tolerance's reach of each other.
    const auto [difference, scale] = tip_error(paper.rows, open.rows);
    CHECK(difference <= 1e-6 * scale);
}

TEST_CASE("gauss4's Newton matrices in mass form: a band LU for FEM, as accurate as the dense one", "[steppers]")
{
    // FEM: M, K and C are banded but for a free hub's row and column, while M^-1 K is dense.
    // gauss4 keeps them apart and factors I (x) M - h^2 A^2 (x) K - h A (x) C as a bordered band: the run must agree
    // with a tight reference as the dense form did, and say which form it used.
    for (const Motion& motion : {torque(1.0), spin_up(4.0)}) {
        // Ny = 32 without axial coordinates: a band of half-width 7 in 64 or 66 (at Nx = Ny = 16 the band is as wide
        // as a quarter of the matrix and the dense form is kept).
        Scene s = paper_scene(Method::fem, 0, 32, motion);
        s.output.t_end = 2.0;
        // rk8pd at 1e-11: at 1e-13 its steps meet round-off on this stiff mesh.
        const std::vector<Row> reference = reference_run(s, 1e-11);
        for (const double rtol : {1e-7, 1e-9}) {
            const Collected c = gauss4_run(s, rtol);
            const bool torque_driven = motion.kind == Motion::Kind::torque;
            INFO((torque_driven ? "torque" : "spin-up")
                 << " rtol " << rtol << ": " << c.summary.newton << ", " << c.summary.steps << " steps");
            CHECK(c.summary.newton.find("mass form, band LU") == 0);
            CHECK(c.summary.newton.find(torque_driven ? "bordered by 2 dense rows" : "bordered by 0 dense rows") !=
                  std::string::npos);
            const auto [error, scale] = tip_error(c.rows, reference);
            CHECK(error <= 300.0 * rtol * scale);
        }
    }
}

TEST_CASE("gauss4's mass form under a control: the work and dissipated energy integrated beside a band LU",
          "[steppers][control]")
{
    // A controlled, damped FEM beam carries the hub's work and the dissipated energy as auxiliary states: quadratures
    // of (q, qd), which gauss4 integrates from the state's stages while the Newton systems stay condensed and banded
    // (the hub's row, where the control's tip feedback lands, in the border). Against a tight rk8pd run, over a step
    // that saturates the torque at first: the tip, the work and the dissipated energy.
    Motion step;
    step.kind = Motion::Kind::step;
    step.angle = 0.5;
    Scene s = paper_scene(Method::fem, 0, 32, step);
    s.control = Control{};
    s.control->kp = 200.0;
    s.control->kd = 150.0;
    s.control->k_tip = 20.0;
    s.control->tau_max = 80.0;
    s.parameters.beta = 1e-4;  // stiffness-proportional: the mesh's highest modes decay, gauss4 steps over them
    s.output.t_end = 1.0;
    const std::vector<Row> reference = reference_run(s, 1e-11);
    double work_scale = 0.0, dissipated_scale = 0.0;
    for (const Row& r : reference) {
        work_scale = std::max(work_scale, std::abs(r.extras.work));
        dissipated_scale = std::max(dissipated_scale, std::abs(r.extras.dissipated));
    }
    REQUIRE(dissipated_scale > 0.0);
    for (const double rtol : {1e-7, 1e-9}) {
        const Collected c = gauss4_run(s, rtol);
        INFO("rtol " << rtol << ": " << c.summary.newton << ", " << c.summary.steps << " steps");
        CHECK(c.summary.newton.find("mass form, band LU") == 0);
        const auto [error, scale] = tip_error(c.rows, reference);
        CHECK(error <= 300.0 * rtol * scale);
        double work_error = 0.0, dissipated_error = 0.0;
        for (std::size_t i = 0; i < reference.size(); ++i) {
            work_error = std::max(work_error, std::abs(c.rows[i].extras.work - reference[i].extras.work));
            dissipated_error =
                std::max(dissipated_error, std::abs(c.rows[i].extras.dissipated - reference[i].extras.dissipated));
        }
        CHECK(work_error <= 300.0 * rtol * work_scale);
        CHECK(dissipated_error <= 300.0 * rtol * dissipated_scale);
    }
}
