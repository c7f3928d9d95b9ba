// A damped blade's modes that do not oscillate (linearize.hpp natural_modes, critical_speeds; the modes table that
// hubbeam modes and hubbeam.modes share): each real decaying eigenvalue is a row of kind "overdamped" with
// frequency 0, and meets no excitation line n Omega, at rest either; a line that leaves rest overdamped and then
// oscillates meets a line where its damped frequency is n Omega, checked on the eigenvalues of the state matrix
// (state_space), which the modes' own filtering and tracking do not touch.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/modes_table.hpp>

#include "eigen_oracles.hpp"

using namespace hubbeam;

namespace {

/// cases/helicopter_blade.toml (FEM, Ny = Nz = 8, Rayleigh damping) with overrides, its modes block at omegas.
ModesBlock blade_block(const std::vector<double>& omegas, const Overrides& overrides = {})
{
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml", overrides);
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    return modes_block(*model, scene.key(), scene, omegas, {1, 2, 3});
}

/// The smallest distance of an eigenvalue's imaginary part of the state matrix about the steady spin at omega to
/// rad_s, relative to rad_s.
double nearest_frequency(double omega, double rad_s, const Overrides& overrides)
{
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml", overrides);
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const StateSpace ss = state_space(*model, steady_spin(*model, omega, scene.motion.initial_theta()));
    const Eigen::VectorXcd lambda = test::general_eigen(ss.A, false).values;
    double nearest = HUGE_VAL;
    for (const std::complex<double>& l : lambda) nearest = std::min(nearest, std::abs(std::abs(l.imag()) - rad_s));
    return nearest / rad_s;
}

}  // namespace

TEST_CASE("a damped blade's overdamped modes are rows of kind overdamped that meet no excitation line",
          "[modes][campbell]")
{
    // Stiffness-proportional damping (beta = 1e-3 s) makes the FEM blade's stiff modes overdamped: a real pair
    // each, the rows of frequency 0 and zeta 1 that once met 1P, 2P and 3P "at Omega = 0" (24 of them).
    const ModesBlock block = blade_block({0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0});
    int overdamped = 0;
    for (const SpinMode& r : block.modes) {
        INFO("Omega " << r.omega << ", mode " << r.number << ", " << r.mode.kind << ", " << r.label);
        const bool real_decaying = r.mode.rad_s == 0.0 && r.mode.growth < 0.0;
        CHECK(real_decaying == (r.mode.kind == "overdamped"));
        if (!real_decaying) continue;
        ++overdamped;
        CHECK(r.mode.damping_ratio == 1.0);
        CHECK(r.mode.undamped_rad_s == -r.mode.growth);
    }
    CHECK(overdamped >= 7 * 8);  // eight at each rate (twelve at rest)
    // The critical speeds are those of the oscillating lines alone, where the damped frequency is n Omega.
    std::vector<std::pair<std::string, int>> met;
    for (const CriticalSpeed& c : block.critical) {
        INFO(c.label << " meets " << c.harmonic << "P at " << c.omega);
        met.emplace_back(c.label, c.harmonic);
        CHECK(c.omega > 0.0);
        CHECK(nearest_frequency(c.omega, c.rad_s, {}) < 1e-7);
    }
    CHECK(met == std::vector<std::pair<std::string, int>>{
                     {"flap 1", 3}, {"flap 1", 2}, {"edge 1", 3}, {"edge 1", 2}, {"edge 1", 1}});
}

TEST_CASE("a line that leaves rest overdamped meets 1P where it oscillates at the spin rate, whatever the step",
          "[modes][campbell]")
{
    // Mass-proportional damping alpha = 22 1/s overdamps the first flap mode at rest (alpha / 2 = 11 above its
    // 10.92 rad/s); the spin stiffens it until its damped frequency sqrt(omega_flap^2 - (alpha + beta
    // omega_flap^2)^2 / 4) passes Omega (about 3.37 rad/s). From the rates 0 and 5 the crossing is bracketed by rest,
    // where the line's gap rad_s - Omega is 0 = 0 - 0: found by halving from rest, not reported at rest.
    const Overrides alpha = {{"damping.mass_proportional", "22"}};
    const ModesBlock coarse = blade_block({0.0, 5.0}, alpha);
    std::vector<double> fine;  // without rest: the crossing bracketed by rates where the gap has a value
    for (double w = 0.25; w <= 5.0; w += 0.25) fine.push_back(w);
    const ModesBlock refined = blade_block(fine, alpha);
    REQUIRE(coarse.critical.size() == 1);
    REQUIRE(refined.critical.size() == 1);
    const CriticalSpeed& c = coarse.critical[0];
    CHECK(c.harmonic == 1);
    CHECK(c.label.rfind("overdamped ", 0) == 0);  // the line began overdamped at rest
    CHECK(c.omega > 3.0);
    CHECK(c.omega < 4.0);
    CHECK(c.omega == Approx(refined.critical[0].omega).epsilon(1e-8));
    CHECK(nearest_frequency(c.omega, c.rad_s, alpha) < 1e-7);
}

TEST_CASE("a line of frequency 0 at rest that oscillates above the excitation line at once never meets it",
          "[modes][campbell]")
{
    // The first flap line at rates 0 and 5 of the blade, its row at rest given frequency 0 (a mode critically damped
    // there): halving from rest finds its mode above 1P and 2P at every rate tried (10.9 rad/s at Omega -> 0), so
    // the bracket shrinks onto rest, where a mode of frequency 0 meets no line: no critical speed, not one at about
    // 1e-10 rad/s.
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/helicopter_blade.toml");
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    const double theta = scene.motion.initial_theta();
    std::vector<SpinMode> rows;
    for (const SpinMode& r : campbell(*model, {0.0, 5.0}, scene.axial, theta))
        if (r.label == "flap 1") rows.push_back(r);
    REQUIRE(rows.size() == 2);
    REQUIRE(rows[1].mode.rad_s > 2.0 * 5.0);
    rows[0].mode.rad_s = 0.0;
    CHECK(critical_speeds(*model, rows, {1, 2}, scene.axial, theta).empty());
    rows[0].mode.rad_s = 1e-3;  // the same line a little above rest's 0: above both lines all along, no crossing
    CHECK(critical_speeds(*model, rows, {1, 2}, scene.axial, theta).empty());
}
