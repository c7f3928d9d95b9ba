// Forward sensitivities (sensitivity.hpp) against central differences of whole runs at moved parameters: the paper's
// four cases and the controlled hub, and every stepper family on the controlled hub.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/stepper.hpp"
#include "simulation/sensitivity.hpp"

using namespace hubbeam;

namespace {

/// The rows of a run of scene, each with its derivative columns after the row's own values.
struct Table {
    std::vector<std::vector<double>> rows;
    std::vector<std::string> columns;
    long steps = 0;  // the stepper's accepted steps
    std::vector<double> column(const std::string& name) const
    {
        const auto at = static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
        REQUIRE(at < columns.size());
        std::vector<double> v;
        for (const auto& r : rows) v.push_back(r[at]);
        return v;
    }
};

Table run(const Scene& scene)
{
    Table t;
    const ColumnSet set = optional_columns_of(scene);
    std::string header = row_header(set);
    for (std::size_t at = 0; at != std::string::npos;) {
        const std::size_t comma = header.find(',', at);
        t.columns.push_back(header.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
        at = comma == std::string::npos ? comma : comma + 1;
    }
    Simulation sim(scene);
    sim.check_error(false);
    const RunSummary s = sim.run([&](const Row& r) {
        std::vector<double> v;
        for_each_value(r, set, [&](double x) { v.push_back(x); });
        t.rows.push_back(std::move(v));
    });
    REQUIRE(s.completed);
    t.steps = s.steps;
    return t;
}

std::string text(double v)
{
    char t[64];
    std::snprintf(t, sizeof t, "%.17g", v);
    return t;
}

/// The scene key that sets each parameter the cases below differentiate.
std::string key_of(const std::string& p)
{
    static const std::pair<const char*, const char*> keys[] = {{"E", "beam.youngs_modulus"},
                                                               {"L", "beam.length"},
                                                               {"rho", "beam.density"},
                                                               {"S", "beam.area"},
                                                               {"I", "beam.second_moment"},
                                                               {"tip_ratio", "beam.tip_ratio"},
                                                               {"J_oh", "hub.inertia"},
                                                               {"a", "hub.radius"},
                                                               {"m_tip", "tip.mass"},
                                                               {"J_tip", "tip.inertia"},
                                                               {"g", "gravity.g"},
                                                               {"alpha", "damping.mass_proportional"},
                                                               {"beta", "damping.stiffness_proportional"},
                                                               {"I_flap", "beam.second_moment_flap"},
                                                               {"G", "beam.shear_modulus"},
                                                               {"J_t", "beam.torsion_constant"},
                                                               {"pitch", "beam.pitch"},
                                                               {"twist", "beam.twist"},
                                                               {"precone", "beam.precone"}};
    for (const auto& [name, key] : keys)
        if (p == name) return key;
    return "control." + p;
}

/// A parameter's or gain's value in scene.
double value_of(const Scene& scene, const std::string& p)
{
    if (const auto at = std::find(param_names.begin(), param_names.end(), p); at != param_names.end()) {
        Parameters values = scene.parameters;
        return value(values, static_cast<Param>(at - param_names.begin()));
    }
    const Control& c = *scene.control;
    const double gains[] = {c.kp, c.kd, c.ki, c.k_tip};
    return gains[std::find(gain_names.begin(), gain_names.end(), p) - gain_names.begin()];
}

/// max |sensitivity - central difference| over the rows, relative to the difference's largest value, for the
/// outputs theta (under torque) and tip_uy.
void check_against_differences(const std::string& file, const std::vector<std::string>& parameters, double t_end,
                               const std::string& stepper, double rtol, double tolerance, Overrides base = {})
{
    base.insert(base.end(), {{"output.t_end", text(t_end)},
                             {"solver.rtol", text(rtol)},
                             {"solver.atol", text(rtol * 1e-2)},
                             {"solver.stepper", stepper}});
    // The differences are of converged runs (rk8pd at rtol 1e-12): an implicit stepper's runs at moved parameters
    // converge their iterations differently, which differences divide by 2h.
    Overrides converged = base;
    converged.insert(converged.end(),
                     {{"solver.rtol", "1e-12"}, {"solver.atol", "1e-14"}, {"solver.stepper", "rk8pd"}});
    Overrides with = base;
    std::string names;
    for (const std::string& p : parameters) names += (names.empty() ? "" : ",") + p;
    with.emplace_back("output.sensitivities", names);
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + file;
    const Scene scene = load_scene(path, with);
    const Table exact = run(scene);
    for (const std::string& p : parameters) {
        const double v = value_of(scene, p);
        // A step of 1e-4: the differences' truncation error is ~1e-8 of the derivative, and the runs' own errors
        // (rtol |y|, uncorrelated from run to run as their steps differ) are divided by 2h p ~ 1e-4 p, not less.
        const double h = 1e-4 * (v != 0.0 ? std::abs(v) : 1.0);
        Overrides up = converged, down = converged;
        up.emplace_back(key_of(p), text(v + h));
        down.emplace_back(key_of(p), text(v - h));
        const Table a = run(load_scene(path, up)), b = run(load_scene(path, down));
        REQUIRE(a.rows.size() == exact.rows.size());
        for (const char* out : {"theta", "tip_uy", "tip_uz", "tip_phi"}) {
            if (std::string(out) == "theta" && scene.drive() != Drive::torque) continue;
            if ((std::string(out) == "tip_uz" && scene.variant.nz == 0) ||
                (std::string(out) == "tip_phi" && scene.variant.nt == 0))
                continue;  // a blade's outputs (docs/model.md section 12)
            const std::vector<double> ya = a.column(out), yb = b.column(out),
                                      d = exact.column("d_" + std::string(out) + "/d_" + p);
            double big = 0.0, err = 0.0;
            for (std::size_t i = 0; i < d.size(); ++i) {
                const double fd = (ya[i] - yb[i]) / (2.0 * h);
                big = std::max(big, std::abs(fd));
                err = std::max(err, std::abs(d[i] - fd));
            }
            INFO(file << " " << stepper << ": d_" << out << "/d_" << p << ", largest " << big);
            CHECK(big > 0.0);
            CHECK(err / big < tolerance);
        }
    }
}

}  // namespace

TEST_CASE("sensitivities equal central differences of whole runs on the paper's cases", "[sensitivities]")
{
    // Converged runs (rtol 1e-10): the differences' own error is about 1e-10 / 1e-5 of the derivative's size.
    check_against_differences("spinup_omega4.toml", {"E", "L", "rho"}, 2.0, "auto", 1e-10, 1e-5);
    check_against_differences("spinup_omega10.toml", {"L", "a"}, 2.0, "auto", 1e-10, 1e-5, {{"hub.radius", "0.3"}});
    check_against_differences("torque_tau1.toml", {"E", "J_oh"}, 2.0, "auto", 1e-10, 1e-5);
    check_against_differences("torque_tau10.toml", {"L", "J_oh"}, 2.0, "auto", 1e-10, 1e-5);
}

TEST_CASE("the hand-assembled model's sensitivities equal central differences of whole runs", "[sensitivities]")
{
    // Without derivative kernels J sigma_j is differenced along sigma_j (2 parameters, 18 states) or, where that
    // costs more, taken from the formed Jacobian (5 parameters, 10 states), and df/dp from models at p -+ h.
    const Overrides assembled = {{"model.source", "assembled"}};
    check_against_differences("torque_tau1.toml", {"E", "J_oh"}, 2.0, "rk8pd", 1e-10, 1e-5, assembled);
    Overrides planar = assembled;
    planar.emplace_back("discretization.nx", "0");
    check_against_differences("torque_tau1.toml", {"E", "L", "rho", "I", "J_oh"}, 2.0, "rk8pd", 1e-10, 1e-5, planar);
}

TEST_CASE("a blade's sensitivities, of tip_uz and tip_phi too, equal central differences of whole runs",
          "[sensitivities]")
{
    // Generated parameter derivatives of a blade with flap and twist fields, without its damping: a damped scene's
    // sensitivity equations take 20 to 1000 times the steps of its run, the planar ones' as the blade's (measured:
    // damped_appendage 86 times), too slow for the suite.
    const Overrides undamped = {{"damping.stiffness_proportional", "0"}};
    check_against_differences("pitched_propeller.toml", {"pitch", "I_flap"}, 1.0, "auto", 1e-10, 1e-5, undamped);
}

TEST_CASE("sensitivities to the controller's gains, on every stepper family", "[sensitivities]")
{
    // The scene's torque saturates until t = 1.24 s. Where it lets go the sensitivities' rates jump (the gains' own
    // terms and the torque's dependence on the state switch on), and a step across that kink has a first-order error
    // that gauss4's step doubling does not estimate: it steps to the switch, a breakpoint the simulation locates
    // (without, its sensitivities came 1e-5 to 2e-5 off at rtol 1e-9 and 1e-10).
    for (const char* stepper : {"rk8pd", "msadams", "gauss4", "rk4imp", "cvode"})
        check_against_differences("controlled_step.toml", {"kp", "kd", "J_oh"}, 3.0, stepper, 1e-10, 1e-5);
}

TEST_CASE("cvode's staggered sensitivities start again from the state a restart gives", "[sensitivities]")
{
    // A run takes a step again from its start (a row too far to interpolate, a saturation switch): CVODES keeps its
    // sensitivities apart from the state, and both must start from the given y, or the retaken step's sensitivities
    // continue from where the first attempt ended.
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/controlled_step.toml";
    const Scene scene = load_scene(path, {{"output.sensitivities", "kp,E"}});
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    SensitivitySystem system(*model, scene);
    std::vector<double> y0(static_cast<std::size_t>(system.size()), 0.0);
    y0[0] = 0.45;
    const auto stepper = make_stepper(system, "cvode", 0.0, y0.data(), 1e-3, 1e-10, 1e-8);
    const auto step_from_start = [&] {
        std::vector<double> y = y0;
        double t = 0.0;
        REQUIRE(stepper->step(t, 0.01, y.data(), INFINITY) == StepStatus::success);
        return std::make_pair(t, y);
    };
    const auto first = step_from_start();
    REQUIRE(std::abs(first.second.back()) > 0.0);  // the sensitivities moved
    stepper->restart(0.0, y0.data());
    const auto again = step_from_start();
    CHECK(again.first == first.first);
    CHECK(again.second == first.second);
}

TEST_CASE("a gain saturated at the first right-hand side has no forcing whatever the memory held", "[sensitivities]")
{
    // The controlled hub's torque starts at its limit, so the gains' forcings are zero there and their columns of
    // the forcings are not written. Scaled by zero instead of zeroed, a column that held a NaN (the heap's bytes at
    // the first right-hand side) made the rates NaN: a notebook's run stopped at t = 0, "non-finite", now and then.
    // Blocks of the column's size filled with NaN are freed just before the system is made, so that the allocator
    // hands one of them to the forcings.
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/controlled_step.toml";
    const Scene scene = load_scene(path, {{"output.sensitivities", "kp,kd"}});
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const std::size_t column_size = static_cast<std::size_t>(model->nq()) * 2;
    {
        std::vector<std::unique_ptr<double[]>> poisoned;
        for (int i = 0; i < 64; ++i) {
            poisoned.emplace_back(new double[column_size]);
            std::fill_n(poisoned.back().get(), column_size, std::numeric_limits<double>::quiet_NaN());
        }
    }
    SensitivitySystem system(*model, scene);
    std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0), f(y.size());
    REQUIRE(system.saturated(0.0, y.data()));
    REQUIRE(system.rhs(0.0, y.data(), f.data()) == 0);
    for (const double v : f) CHECK(std::isfinite(v));
}

TEST_CASE("each row's derivative by a parameter is the difference of the state's equations at moved parameters",
          "[sensitivities]")
{
    // With the sensitivities zero, a block's rates are pbar_j df/dp_j alone: row by row (the hub's work and the
    // dissipated energy included), against central differences of the plain equations (FirstOrderSystem's rhs) of
    // models and controls built at p_j -+ h, at a state of the test's choosing (the controlled hub unsaturated).
    struct Case {
        const char* file;
        std::vector<std::string> names;
    };
    for (const Case& c : {Case{"damped_appendage.toml", {"E", "alpha", "beta", "rho", "J_oh", "L"}},
                          Case{"controlled_step.toml", {"kp", "kd", "J_oh", "E"}}}) {
        std::string names;
        for (const std::string& p : c.names) names += (names.empty() ? "" : ",") + p;
        const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + c.file;
        const Scene scene = load_scene(path, {{"output.sensitivities", names}});
        const auto model = make_model(scene.key(), scene.parameters, scene.source);
        SensitivitySystem system(*model, scene);
        const int n = system.state_size(), nq = model->nq();
        std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0), f(y.size());
        for (int i = 0; i < n; ++i) y[static_cast<std::size_t>(i)] = 0.01 * std::sin(1.0 + 3.7 * i);  // a state
        y[0] = 0.45;                             // the hub near its reference 0.5: the controller unsaturated
        y[static_cast<std::size_t>(nq)] = 0.01;  // theta_dot
        const double t = 0.7;
        REQUIRE(system.rhs(t, y.data(), f.data()) == 0);
        for (std::size_t j = 0; j < c.names.size(); ++j) {
            const std::string& name = c.names[j];
            const auto rates_at = [&](double delta, double& scale) {
                Scene moved = scene;
                moved.output.sensitivities.clear();
                double* v = nullptr;
                if (name == "kp")
                    v = &moved.control->kp;
                else if (name == "kd")
                    v = &moved.control->kd;
                else
                    v = &value(moved.parameters,
                               static_cast<Param>(std::find(param_names.begin(), param_names.end(), name) -
                                                  param_names.begin()));
                scale = *v != 0.0 ? std::abs(*v) : 1.0;
                *v += delta * scale;
                const auto m = make_model(moved.key(), moved.parameters, moved.source);
                FirstOrderSystem plain(*m, moved.motion, moved.axial, moved.controller(), &moved.parameters);
                REQUIRE(plain.state_size() == n);
                std::vector<double> out(static_cast<std::size_t>(n));
                REQUIRE(plain.rhs(t, y.data(), out.data()) == 0);
                return out;
            };
            double scale = 1.0;
            const double h = 1e-6;  // of the parameter's size
            const std::vector<double> up = rates_at(h, scale), down = rates_at(-h, scale);
            for (int i = 0; i < n; ++i) {
                // d/dp_j times pbar_j = d/d(p_j / pbar_j): the difference over 2h of the scaled parameter
                const double expected =
                    (up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2.0 * h);
                INFO(c.file << ": d(row " << i << ")/d_" << name);
                CHECK(f[static_cast<std::size_t>(n * (1 + static_cast<int>(j)) + i)] ==
                      Approx(expected).epsilon(1e-6).margin(1e-9 * (1.0 + std::abs(up[static_cast<std::size_t>(i)]))));
            }
        }
    }
}

TEST_CASE("sensitivities to every parameter and gain, at zero and at other values, equal differences of whole runs",
          "[sensitivities]")
{
    // The controlled step of cases/controlled_step.toml, down (its torque saturates negative for the first second),
    // with every term of the model: a tip body, gravity, Rayleigh damping, a tapered depth, an integral term and tip
    // feedback. Short converged runs; a derivative read as 0 or off by a factor is off by its own size.
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/controlled_step.toml";
    const Overrides every_term = {{"motion.angle", "-0.5"},
                                  {"model.order", "zero"},
                                  {"beam.taper", "depth"},
                                  {"beam.tip_ratio", "0.7"},
                                  {"hub.radius", "0.1"},
                                  {"tip.mass", "0.5"},
                                  {"tip.inertia", "0.02"},
                                  {"gravity.g", "9.81"},
                                  {"damping.mass_proportional", "0.05"},
                                  {"damping.stiffness_proportional", "1e-3"},
                                  {"control.ki", "5"},
                                  {"control.k_tip", "20"},
                                  {"output.t_end", "2"}};
    const auto with = [](Overrides o, const Overrides& more) {
        o.insert(o.end(), more.begin(), more.end());
        return o;
    };
    const Overrides tight = {{"solver.rtol", "1e-12"}, {"solver.atol", "1e-14"}, {"solver.stepper", "rk8pd"}};
    const std::vector<std::string> outputs = {"theta", "tip_uy"};
    /// max |sensitivity - difference| / max |difference| over the rows, for each output, of p in scene's run; at a
    /// value of zero, differences over 1e-4 of scale.
    const auto check = [&](const Overrides& scene_overrides, const std::vector<std::string>& names,
                           double scale = 1.0) {
        std::string list;
        for (const std::string& p : names) list += (list.empty() ? "" : ",") + p;
        const Overrides base = with(scene_overrides, {{"output.sensitivities", list}});
        const Scene scene = load_scene(path, with(base, {{"solver.rtol", "1e-10"}, {"solver.atol", "1e-12"}}));
        const Table exact = run(scene);
        for (const std::string& p : names) {
            const double v = value_of(scene, p);
            // Central differences, h = 1e-4 of the value (see check_against_differences); at 0, where most of these
            // cannot go negative, one-sided ones of second order, (-3 y(0) + 4 y(h) - y(2h)) / (2h), h = 1e-4 of
            // the parameter's size elsewhere in this test (beta 1e-3 s: at h = 1e-4 s their error was 1e-3).
            const double h = 1e-4 * (v != 0.0 ? std::abs(v) : scale);
            // The runs differenced carry no sensitivities (at 1e-12 they cost 50 times more), except at zero, where
            // asking for p keeps its term in the variant.
            const Overrides plain = with(with(scene_overrides, tight), {{"output.sensitivities", v != 0.0 ? "" : p}});
            const auto at = [&](double x) { return run(load_scene(path, with(plain, {{key_of(p), text(x)}}))); };
            const std::vector<Table> runs =
                v != 0.0 ? std::vector<Table>{at(v + h), at(v - h)} : std::vector<Table>{at(0.0), at(h), at(2.0 * h)};
            for (const std::string& out : outputs) {
                std::vector<std::vector<double>> y;
                for (const Table& t : runs) {
                    REQUIRE(t.rows.size() == exact.rows.size());
                    y.push_back(t.column(out));
                }
                const std::vector<double> d = exact.column("d_" + out + "/d_" + p);
                double big = 0.0, err = 0.0;
                for (std::size_t i = 0; i < d.size(); ++i) {
                    const double fd = v != 0.0 ? (y[0][i] - y[1][i]) / (2.0 * h)
                                               : (-3.0 * y[0][i] + 4.0 * y[1][i] - y[2][i]) / (2.0 * h);
                    big = std::max(big, std::abs(fd));
                    err = std::max(err, std::abs(d[i] - fd));
                }
                INFO("d_" << out << "/d_" << p << " at " << p << " = " << v << ": largest " << big << ", off by "
                          << err);
                CHECK(big > 0.0);
                CHECK(err < 1e-4 * big);
            }
        }
    };
    SECTION("at non-zero values, a few at once")
    {
        // In groups: a run's cost grows with the square of its parameters' count (each block's Jacobian product).
        check(every_term, {"m_tip", "J_tip", "g", "alpha"});
        check(every_term, {"beta", "ki", "k_tip", "kp"});
        check(every_term, {"kd", "S", "I", "tip_ratio"});
        check(every_term, {"E", "rho", "L", "a", "J_oh"});
    }
    SECTION("at zero, each alone")
    {
        // Each parameter alone (another in the list would bring the term into the model by itself), at zero with the
        // others of its term: the sensitivity must bring the term in.
        const struct {
            const char* name;
            Overrides zero;
        } cases[] = {
            {"m_tip", {{"tip.mass", "0"}, {"tip.inertia", "0"}}},
            {"J_tip", {{"tip.mass", "0"}, {"tip.inertia", "0"}}},
            {"g", {{"gravity.g", "0"}}},
            {"alpha", {{"damping.mass_proportional", "0"}, {"damping.stiffness_proportional", "0"}}},
            {"beta", {{"damping.mass_proportional", "0"}, {"damping.stiffness_proportional", "0"}}},
            {"ki", {{"control.ki", "0"}}},
            {"k_tip", {{"control.k_tip", "0"}}},
            {"a", {{"hub.radius", "0"}}},
        };
        const Scene sizes = load_scene(path, every_term);
        for (const auto& c : cases) {
            INFO(c.name << " at zero");
            check(with(every_term, c.zero), {c.name}, value_of(sizes, c.name));
        }
    }
}

TEST_CASE("sensitivities left out of the step-size control, on every stepper family", "[sensitivities]")
{
    // solver.sensitivity_error_control = "off": the state alone chooses the steps (CVODES's errconS = false), and the
    // sensitivities carry the error of steps chosen for the state. Measured at rtol 1e-10 on this scene: at most
    // 3.5e-5 of a derivative's largest value (msadams, d_tip_uy/d_J_oh), against 1e-5 with them controlled; the bound
    // leaves a factor 3 (docs/sensitivities.md).
    const Overrides off = {{"solver.sensitivity_error_control", "off"}};
    for (const char* stepper : {"rk8pd", "msadams", "gauss4", "rk4imp", "cvode"})
        check_against_differences("controlled_step.toml", {"kp", "kd", "J_oh", "E"}, 3.0, stepper, 1e-10, 1e-4, off);
}

TEST_CASE("gauss4's exact solve of sensitivities left out of the error test on the stiff spin-up", "[sensitivities]")
{
    // With axial coordinates (Nx = 4), where gauss4 solves the sensitivities' linear stage equations exactly with
    // the Jacobians at the converged state stages: against central differences of converged runs, as the controlled
    // hub's test does, over the spin-up's first 5 s. Measured: within 9.4e-9 (E), 7.6e-8 (L) and 9.5e-9 (I) of the
    // largest value; the bound leaves a factor 13.
    const Overrides off = {{"solver.sensitivity_error_control", "off"}};
    check_against_differences("spinup_omega4.toml", {"E", "L", "I"}, 5.0, "gauss4", 1e-10, 1e-6, off);
}

TEST_CASE("sensitivities left out of the step-size control leave the state's steps and rows as a plain run's",
          "[sensitivities]")
{
    // rk8pd's stages and the staggered correctors of gauss4 and cvode (the state solved first) do not see the
    // sensitivities: the state's steps, and so its rows, are bitwise those of the run without them. With the
    // sensitivities controlled, E's took 2.4 times the steps.
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/controlled_step.toml";
    for (const char* stepper : {"rk8pd", "gauss4", "cvode"}) {
        const Overrides plain = {{"output.t_end", "3"}, {"solver.stepper", stepper}};
        Overrides off = plain;
        off.insert(off.end(), {{"output.sensitivities", "kp,E"}, {"solver.sensitivity_error_control", "off"}});
        const Table a = run(load_scene(path, plain)), b = run(load_scene(path, off));
        REQUIRE(a.rows.size() == b.rows.size());
        for (const std::string& c : a.columns) {
            INFO(stepper << ": " << c);
            CHECK(a.column(c) == b.column(c));
        }
    }
    // The paper's spin-up with axial coordinates (stiff): a simplified Newton iteration on the blocks, with the
    // state's Newton matrix, did not always converge there, and its failed steps were taken again (E: 1,436 steps
    // against 1,434). gauss4 solves the blocks' linear stage equations exactly and takes the plain run's steps.
    {
        const std::string spin_up = std::string(HUBBEAM_SOURCE_DIR) + "/cases/spinup_omega4.toml";
        const Overrides plain = {{"solver.stepper", "gauss4"}};
        Overrides off = plain;
        off.insert(off.end(), {{"output.sensitivities", "E"}, {"solver.sensitivity_error_control", "off"}});
        const Table a = run(load_scene(spin_up, plain)), b = run(load_scene(spin_up, off));
        REQUIRE(a.rows.size() == b.rows.size());
        CHECK(a.steps == b.steps);
        for (const std::string& c : a.columns) {
            INFO("spin-up: " << c);
            CHECK(a.column(c) == b.column(c));
        }
    }
    // GSL's multistep steppers iterate on the whole system, so their rows and steps differ from the plain run's by its
    // round-off: measured over these 3 s, 6 % more (msadams), 0.2 % fewer (msbdf), where the sensitivities controlled
    // took 1.44 to 1.67 times the plain run's.
    for (const char* stepper : {"msadams", "msbdf"}) {
        const Overrides plain = {{"output.t_end", "3"}, {"solver.stepper", stepper}};
        Overrides off = plain;
        off.insert(off.end(), {{"output.sensitivities", "kp,E"}, {"solver.sensitivity_error_control", "off"}});
        const long a = run(load_scene(path, plain)).steps, b = run(load_scene(path, off)).steps;
        INFO(stepper << ": " << a << " steps plain, " << b << " with the sensitivities left out");
        CHECK(b <= 1.1 * a);
    }
}
