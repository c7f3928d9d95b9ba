// The error check's estimate against the true error of whole runs: neither understated (a wrong run exits 0) nor
// overstated (a right run is called untrustworthy), on the cases whose estimate the end window sets.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include "runs.hpp"

using namespace hubbeam;

namespace {

/// The largest difference from reference over the rows, relative to the column's largest value, of the column
/// (of those every run writes) where that is largest.
double true_error(const std::vector<Row>& rows, const std::vector<Row>& reference)
{
    REQUIRE(rows.size() == reference.size());
    double worst = 0.0;
    for (const RowColumn& c : row_columns) {
        double peak = 0.0, diff = 0.0;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            REQUIRE(rows[i].t == reference[i].t);
            peak = std::max(peak, std::abs(reference[i].*c.member));
            diff = std::max(diff, std::abs(rows[i].*c.member - reference[i].*c.member));
        }
        if (peak > 0.0) worst = std::max(worst, diff / peak);
    }
    return worst;
}

}  // namespace

TEST_CASE("the error estimate of a run at the cases' tolerances is within a factor of 5 of its true error",
          "[monitor]")
{
    // The cases as cases/ sets them, against rk8pd at rtol 1e-12. Their errors are mostly atol-sized noise on a
    // coordinate near zero (tip_ux1), which the end window's estimate scales to the whole run as independent errors
    // add, by the square root of the windows' count: on the spin-up it is then 2.8 times the true error, and a linear
    // sum would make it 20 times.
    for (const char* name : {"torque_tau1", "spinup_omega4"}) {
        const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + name + ".toml");
        const test::Collected run = test::completed_run(s);
        Scene tight = s;
        tight.solver.stepper = "rk8pd";
        tight.solver.rtol = 1e-12;
        tight.solver.atol = 1e-15;
        tight.solver.error_check = ErrorCheck::off;
        const double error = true_error(run.rows, test::run(tight));
        INFO(name << ": estimated " << run.summary.estimated_error << " (" << run.summary.error_column << "), true "
                  << error);
        CHECK(run.summary.estimated_error > error / 3.0);
        CHECK(run.summary.estimated_error < 5.0 * error);
    }
}
