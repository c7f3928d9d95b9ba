// Forward sensitivities (sensitivity.hpp) against central differences of whole runs at moved parameters: the paper's
// four cases and the controlled hub, and every stepper family on the controlled hub.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "make_model.hpp"
#include "scene.hpp"
#include "sensitivity.hpp"
#include "simulate.hpp"

using namespace hubbeam;

namespace {

/// The rows of a run of scene, each with its derivative columns after the row's own values.
struct Table {
    std::vector<std::vector<double>> rows;
    std::vector<std::string> columns;
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
    if (p == "E") return "beam.youngs_modulus";
    if (p == "L") return "beam.length";
    if (p == "rho") return "beam.density";
    if (p == "J_oh") return "hub.inertia";
    if (p == "a") return "hub.radius";
    return "control." + p;
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
    converged.insert(converged.end(), {{"solver.rtol", "1e-12"}, {"solver.atol", "1e-14"}, {"solver.stepper", "rk8pd"}});
    Overrides with = base;
    std::string names;
    for (const std::string& p : parameters) names += (names.empty() ? "" : ",") + p;
    with.emplace_back("output.sensitivities", names);
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + file;
    const Scene scene = load_scene(path, with);
    const Table exact = run(scene);
    for (const std::string& p : parameters) {
        Parameters values = scene.parameters;
        double v = 0.0;
        if (const auto at = std::find(param_names.begin(), param_names.end(), p); at != param_names.end())
            v = value(values, static_cast<Param>(at - param_names.begin()));
        else
            v = p == "kp" ? scene.control->kp : scene.control->kd;
        // A step of 1e-4: the differences' truncation error is ~1e-8 of the derivative, and the runs' own errors
        // (rtol |y|, uncorrelated from run to run as their steps differ) are divided by 2h p ~ 1e-4 p, not less.
        const double h = 1e-4 * (v != 0.0 ? std::abs(v) : 1.0);
        Overrides up = converged, down = converged;
        up.emplace_back(key_of(p), text(v + h));
        down.emplace_back(key_of(p), text(v - h));
        const Table a = run(load_scene(path, up)), b = run(load_scene(path, down));
        REQUIRE(a.rows.size() == exact.rows.size());
        for (const char* out : {"theta", "tip_uy"}) {
            if (std::string(out) == "theta" && scene.drive() != Drive::torque) continue;
            const std::vector<double> ya = a.column(out), yb = b.column(out), d = exact.column("d_" + std::string(out) + "/d_" + p);
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

TEST_CASE("sensitivities to the controller's gains, on every stepper family", "[sensitivities]")
{
    // The scene's torque saturates until t = 1.24 s. Where it lets go the sensitivities' rates jump (the gains' own
    // terms and the torque's dependence on the state switch on), and a step across that kink has a first-order error
    // that gauss4's step doubling does not estimate: it steps to the switch, a breakpoint the simulation locates
    // (without, its sensitivities came 1e-5 to 2e-5 off at rtol 1e-9 and 1e-10).
    for (const char* stepper : {"rk8pd", "msadams", "gauss4", "rk4imp"})
        check_against_differences("controlled_step.toml", {"kp", "kd", "J_oh"}, 3.0, stepper, 1e-10, 1e-5);
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
        y[0] = 0.45;   // the hub near its reference 0.5: the controller unsaturated
        y[static_cast<std::size_t>(nq)] = 0.01;  // theta_dot
        const double t = 0.7;
        REQUIRE(system.rhs(t, y.data(), f.data()) == 0);
        for (std::size_t j = 0; j < c.names.size(); ++j) {
            const std::string& name = c.names[j];
            const auto rates_at = [&](double delta, double& scale) {
                Scene moved = scene;
                moved.output.sensitivities.clear();
                double* v = nullptr;
                if (name == "kp") v = &moved.control->kp;
                else if (name == "kd") v = &moved.control->kd;
                else v = &value(moved.parameters,
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
                const double expected = (up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2.0 * h);
                INFO(c.file << ": d(row " << i << ")/d_" << name);
                CHECK(f[static_cast<std::size_t>(n * (1 + static_cast<int>(j)) + i)] ==
                      Approx(expected).epsilon(1e-6).margin(1e-9 * (1.0 + std::abs(up[static_cast<std::size_t>(i)]))));
            }
        }
    }
}
