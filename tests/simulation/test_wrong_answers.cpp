// Answers that must never come out wrong with exit 0: the error check covers every column a run writes (and every
// row of a run looser than the defaults, whose error can add up between its windows), a row with a non-finite value
// is never written, scenes whose parameters or angles would give silent nonsense are refused, and a table's messages
// say where the problem is without echoing what the file holds.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "simulation/column_check.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

const std::string cases = std::string(HUBBEAM_SOURCE_DIR) + "/cases/";

using Folder = TempFolder;

/// The SceneError message of loading file (with overrides); fails the test when it loads.
std::string error_of(const std::string& file, const Overrides& overrides = {})
{
    try {
        load_scene(file, overrides);
    } catch (const SceneError& e) {
        return e.what();
    }
    FAIL("no SceneError for " << file);
    return {};
}

/// The header's fields.
std::vector<std::string> fields(const std::string& header)
{
    std::vector<std::string> names;
    for (std::size_t at = 0; at <= header.size();) {
        const std::size_t comma = std::min(header.find(',', at), header.size());
        names.push_back(header.substr(at, comma - at));
        at = comma + 1;
    }
    return names;
}

}  // namespace

TEST_CASE("the error check compares every column a run writes, a derived one perturbed in the run alone included",
          "[simulate][error]")
{
    // A controlled hub with sensitivities: state, energy, optional (tau, theta_ref, work) and derivative columns.
    Scene scene =
        load_scene(cases + "controlled_step.toml", {{"output.t_end", "0.05"}, {"output.sensitivities", "kp,J_oh"}});
    const ColumnSet set = optional_columns_of(scene);
    const std::vector<std::string> names = fields(row_header(set));
    std::vector<double> row;
    simulate(scene, [&](const Row& r) {
        if (r.t == 0.05) append_row_values(r, set, row);
    });
    // The values compared are the CSV line's, one for each column of its header.
    REQUIRE(row.size() == names.size());
    // Two parameters by the planar beam's five outputs: theta, theta_dot, tip_uy, tip_ux1, tip_ux.
    REQUIRE(names.size() == row_width + 3 + 2 * 5);
    std::vector<double> peak(row.size()), floor(row.size(), 0.0);
    for (std::size_t c = 0; c < row.size(); ++c) peak[c] = std::max(std::abs(row[c]), 1e-3);
    for (std::size_t c = 1; c < row.size(); ++c) {  // t is the time of both rows
        INFO(names[c]);
        std::vector<double> run = row;
        run[c] += 2.0 * error_tolerance * peak[c];
        const ColumnDifference d = largest_difference(run, row, peak, floor);
        CHECK(d.column == c);
        CHECK(d.fraction > error_tolerance);
        // A non-finite value in one row is the largest difference there can be.
        run[c] = std::numeric_limits<double>::quiet_NaN();
        CHECK(largest_difference(run, row, peak, floor).fraction == INFINITY);
    }
    CHECK(largest_difference(row, row, peak, floor).fraction == 0.0);
    // A re-run that stopped early has fewer values: nothing to compare.
    CHECK(largest_difference(row, std::vector<double>(row.begin(), row.end() - 1), peak, floor).fraction < 0.0);
}

TEST_CASE("a run looser than the defaults is judged by the whole run: an error that adds up in dissipated is seen, a "
          "right loose run passes",
          "[simulate][error]")
{
    // cases/damped_appendage.toml at rtol 1e-2: cvode's dissipated energy takes an error in every step that adds up
    // over the run (5.5 % of its largest value by t = 20 s against rk8pd at rtol 1e-11), while its windows, where
    // little is dissipated, estimated 9e-5 and the run exited 0; gauss4's is 0.36 % off and stands.
    const auto dissipated = [](const std::vector<Row>& rows) {
        std::vector<double> d;
        for (const Row& r : rows) d.push_back(r.extras.dissipated);
        return d;
    };
    const auto run_of = [](const Scene& s, std::vector<Row>& rows) {
        return simulate(s, [&rows](const Row& r) { rows.push_back(r); });
    };
    std::vector<Row> reference;
    const RunSummary tight = run_of(load_scene(cases + "damped_appendage.toml", {{"solver.stepper", "rk8pd"},
                                                                                {"solver.rtol", "1e-11"},
                                                                                {"solver.atol", "1e-13"},
                                                                                {"solver.error_check", "off"}}),
                                    reference);
    REQUIRE(tight.completed);
    const std::vector<double> truth = dissipated(reference);
    const double peak = *std::max_element(truth.begin(), truth.end());
    for (const auto& [stepper, wrong] : {std::pair{"cvode", true}, {"gauss4", false}}) {
        std::vector<Row> rows;
        const RunSummary s =
            run_of(load_scene(cases + "damped_appendage.toml", {{"solver.stepper", stepper}, {"solver.rtol", "1e-2"}}),
                   rows);
        INFO(stepper << ": " << s.failure);
        REQUIRE(rows.size() == reference.size());  // the rows are kept to t_end either way
        const std::vector<double> d = dissipated(rows);
        double error = 0.0;
        for (std::size_t i = 0; i < d.size(); ++i) error = std::max(error, std::abs(d[i] - truth[i]) / peak);
        INFO("dissipated " << error << " off, estimated " << s.estimated_error << " (" << s.error_column << ")");
        CHECK((error > error_tolerance) == wrong);  // the runs are as said
        CHECK(s.error_from == "the whole run");
        CHECK(s.error_column == "dissipated");
        CHECK(s.estimated_error > 0.8 * error);
        CHECK(s.estimated_error < 1.25 * error);
        CHECK(s.completed == !wrong);
        if (wrong)
            CHECK(s.failure.find("untrustworthy: the run's error exceeds 0.01: its dissipated differs by 0.05") == 0);
    }
    // Either tolerance looser than the defaults' makes the whole run the reference; at the defaults the windows stay.
    for (const auto& [key, value, from] : {std::tuple{"solver.atol", "1e-9", "the whole run"},
                                           {"solver.rtol", "1e-6", "the whole run"},
                                           {"solver.rtol", "1e-8", "windows"}}) {
        const RunSummary s =
            simulate(load_scene(cases + "spinup_omega4.toml", {{"output.t_end", "1"}, {key, value}}), [](const Row&) {});
        INFO(key << " = " << value << ": " << s.failure);
        CHECK(s.error_from == from);
    }
}

TEST_CASE("a row with a non-finite value is not written: the run stops at the rows before it and says so", "[simulate]")
{
    // A torque law that is NaN at one row's time only (the steps, with rk8pd's free stepping, never end there), so
    // the state stays finite and only that row's tau column would be NaN.
    Scene scene = load_scene(cases + "controlled_step.toml",
                             {{"output.t_end", "1"}, {"solver.stepper", "rk8pd"}, {"solver.error_check", "off"}});
    scene.control->law = [](double t, const HubState&) {
        return std::abs(t - 0.5) < 1e-12 ? std::numeric_limits<double>::quiet_NaN() : 1.0;
    };
    const ColumnSet set = optional_columns_of(scene);
    std::vector<double> last;
    long rows = 0;
    bool finite = true;
    const RunSummary summary = simulate(scene, [&](const Row& r) {
        last.clear();
        append_row_values(r, set, last);
        for (const double v : last) finite = finite && std::isfinite(v);
        ++rows;
    });
    INFO(summary.failure);
    CHECK(finite);
    CHECK_FALSE(summary.completed);
    CHECK(rows == 50);  // t = 0 to 0.49 s
    CHECK(summary.failure.find("non-finite at t = 0.5 s (tau is ") != std::string::npos);
    CHECK(summary.failure.find("the rows up to t = 0.49 s are written, not this one") != std::string::npos);
}

TEST_CASE("a profile refuses sensitivities to rho, S, I and E, which its table replaces", "[scene][sensitivities]")
{
    for (const char* p : {"rho", "S", "I", "E"}) {
        const std::string message =
            error_of(cases + "profile_blade.toml", {{"output.sensitivities", std::string("L,") + p}});
        INFO(message);
        CHECK(message.find("output.sensitivities: expected a parameter that the scene uses, not " + std::string(p) +
                           " with beam.profile") != std::string::npos);
    }
    CHECK(load_scene(cases + "profile_blade.toml", {{"output.sensitivities", "L,J_oh"}}).output.sensitivities.size() ==
          2);
}

TEST_CASE("a sensitivity to a parameter of a term the scene does not carry is refused, not a column of zeros",
          "[scene][sensitivities]")
{
    // Without a [support] the hub does not translate and its mass and support are in no equation; without a taper
    // the tip ratio is in none: their derivatives would be zeros that say nothing.
    const std::vector<std::pair<std::string, std::string>> refused = {
        {"m_hub", "a [support] table"}, {"k_x", "a [support] table"}, {"c_y", "a [support] table"},
        {"tip_ratio", "beam.taper \"width\" or \"depth\""}};
    for (const auto& [p, chosen_by] : refused) {
        const std::string message = error_of(cases + "spinup_omega4.toml", {{"output.sensitivities", "E," + p}});
        INFO(message);
        CHECK(message.find("output.sensitivities: expected " + p + " only with " + chosen_by) != std::string::npos);
    }
    // Where the scene carries the term, they are derivatives like any other.
    CHECK(load_scene(cases + "ground_resonance.toml", {{"rotor.blades", "1"}, {"rotor.tip_masses", "0"},
                                                       {"output.sensitivities", "m_hub,k_x"}})
              .output.sensitivities.size() == 2);
    const Scene tapered = load_scene(cases + "tapered_blade.toml", {{"output.sensitivities", "tip_ratio"}});
    CHECK(tapered.output.sensitivities.size() == 1);
}

TEST_CASE("hub angles beyond max_hub_angle are refused, naming the key, the value and the bound", "[scene]")
{
    const Folder f;
    std::ifstream in(cases + "spinup_omega4.toml");
    const std::string spin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // At 1e17 rad a hub turning at 2 rad/s does not move at all in double precision.
    for (const auto& [key, value] : {std::pair{"motion.theta0", "1e17"}, {"motion.theta0", "-2e6"}}) {
        const std::string message = error_of(f.write("s.toml", spin), {{key, value}});
        INFO(message);
        CHECK(message.find(std::string(key) + ": expected |theta0| <= 1e+06 rad") != std::string::npos);
    }
    CHECK(load_scene(f.write("s.toml", spin), {{"motion.theta0", "1e6"}}).motion.theta0 == 1e6);
    // The scene with its [motion] table's keys replaced by motion.
    const auto with_motion = [&](const std::string& motion) {
        const std::size_t from = spin.find("[motion]\n") + 9, to = spin.find("\n[", from) + 1;
        return spin.substr(0, from) + motion + spin.substr(to);
    };
    const std::string held = error_of(f.write("h.toml", with_motion("kind = \"held\"\nangle = 1e9\n")));
    INFO(held);
    CHECK(held.find("motion.angle: expected |angle| <= 1e+06 rad") != std::string::npos);
    // An angle table's values too.
    f.write("m.csv", "t,theta\n0,0\n1,0.5\n2,3e6\n40,0\n");
    const std::string table = error_of(f.write("t.toml", with_motion("kind = \"table\"\nfile = \"m.csv\"\n")));
    INFO(table);
    CHECK(table.find((f.path / "m.csv").string() + ":4: expected |theta| <= 1e+06 rad") != std::string::npos);
    // A run whose angle passes the bound stops there: the spin-up, 1.9e-3 rad in its first second, from 1e-3 rad below.
    const Scene near = load_scene(f.write("n.toml", spin),
                                  {{"motion.theta0", "999999.999"}, {"output.t_end", "1"}, {"discretization.nx", "0"}});
    double last = 0.0;
    const RunSummary summary = simulate(near, [&](const Row& r) { last = r.theta; });
    INFO(summary.failure);
    CHECK_FALSE(summary.completed);
    CHECK(summary.failure.find("has passed 1e+06 rad, beyond which double precision") != std::string::npos);
    CHECK(last > max_hub_angle);
    CHECK(last < max_hub_angle + 0.05);  // the first row past it
}

TEST_CASE("a motion or profile table's message says what was expected and where, never what the file holds",
          "[scene][profile]")
{
    const Folder f;
    std::ifstream in(cases + "torque_table.toml");
    const std::string scene((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string file = f.write("torque_table.toml", scene);
    const std::string csv = (f.path / "torque_table.csv").string();
    const auto message_of = [&](const std::string& table) {
        f.write("torque_table.csv", table);
        const std::string message = error_of(file);
        INFO(message);
        CHECK(message.find("s3cr3t") == std::string::npos);
        return message;
    };
    const auto has = [](const std::string& message, const std::string& part) {
        INFO(message);
        CHECK(message.find(part) != std::string::npos);
    };
    // A credentials file's first line is a header without the columns: neither it nor a field is echoed.
    has(message_of("user:s3cr3t:1000\n0,0\n"),
        csv + ":1: expected a column t in its header (time, s), got none among its 1 columns");
    has(message_of("t,tau\n0,1\n1,s3cr3t\n"), csv +
                                                  ":3: expected a finite number in column tau (the hub torque, N m), "
                                                  "field 2 of the line");
    // Each column is described by its own meaning, not the table's other column's.
    has(message_of("time,tau,s3cr3t\n0,1,2\n1,1,2\n"), "expected a column t in its header (time, s)");
    // A duplicated column would be read from its first copy without a word.
    has(message_of("t,tau,tau\n0,1,2\n1,1,2\n"),
        csv + ":1: expected one column tau in its header (the hub torque, N m), got 2");
    // The profile reader is the same reader.
    const std::string blade = f.write("blade.toml", [&] {
        std::ifstream b(cases + "profile_blade.toml");
        return std::string((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    }());
    f.write("profile_blade.csv", "x/L,m,EI,EI,ES\n0,1,1,1,1\n1,1,1,1,1\n");
    has(error_of(blade),
        "expected one column EI in its header (bending stiffness (edgewise out of the plane), N m^2), got 2");
    f.write("profile_blade.csv", "root:s3cr3t\n");
    const std::string profile = error_of(blade);
    has(profile, "expected a column x/L in its header (the station along the span, 0 at the root to 1 at the tip)");
    CHECK(profile.find("s3cr3t") == std::string::npos);
}
