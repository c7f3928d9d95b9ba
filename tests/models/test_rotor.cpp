// A rotor of several blades on one hub (docs/model.md section 13), checked against single blades run alone: with a
// prescribed spin the blades do not interact, so blade b is the single blade at the hub angle theta + 2 pi (b-1)/N
// (motion.theta0) with its own pitch and tip mass; under a torque, N identical blades turn their hub as one blade with
// 1/N of the hub's inertia and torque; about a steady spin each blade mode appears N times. The rotor's own code
// (gather, scatter, the torque on the hub once) is what these catch; the blades' kernels are the single blade's.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <map>
#include <string>
#include <vector>

#include "runs.hpp"
#include "soft_blade.hpp"

using namespace hubbeam;
using hubbeam::test::run_columns;

namespace {

/// The soft blade (soft_blade.hpp) in the plane of rotation under gravity (so that a blade's azimuth matters), with
/// overrides, its [motion] a spin-up to 6 rad/s in 2 s or a torque pulse (motion.tau0 to set).
Scene scene_with(const Overrides& o, bool torque = false)
{
    const std::string extra = "\n[gravity]\ng = 9.81\n\n[solver]\nstepper = \"rk8pd\"\nrtol = 1e-11\natol = 1e-13\n"
                              "error_check = \"off\"\n";
    return parse_scene(test::soft_blade_scene(torque, extra), "rotor_test.toml", o);
}


double max_difference(const std::vector<double>& a, const std::vector<double>& b)
{
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

double peak(const std::vector<double>& a)
{
    double p = 0.0;
    for (double v : a) p = std::max(p, std::abs(v));
    return p;
}

}  // namespace

TEST_CASE("a prescribed rotor's blade b is the single blade at its azimuth, pitch and tip mass", "[rotor]")
{
    const Scene rotor = scene_with({{"rotor.blades", "3"},
                                    {"rotor.pitch_offsets", "0, 0.05, -0.08"},
                                    {"rotor.tip_masses", "1.5, 0, 4"}});
    auto rows = run_columns(rotor);
    REQUIRE(rows.count("tip_uy_3") == 1);
    REQUIRE(rows.count("tip_uy") == 0);
    const double pi = std::acos(-1.0);
    const double pitch_offsets[] = {0.0, 0.05, -0.08}, tip_masses[] = {1.5, 0.0, 4.0};
    for (int b = 0; b < 3; ++b) {
        const Scene one = scene_with({{"motion.theta0", std::to_string(2.0 * pi * b / 3.0)},
                                      {"beam.pitch", std::to_string(0.1 + pitch_offsets[b])},
                                      {"tip.mass", std::to_string(tip_masses[b])}});
        auto alone = run_columns(one);
        for (const char* c : {"tip_uy", "tip_uz", "tip_phi", "tip_ux"}) {
            const std::string mine = std::string(c) + "_" + std::to_string(b + 1);
            INFO("blade " << b + 1 << " column " << c);
            // std::to_string's six decimals move the azimuth by < 5e-7 rad: far below the tolerance's effect.
            CHECK(max_difference(rows[mine], alone[c]) <= 1e-6 * peak(alone[c]) + 1e-12);
        }
    }
    // The blades differ (the check would pass for a rotor that ran blade 1 thrice).
    CHECK(max_difference(rows["tip_uz_1"], rows["tip_uz_3"]) > 1e-3 * peak(rows["tip_uz_1"]));
}

TEST_CASE("a planar rotor's blade b is the single planar blade at its azimuth, column by column", "[rotor]")
{
    // In the plane (no flap or twist fields, no pitch) each blade has three tip columns, not five.
    const Overrides planar = {{"discretization.nz", "0"}, {"discretization.nt", "0"}, {"beam.pitch", "0"}};
    Overrides with_blades = planar;
    with_blades.push_back({"rotor.blades", "3"});
    with_blades.push_back({"rotor.tip_masses", "1.5, 0, 4"});
    auto rows = run_columns(scene_with(with_blades));
    REQUIRE(rows.count("tip_uz_2") == 0);
    const double pi = std::acos(-1.0);
    const double tip_masses[] = {1.5, 0.0, 4.0};
    for (int b = 0; b < 3; ++b) {
        Overrides one = planar;
        one.push_back({"motion.theta0", std::to_string(2.0 * pi * b / 3.0)});
        one.push_back({"tip.mass", std::to_string(tip_masses[b])});
        auto alone = run_columns(scene_with(one));
        for (const char* c : {"tip_uy", "tip_ux1", "tip_ux"}) {
            const std::string mine = std::string(c) + "_" + std::to_string(b + 1);
            INFO("blade " << b + 1 << " column " << c);
            CHECK(max_difference(rows[mine], alone[c]) <= 1e-6 * peak(alone[c]) + 1e-12);
        }
    }
}

TEST_CASE("a rotor of N identical blades under a torque turns the hub as one blade with 1/N of its inertia and torque",
          "[rotor]")
{
    const Overrides torque = {{"motion.tau0", "30"}, {"gravity.g", "0"}};
    Overrides rotor = torque;
    rotor.push_back({"rotor.blades", "3"});
    Overrides one = torque;
    one.push_back({"hub.inertia", std::to_string(40.0 / 3.0)});
    one.push_back({"motion.tau0", "10"});
    // Later overrides win: the single blade's hub is a third of the rotor's.
    auto r = run_columns(scene_with(rotor, true));
    auto s = run_columns(scene_with(one, true));
    CHECK(max_difference(r["theta"], s["theta"]) <= 1e-8 * peak(s["theta"]));
    for (int b = 1; b <= 3; ++b) {
        INFO("blade " << b);
        CHECK(max_difference(r["tip_uy_" + std::to_string(b)], s["tip_uy"]) <= 1e-7 * peak(s["tip_uy"]));
    }
    // Energies and angular momentum are the rotor's: three blades' and one hub's (at t = 0.25 s, the torque's peak
    // impulse; the pulse's net impulse is zero, so the momentum ends at round-off).
    const std::size_t mid = 5;
    REQUIRE(s["t"][mid] == Approx(0.25));
    CHECK(r["kinetic"][mid] == Approx(3.0 * s["kinetic"][mid]).epsilon(1e-7));
    CHECK(r["momentum"][mid] == Approx(3.0 * s["momentum"][mid]).epsilon(1e-7));
}

TEST_CASE("about a steady spin a rotor of N identical blades has each blade mode N times", "[rotor]")
{
    const Overrides still = {{"gravity.g", "0"}};
    Overrides three = still;
    three.push_back({"rotor.blades", "3"});
    const Scene rotor = scene_with(three), one = scene_with(still);
    const auto rotor_model = make_scene_model(rotor);
    const auto blade_model = make_scene_model(one);
    REQUIRE(rotor_model->nq() == 3 * blade_model->nq());
    const auto blade = natural_modes(*blade_model, steady_spin(*blade_model, 6.0));
    const auto all = natural_modes(*rotor_model, steady_spin(*rotor_model, 6.0));
    REQUIRE(all.size() == 3 * blade.size());
    for (std::size_t i = 0; i < blade.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k) {
            INFO("blade mode " << i << " copy " << k);
            CHECK(all[3 * i + k].undamped_rad_s == Approx(blade[i].undamped_rad_s).epsilon(1e-9));
            CHECK(all[3 * i + k].kind == blade[i].kind);
        }
}

TEST_CASE("a rotor's scene keys are checked, naming the key", "[rotor]")
{
    const auto refused = [](const Overrides& o, const std::string& key) {
        try {
            scene_with(o);
        } catch (const SceneError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(key) != std::string::npos);
            return true;
        }
        return false;
    };
    CHECK(refused({{"rotor.blades", "0"}}, "rotor.blades"));
    CHECK(refused({{"rotor.blades", "65"}}, "rotor.blades"));
    CHECK(refused({{"rotor.blades", "3"}, {"rotor.pitch_offsets", "0, 0.1"}}, "rotor.pitch_offsets"));
    CHECK(refused({{"rotor.blades", "2"}, {"rotor.pitch_offsets", "0, 7"}}, "rotor.pitch_offsets"));
    CHECK(refused({{"rotor.blades", "2"}, {"rotor.tip_masses", "1, -1"}}, "rotor.tip_masses"));
    CHECK(refused({{"rotor.blades", "2"}, {"rotor.tip_masses", "1, x"}}, "rotor.tip_masses"));
    CHECK(refused({{"rotor.blades", "2"}, {"rotor.tip_masses", "1, 1"}, {"tip.mass", "2"}}, "rotor.tip_masses"));
    CHECK(refused({{"rotor.blades", "2"}, {"output.sensitivities", "L"}}, "output.sensitivities"));
    // One blade keeps a single blade's columns.
    const Scene one = scene_with({});
    const std::vector<std::string> names = row_column_names(optional_columns_of(one));
    CHECK(std::find(names.begin(), names.end(), "tip_uy") != names.end());
    CHECK(std::find(names.begin(), names.end(), "tip_uy_1") == names.end());
}

TEST_CASE("a balanced rotor under gravity does not swing on a free hub, where one blade falls", "[rotor]")
{
    // Three blades at 120 degrees: their weights' moments about the axis cancel (for rigid blades exactly; the blades'
    // sag leaves a moment of the sag's order). A single blade at 0.3 rad above the horizontal falls.
    const Overrides free = {{"motion.theta0", "0.3"}, {"gravity.g", "9.81"}};
    Overrides rotor = free;
    rotor.push_back({"rotor.blades", "3"});
    auto r = run_columns(scene_with(rotor, true));
    auto s = run_columns(scene_with(free, true));
    const auto swing = [](const std::vector<double>& theta) {
        double d = 0.0;
        for (double v : theta) d = std::max(d, std::abs(v - 0.3));
        return d;
    };
    CHECK(swing(s["theta"]) > 0.05);
    CHECK(swing(r["theta"]) < 1e-3 * swing(s["theta"]));
}
