// How critical_speeds searches (linearize.hpp): which lines it searches (one mode followed between two rates, not
// nearly critically damped at both), and that it finds each crossing with a few factorizations near the line's
// eigenvalue, not with every eigenvalue at every rate it tries.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>

using namespace hubbeam;

TEST_CASE("critical speeds leave out lines that jump between modes or are nearly critically damped at both rates",
          "[modes][campbell][critical search]")
{
    // The helicopter blade at FEM Ny = 64: under beta = 1e-3 s its high edge modes lie near critical damping (their
    // eigenvalues about -1/beta = -1000 1/s, among the overdamped modes' slow roots), with damped frequencies below
    // 3 n rad/s; between 0 and 3 rad/s no other mode comes down to n Omega (flap 1 is at 10.9 rad/s).
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml", {{"discretization.ny", "64"}});
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const double theta = scene.motion.initial_theta();
    const std::vector<SpinMode> rows = campbell(*model, {0.0, 3.0}, scene.axial, theta);
    std::map<std::string, std::vector<const SpinMode*>> lines;
    for (const SpinMode& r : rows) lines[r.label].push_back(&r);
    int nearly_critical = 0, jumping = 0;  // lines whose frequency changes sign against 1P .. 3P
    for (const auto& [label, line] : lines) {
        if (line.size() != 2) continue;
        bool crosses = false;
        for (int n = 1; n <= 3; ++n)
            crosses = crosses || (line[0]->mode.rad_s - 0.0) * (line[1]->mode.rad_s - 3.0 * n) < 0.0;
        if (!crosses) continue;
        if (!(line[1]->mac > 0.5))
            ++jumping;
        else if (line[0]->mode.damping_ratio > 0.999 && line[1]->mode.damping_ratio > 0.999)
            ++nearly_critical;
    }
    CHECK(nearly_critical > 0);  // the case this test is about is in the table
    CHECK(jumping > 0);
    for (const CriticalSpeed& c : critical_speeds(*model, rows, {1, 2, 3}, scene.axial, theta)) {
        INFO(c.label << " meets " << c.harmonic << "P at " << c.omega);
        const auto& line = lines.at(c.label);
        CHECK(line[1]->mac > 0.5);
        CHECK(!(line[0]->mode.damping_ratio > 0.999 && line[1]->mode.damping_ratio > 0.999));
    }
}

TEST_CASE("critical speeds cost a few eigen solutions of the whole system, not one per rate tried",
          "[modes][campbell][critical search]")
{
    // The helicopter blade at FEM Ny = Nz = 32 between 0 and 30 rad/s: flap 1 meets 3P and 2P, edge 1 meets 3P, 2P
    // and 1P, each crossing about six rates tried. Following each line's mode by inverse iteration near its
    // predicted eigenvalue costs about 3 full solutions of the modes (natural_modes at one rate, timed here) for all
    // five; computing every mode at every rate tried, or a prediction so poor that every rate falls back to it,
    // costs 30 or more. Timed against the same machine's full solution, the fastest of three each, so that a loaded
    // machine slows both; 12 leaves room for the noise of timing.
    const Scene scene =
        load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml", {{"discretization.ny", "32"}, {"discretization.nz", "32"}});
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const double theta = scene.motion.initial_theta();
    const std::vector<SpinMode> rows = campbell(*model, {0.0, 30.0}, scene.axial, theta);
    using clock = std::chrono::steady_clock;
    double full = HUGE_VAL, search = HUGE_VAL;  // the fastest of three: the least disturbed by other work
    std::vector<CriticalSpeed> speeds;
    for (int k = 0; k < 3; ++k) {
        auto t0 = clock::now();
        (void)natural_modes(*model, steady_spin(*model, 15.0, theta), scene.axial);
        full = std::min(full, std::chrono::duration<double>(clock::now() - t0).count());
        t0 = clock::now();
        speeds = critical_speeds(*model, rows, {1, 2, 3}, scene.axial, theta);
        search = std::min(search, std::chrono::duration<double>(clock::now() - t0).count());
    }
    CHECK(speeds.size() == 5);
    INFO("search " << search << " s, one full solution " << full << " s");
    CHECK(search < 12.0 * full);
}

TEST_CASE("a line whose pairing between two rates is in doubt is not searched there", "[modes][campbell]")
{
    // The helicopter blade's flap 1 line at 0 and 30 rad/s meets 3P and 2P. Its pairing's MAC at 30 set to 1/2 (a
    // line that passes to a mode of another shape between the rates) leaves the interval out; just above 1/2 the
    // line is searched and both crossings are found.
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml");
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const double theta = scene.motion.initial_theta();
    std::vector<SpinMode> rows;
    for (const SpinMode& r : campbell(*model, {0.0, 30.0}, scene.axial, theta))
        if (r.label == "flap 1") rows.push_back(r);
    REQUIRE(rows.size() == 2);
    rows[1].mac = 0.5;
    CHECK(critical_speeds(*model, rows, {1, 2, 3}, scene.axial, theta).empty());
    rows[1].mac = 0.51;
    CHECK(critical_speeds(*model, rows, {1, 2, 3}, scene.axial, theta).size() == 2);
}
