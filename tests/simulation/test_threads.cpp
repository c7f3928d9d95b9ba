// One model shared by runs on two threads (docs/architecture.md, "Models and runs"): each thread's rows equal a serial
// run's exactly, GSL's process-wide error handler stays off while any run steps and comes back as the caller left it,
// and a model is refused by a scene it cannot serve.
#include <catch2/catch.hpp>
#include <gsl/gsl_errno.h>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/stepper.hpp"

using namespace hubbeam;

namespace {

/// A run's every value: the rows' columns (the derivative columns of a sensitivity run copied while the sink runs),
/// and what the summary counts.
struct Record {
    std::vector<double> values;
    std::vector<Row> rows;
    RunSummary summary;
};

Record record(const Scene& scene, std::unique_ptr<Simulation> simulation)
{
    Record r;
    const ColumnSet set = optional_columns_of(scene);
    r.summary = simulation->run([&](const Row& row) {
        for_each_value(row, set, [&](double v) { r.values.push_back(v); });
        r.rows.push_back(row);
        r.rows.back().derived = nullptr;
    });
    return r;
}

/// Two records alike to the bit: rows, the run's end and its counts.
void require_equal(const Record& a, const Record& b)
{
    REQUIRE(a.rows.size() == b.rows.size());
    REQUIRE(a.values.size() == b.values.size());
    for (std::size_t i = 0; i < a.values.size(); ++i) {
        INFO("value " << i);
        REQUIRE(a.values[i] == b.values[i]);
    }
    CHECK(a.summary.completed == b.summary.completed);
    CHECK(a.summary.failure == b.summary.failure);
    CHECK(a.summary.steps == b.summary.steps);
    CHECK(a.summary.rhs_evals == b.summary.rhs_evals);
    CHECK(a.summary.jacobian_evals == b.summary.jacobian_evals);
    CHECK(a.summary.estimated_error == b.summary.estimated_error);
}

Scene case_scene(const std::string& name, const Overrides& overrides)
{
    return load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + name, overrides);
}

/// A handler that counts the errors GSL reports to it: the caller's own, which a run must leave in place.
int caller_handler_calls = 0;
void caller_handler(const char*, const char*, int, int) { ++caller_handler_calls; }

/// The handler GSL calls now (read by swapping it out and back).
gsl_error_handler_t* current_handler()
{
    gsl_error_handler_t* h = gsl_set_error_handler(nullptr);
    gsl_set_error_handler(h);
    return h;
}

/// Two threads each run scene on one model built once; each thread's record must equal a serial run's (on a model
/// of its own). Repeated, since a shared work array corrupts a run only where the threads' calls interleave.
/// Runs scene on model on two threads at once (each making its own Simulation there: the automatic stepper's pilot
/// run reads the model too) and requires both to equal serial.
void run_on_two_threads(const Scene& scene, const std::shared_ptr<const Model>& model, const Record& serial)
{
    Record a, b;
    std::thread first([&] { a = record(scene, std::make_unique<Simulation>(scene, model)); });
    std::thread second([&] { b = record(scene, std::make_unique<Simulation>(scene, model)); });
    first.join();
    second.join();
    require_equal(a, serial);
    require_equal(b, serial);
}

void two_threads_equal_serial(const Scene& scene, int repeats)
{
    const Record serial = record(scene, std::make_unique<Simulation>(scene));
    INFO(serial.summary.failure);
    REQUIRE(serial.rows.size() > 10);
    const std::shared_ptr<const Model> model = make_model(scene.key(), scene.parameters, scene.source);
    gsl_set_error_handler(caller_handler);
    for (int k = 0; k < repeats; ++k) {
        run_on_two_threads(scene, model, serial);
        // A handler swapped per run would be left off here whenever the runs' ends crossed their starts.
        REQUIRE(current_handler() == &caller_handler);
    }
    gsl_set_error_handler(nullptr);
    CHECK(caller_handler_calls == 0);
}

}  // namespace

TEST_CASE("two threads running one generated model: the spin-up's rows and sensitivities are a serial run's", "[threads]")
{
    // The parameter derivatives (dM/dp, dQ/dp) are evaluated at every right-hand side: the generated model's
    // kernels at c = dc/dp less at c = 0, the latter into an array of the call's own.
    const Scene scene = case_scene("spinup_omega4.toml", {{"output.t_end", "2"}, {"output.dt_out", "0.05"},
                                                          {"output.sensitivities", "E,L,rho"}});
    REQUIRE(scene.source != ModelSource::assembled);
    REQUIRE(std::string(make_model(scene.key(), scene.parameters)->source()) == "generated");
    two_threads_equal_serial(scene, 12);
}

TEST_CASE("two threads running one model under torque with implicit steppers: rows equal a serial run's", "[threads]")
{
    // GSL's rk4imp forms the exact Jacobian at every step; msbdf is GSL's multistep implicit one; cvode the SUNDIALS
    // family with its own context per stepper.
    for (const std::string stepper : {"rk4imp", "msbdf", "gauss4", "cvode"}) {
        DYNAMIC_SECTION(stepper)
        {
            const Scene scene = case_scene("torque_tau1.toml", {{"output.t_end", "1"}, {"output.dt_out", "0.05"},
                                                                {"solver.stepper", stepper}});
            two_threads_equal_serial(scene, 2);
        }
    }
}

TEST_CASE("two threads whose GSL stepper fails: each run stops as a serial one does, with GSL's status", "[threads]")
{
    // rk8pd cannot meet rtol 1e-16: the failure comes back from GSL as a status, translated where the stepper
    // returns it.
    const Scene scene = case_scene("spinup_omega4.toml", {{"output.t_end", "1"},
                                                          {"solver.stepper", "rk8pd"},
                                                          {"solver.rtol", "1e-16"},
                                                          {"solver.atol", "1e-300"}});
    const Record serial = record(scene, std::make_unique<Simulation>(scene));
    REQUIRE_FALSE(serial.summary.completed);
    REQUIRE_THAT(serial.summary.failure, Catch::Contains("(GSL status -1)"));
    const std::shared_ptr<const Model> model = make_model(scene.key(), scene.parameters, scene.source);
    for (int k = 0; k < 2; ++k) {
        run_on_two_threads(scene, model, serial);
    }
}

TEST_CASE("GSL's error handler stays off while any GSL stepper lives, then is the caller's again", "[threads]")
{
    const Scene scene = case_scene("spinup_omega4.toml", {});
    const std::unique_ptr<Model> model = make_model(scene.key(), scene.parameters, scene.source);
    FirstOrderSystem system(*model, scene.motion);
    const std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0);
    gsl_set_error_handler(caller_handler);
    caller_handler_calls = 0;
    {
        // Two runs' steppers, the first ending before the second (as on two threads).
        auto first = make_stepper(system, "rk8pd", 0.0, y.data(), 1e-3, 1e-10, 1e-8);
        auto second = make_stepper(system, "msbdf", 0.0, y.data(), 1e-3, 1e-10, 1e-8);
        first.reset();
        // An error GSL reports while the second still steps returns as a status, without the caller's handler.
        gsl_error("reported while a stepper lives", __FILE__, __LINE__, GSL_EINVAL);
        CHECK(caller_handler_calls == 0);
    }
    CHECK(current_handler() == &caller_handler);
    gsl_error("reported after the steppers ended", __FILE__, __LINE__, GSL_EINVAL);
    CHECK(caller_handler_calls == 1);
    gsl_set_error_handler(nullptr);
}

TEST_CASE("a shared model is refused by a scene of another variant or other parameters", "[threads]")
{
    const Scene scene = case_scene("spinup_omega4.toml", {});
    const std::shared_ptr<const Model> model = make_model(scene.key(), scene.parameters, scene.source);
    CHECK_NOTHROW(Simulation(scene, model));
    const Scene finer = case_scene("spinup_omega4.toml", {{"discretization.ny", "5"}});
    CHECK_THROWS_AS(Simulation(finer, model), std::invalid_argument);
    CHECK_THROWS_WITH(Simulation(finer, model), Catch::Contains("cannot run a scene of variant amm_nx4_ny5"));
    const Scene longer = case_scene("spinup_omega4.toml", {{"beam.length", "9"}});
    CHECK_THROWS_WITH(Simulation(longer, model), Catch::Contains("other physical parameters"));
    CHECK_THROWS_AS(Simulation(scene, std::shared_ptr<const Model>()), std::invalid_argument);
    // The assembled path says its parameters too.
    const std::shared_ptr<const Model> assembled = make_model(scene.key(), scene.parameters, ModelSource::assembled);
    CHECK_THROWS_WITH(Simulation(longer, assembled), Catch::Contains("other physical parameters"));
}

TEST_CASE("a simulation runs the scene it was given, whatever becomes of the caller's object", "[threads]")
{
    // Its own copy: a scene changed after the simulation was made (or a temporary, gone) does not reach the run.
    Scene scene = case_scene("spinup_omega4.toml", {{"output.t_end", "0.5"}, {"solver.error_check", "off"}});
    Simulation simulation(scene);
    scene.output.t_end = 3.0;
    scene.output.dt_out = 0.5;
    std::vector<double> times;
    const RunSummary summary = simulation.run([&](const Row& row) { times.push_back(row.t); });
    CHECK(summary.completed);
    REQUIRE(times.size() == 51);  // rows every 0.01 s to 0.5 s, as the scene said when the simulation was made
    CHECK(times.back() == 0.5);
}
