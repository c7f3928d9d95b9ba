// What says whether a run can be trusted: the error indicator (windows re-run at a tighter tolerance) against the
// true error of the run, found from an independent run at a far tighter tolerance; the invariant monitor against
// the physics of the beam's free vibration; and the output row's definition (order zero's tip_ux, the columns).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <hubbeam/output.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <string>
#include <vector>

#include "runs.hpp"

using namespace hubbeam;
using test::paper_scene;
using test::spin_up;
using test::torque;

namespace {

using test::collect;
using test::Collected;

/// The true error of rows: the largest difference from reference in tip_uy, tip_ux1 and tip_ux, relative to the
/// column's largest value, over the rows both have.
double true_error(const std::vector<Row>& rows, const std::vector<Row>& reference)
{
    double worst = 0.0;
    for (double Row::*c : {&Row::tip_uy, &Row::tip_ux1, &Row::tip_ux}) {
        double peak = 0.0, diff = 0.0;
        for (std::size_t i = 0; i < std::min(rows.size(), reference.size()); ++i) {
            REQUIRE(rows[i].t == reference[i].t);
            peak = std::max(peak, std::abs(reference[i].*c));
            diff = std::max(diff, std::abs(rows[i].*c - reference[i].*c));
        }
        if (peak > 0.0) worst = std::max(worst, diff / peak);
    }
    return worst;
}

/// The scene at a tolerance far below any the tests judge (its own error is below 1e-6 of every column's peak).
Scene reference_of(Scene s)
{
    s.solver.stepper = "rk8pd";
    s.solver.rtol = 1e-12;
    s.solver.atol = 1e-15;
    return s;
}

}  // namespace

TEST_CASE("a run that its tolerance made wrong is untrustworthy, and the tolerance is named", "[monitor]")
{
    // Explicit steppers at loose tolerances on the stiff axial modes (docs/model.md section 7): the axial stretch
    // is wrong by its own size at once (atol 1e-4 m against a stretch of 2e-6 m), or the steps at the edge of
    // stability let an axial mode grow. Neither changes the Jacobi integral visibly, and the second run ends
    // before the drive does, where that integral is not constant.
    struct Case {
        const char* name;
        Scene scene;
    };
    Scene atol_case = paper_scene(Method::amm, 4, 4, torque(10.0));
    atol_case.solver.stepper = "rk2";
    atol_case.solver.rtol = 1e-2;
    atol_case.solver.atol = 1e-4;
    atol_case.output.t_end = 5.0;
    Scene unstable_case = paper_scene(Method::amm, 4, 4, spin_up(4.0));
    unstable_case.solver.stepper = "rkf45";
    unstable_case.solver.rtol = 1e-2;
    unstable_case.solver.atol = 1e-10;
    unstable_case.output.t_end = 7.0;
    for (const Case& c : {Case{"rk2, atol 1e-4, hub torque", atol_case}, Case{"rkf45, rtol 1e-2, 7 s of spin-up", unstable_case}}) {
        const Collected run = collect(c.scene), reference = collect(reference_of(c.scene));
        REQUIRE(reference.summary.completed);
        const double error = true_error(run.rows, reference.rows);
        INFO(c.name << ": true error " << error << ", estimated " << run.summary.estimated_error << ": "
                    << run.summary.failure);
        CHECK(error > 10.0 * error_tolerance);  // the runs are wrong indeed
        CHECK_FALSE(run.summary.completed);
        CHECK(run.summary.failure.find("the run's error exceeds") != std::string::npos);
        CHECK(run.summary.failure.find("tighten --rtol/--atol") != std::string::npos);
        // The estimate is of the true error's size, within a factor of 3 either way, up to errors of the column's
        // own size: it is relative to the run's largest value, which a grown error dominates.
        CHECK(run.summary.estimated_error > std::min(error, 1.0) / 3.0);
        CHECK(run.summary.estimated_error < error * 3.0);
        CHECK(run.rows.size() == reference.rows.size());  // rows kept to t_end
    }
}

TEST_CASE("a failure caused by the tolerance is not blamed on the model", "[monitor]")
{
    // At atol 1e300 every step passes, and the tip is thrown beyond the beam's length in a few steps; at the
    // tolerance the re-run uses, the same scene stays within 0.3 m of the axis (cases/spinup_omega4.toml).
    Scene s = load_scene(HUBBEAM_SOURCE_DIR "/cases/spinup_omega4.toml");
    s.solver.atol = 1e300;
    s.solver.stepper = "rk4imp";  // gauss4, A-stable and symmetric, stays bounded: it is found untrustworthy instead
    const Collected run = collect(s);
    INFO(run.summary.failure);
    REQUIRE_FALSE(run.summary.completed);
    CHECK(run.summary.failure.find("the run's error, not the model") != std::string::npos);
    CHECK(run.summary.failure.find("tighten --rtol/--atol") != std::string::npos);
    CHECK(run.summary.failure.find("model no longer holds") == std::string::npos);
    CHECK(run.summary.t_reached == run.rows.back().t);

    // The model's own limit stays the model's: order zero spun past its first bending frequency (2.91 rad/s)
    // fails at any tolerance.
    Scene zero = paper_scene(Method::amm, 0, 4, spin_up(4.0));
    zero.variant.order = Order::zero;
    zero.output.t_end = 12.0;
    const Collected unstable = collect(zero);
    INFO(unstable.summary.failure);
    REQUIRE_FALSE(unstable.summary.completed);
    CHECK(unstable.summary.failure.rfind("unstable: the hub rate", 0) == 0);
}

TEST_CASE("the error indicator leaves correct runs alone and bounds their error", "[monitor]")
{
    // The paper's cases as cases/ sets them (rtol 1e-8, atol 1e-10, the automatic stepper): their true error,
    // against a run at 1e-12, is far below error_tolerance, and the indicator says so without understating it
    // tenfold (the axial stretch near atol dominates both).
    for (const char* name : {"spinup_omega4", "spinup_omega10", "torque_tau1", "torque_tau10"}) {
        const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + name + ".toml");
        const Collected run = collect(s);
        INFO(name << ": " << run.summary.failure << "; estimated " << run.summary.estimated_error);
        CHECK(run.summary.completed);
        CHECK(run.summary.estimated_error >= 0.0);
        CHECK(run.summary.estimated_error < 0.2 * error_tolerance);
        if (std::string(name) == "torque_tau1" || std::string(name) == "spinup_omega4") {
            Scene ref = reference_of(s);
            ref.solver.stepper = s.motion.kind == Motion::Kind::torque ? "rk8pd" : "rk4imp";
            const Collected reference = collect(ref);
            const double error = true_error(run.rows, reference.rows);
            INFO("true error " << error);
            CHECK(error < error_tolerance);
            CHECK(run.summary.estimated_error > error / 10.0);
        }
    }
}

TEST_CASE("the invariant monitor: the Jacobi integral's drift against the beam's vibration energy", "[monitor]")
{
    // After the spin-up the beam vibrates freely about the straight shape, mostly in its first mode; its largest
    // strain energy is that of the first cantilever mode at the tip amplitude a: U = 1/2 EI int phi''^2 dx with
    // phi(L) = a, which is (beta_1 L)^4 EI a^2 / (8 L^3), beta_1 L = 1.8751 (int phi^2 dx = L phi(L)^2 / 4 for a
    // cantilever mode). Spin stiffening changes the mode's shape a little: 15 %. No axial coordinates, whose
    // centrifugal stretch energy would add a constant.
    Scene s = paper_scene(Method::amm, 0, 4, spin_up(4.0));
    s.output.t_end = 30.0;
    s.output.dt_out = 0.005;
    const Collected run = collect(s);
    REQUIRE(run.summary.completed);
    double a = 0.0;
    for (const Row& r : run.rows)
        if (r.t >= 15.0) a = std::max(a, std::abs(r.tip_uy));
    const Parameters& p = s.parameters;
    const double beta_L = 1.8751040687119611;
    const double modal = std::pow(beta_L, 4) * p.E * p.I * a * a / (8.0 * p.L * p.L * p.L);
    INFO("amplitude " << a << " m: vibration energy " << run.summary.vibration_energy << " J, first mode " << modal
                      << " J; drift " << run.summary.jacobi_drift << " J");
    CHECK(run.summary.t_steady == 15.0);
    CHECK(std::abs(run.summary.vibration_energy / modal - 1.0) < 0.15);
    // docs/model.md section 7: T2 - T0 + U is constant at steady spin, to the integration's tolerance.
    CHECK(run.summary.jacobi_drift <= 1e-6 * run.summary.vibration_energy);

    // A run the monitor must catch (rk2 at absurd tolerances): the message and the summary give one ratio.
    Scene loose = paper_scene(Method::amm, 0, 4, spin_up(4.0));
    loose.solver.stepper = "rk2";
    loose.solver.rtol = 0.5;
    loose.solver.atol = 1.0;
    const Collected bad = collect(loose);
    REQUIRE_FALSE(bad.summary.completed);
    char ratio[64];
    std::snprintf(ratio, sizeof ratio, " %.2g of the vibration energy", bad.summary.jacobi_drift / bad.summary.vibration_energy);
    INFO(bad.summary.failure);
    CHECK(bad.summary.failure.find(ratio) != std::string::npos);
    CHECK(format_summary(bad.summary, loose).find(ratio) != std::string::npos);
}

TEST_CASE("order zero's tip_ux is tip_ux1: that model has no foreshortening", "[monitor]")
{
    // docs/model.md section 3: order zero drops u_x2, so u_x = u_x1; order first keeps u_x2 = -1/2 B^T H(L) B,
    // nonzero once the beam bends.
    Scene zero = paper_scene(Method::bim, 4, 4, torque(10.0));
    zero.variant.order = Order::zero;
    zero.output.t_end = 3.0;
    Scene first = zero;
    first.variant.order = Order::first;
    const std::vector<Row> z = test::run(zero), f = test::run(first);
    double bent = 0.0, foreshortened = 0.0;
    for (const Row& r : z) {
        CHECK(r.tip_ux == r.tip_ux1);
        bent = std::max(bent, std::abs(r.tip_uy));
    }
    for (const Row& r : f) foreshortened = std::max(foreshortened, std::abs(r.tip_ux - r.tip_ux1));
    CHECK(bent > 0.01);
    CHECK(foreshortened > 1e-5);
}

TEST_CASE("the output row's columns: one table read by the header and the CSV line", "[monitor]")
{
    // Each column's member holds a distinct value: the CSV line carries it under its own header name.
    Row row{};
    for (std::size_t i = 0; i < row_width; ++i) row.*row_columns[i].member = 0.25 + static_cast<double>(i);
    std::vector<std::string> names, values;
    for (std::string h = row_header(), part; !h.empty();) {
        const auto comma = h.find(',');
        names.push_back(h.substr(0, comma));
        h = comma == std::string::npos ? "" : h.substr(comma + 1);
    }
    for (std::string line = csv_line(row); !line.empty();) {
        const auto comma = line.find(',');
        values.push_back(line.substr(0, comma));
        line = comma == std::string::npos ? "" : line.substr(comma + 1);
    }
    REQUIRE(names.size() == row_width);
    REQUIRE(values.size() == row_width);
    const std::vector<std::string> expected{"t", "theta", "theta_dot", "tip_uy", "tip_ux1", "tip_ux",
                                            "kinetic", "potential", "momentum", "jacobi"};
    CHECK(names == expected);
    CHECK(row.tip_ux1 == 4.25);  // the member named tip_ux1 is the fifth column
    for (std::size_t i = 0; i < row_width; ++i) CHECK(std::stod(values[i]) == 0.25 + static_cast<double>(i));
}
