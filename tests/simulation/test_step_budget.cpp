// The step budget (solver.max_steps): a run whose pace projects past it stops early, long before it has spent it,
// says so with the projection, and keeps the rows written so far.
#include <catch2/catch.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <regex>
#include <string>
#include <vector>

#include "runs.hpp"

using namespace hubbeam;
using namespace hubbeam::test;

TEST_CASE("a run whose pace projects past solver.max_steps stops early and keeps its rows", "[budget]")
{
    // The paper's spin-up on rk8pd: its axial mode (980 rad/s) bounds the explicit steps by stability, about 2,000 a
    // second at an even pace, so 30 s take some 60,000, fifteen times a budget of 4,000. The pace is measured from a
    // twentieth of the budget on: the run stops there, not at the budget's end a tenth of the way through.
    const std::string path = std::string(HUBBEAM_SOURCE_DIR) + "/cases/spinup_omega4.toml";
    const Overrides rk8pd = {{"solver.stepper", "rk8pd"}};
    Overrides limited = rk8pd;
    limited.push_back({"solver.max_steps", "4000"});
    const Collected stopped = collect(load_scene(path, limited));
    REQUIRE_FALSE(stopped.summary.completed);
    const std::string& why = stopped.summary.failure;
    INFO(why);
    std::smatch m;
    REQUIRE(std::regex_search(why, m,
                              std::regex("too many steps: ([0-9]+) by t = ([0-9.e+-]+) s, about ([0-9.e+-]+) to "
                                         "t_end, more than solver.max_steps = 4000")));
    const long taken = std::stol(m[1]);
    const double t_stop = std::stod(m[2]), projected = std::stod(m[3]);
    // Stopped on the projection, with most of the budget left: not by the plain limit.
    CHECK(taken < 4000 / 10);
    CHECK(projected > 4000);
    CHECK(projected == Approx(static_cast<double>(taken) * 30.0 / t_stop).epsilon(1e-2));
    CHECK(t_stop < 30.0 / 10);
    // The rows written so far are kept: those of the same run without a budget, to the stop.
    REQUIRE_FALSE(stopped.rows.empty());
    CHECK(stopped.rows.back().t <= t_stop);
    CHECK(stopped.rows.back().t > t_stop - 0.01);  // dt_out = 0.01 s
    Overrides short_run = rk8pd;
    short_run.push_back({"output.t_end", "0.5"});
    const std::vector<Row> full = run(load_scene(path, short_run));
    REQUIRE(full.size() > stopped.rows.size());
    for (std::size_t k = 0; k < stopped.rows.size(); ++k) {
        INFO("row " << k);
        CHECK(stopped.rows[k].t == full[k].t);
        CHECK(stopped.rows[k].tip_uy == Approx(full[k].tip_uy).margin(1e-12));
    }
}
