// A rotor's multi-blade (Coleman) coordinates (docs/model.md section 13.2) against what is known without them: on a
// hub that does not translate, each single blade's rotating-frame mode (its own model, alone) appears as a collective
// mode at its frequency, as forward and backward whirls at omega + Omega and |omega - Omega|, and with 4 blades as a
// differential mode; on an anisotropic moving hub, the transformed system's eigenvalues are the Floquet exponents of
// the periodic rotating-frame system (floquet(), which integrates it over a revolution) modulo i Omega; the
// transformed matrix is the same at every azimuth; and ground resonance (Coleman and Feingold 1958) appears where
// the backward lead-lag whirl meets the support's frequency, and goes with damping on both sides only; with one mode
// per blade, the roots of their characteristic equation, written out here.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <memory>
#include <string>
#include <vector>

#include "eigen_oracles.hpp"
#include "runs.hpp"
#include "soft_blade.hpp"

using namespace hubbeam;

namespace {

/// The soft blade (soft_blade.hpp), no gravity, with overrides, spun up by a prescribed drive or free under a torque.
Scene blade_with(const Overrides& o, bool torque = false)
{
    return parse_scene(test::soft_blade_scene(torque), "multiblade_test.toml", o);
}

/// A rotor soft in-plane (its first edge frequency 5.1 rad/s at rest) on a soft support, planar blades.
const char* ground_scene = R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 2.1e-6
youngs_modulus = 1e10

[hub]
radius = 0.3
inertia = 40.0
mass = 100.0

[support]
stiffness_x = 3000.0
stiffness_y = 3000.0

[rotor]
blades = 3

[motion]
kind = "torque"
tau0 = 0.0
duration = 1.0

[discretization]
method = "fem"
ny = 4
nx = 0

[output]
t_end = 1.0
dt_out = 0.1
)";

Scene ground_with(const Overrides& o)
{
    return parse_scene(ground_scene, "ground_test.toml", o);
}

std::complex<double> eigenvalue(const NaturalMode& m)
{
    return {m.growth, m.rad_s};
}

/// Checks that each single-blade mode appears in the rotor's fixed-frame modes as collective omega, FW omega + Omega,
/// BW |omega - Omega| (and differential omega with an even N), each once, to 1e-9 of the larger frequency.
void check_whirls(int blades, double omega)
{
    const Scene one = blade_with({}), rotor = blade_with({{"rotor.blades", std::to_string(blades)}});
    const auto single = make_scene_model(one), model = make_scene_model(rotor);
    const std::vector<NaturalMode> rotating = natural_modes(*single, steady_spin(*single, omega));
    const std::vector<NaturalMode> fixed = multiblade_modes(*model, steady_spin(*model, omega));
    REQUIRE(fixed.size() == blades * rotating.size());
    std::vector<bool> used(fixed.size(), false);
    for (const NaturalMode& m : rotating) {
        struct Expected {
            std::string kind;
            double rad_s;
        };
        std::vector<Expected> expected = {{"collective " + m.kind, m.rad_s},
                                          {"FW " + m.kind, m.rad_s + omega},
                                          {"BW " + m.kind, std::abs(m.rad_s - omega)}};
        if (blades % 2 == 0) expected.push_back({"differential " + m.kind, m.rad_s});
        for (const Expected& e : expected) {
            INFO(blades << " blades at " << omega << " rad/s: " << e.kind << " at " << e.rad_s << " rad/s");
            std::size_t found = fixed.size();
            for (std::size_t k = 0; k < fixed.size(); ++k)
                if (!used[k] && fixed[k].kind == e.kind &&
                    std::abs(fixed[k].rad_s - e.rad_s) <= 1e-9 * (m.rad_s + omega))
                    found = k;
            REQUIRE(found < fixed.size());
            used[found] = true;
            CHECK(fixed[found].growth == 0.0);
        }
    }
}

/// The rotor's fixed-frame modes at the spin omega; held: the hub held at its rate (a prescribed spin, Coleman's).
std::vector<NaturalMode> fixed_modes(const Model& model, double omega, bool held = false)
{
    SteadySpin steady = steady_spin(model, omega);
    steady.held = held;
    return multiblade_modes(model, steady);
}

/// The largest growth among fixed_modes, over the mode's |lambda| (round-off: 1e-11).
double worst_growth(const Model& model, double omega, bool held = false)
{
    double worst = -HUGE_VAL;
    for (const NaturalMode& m : fixed_modes(model, omega, held)) worst = std::max(worst, m.growth / m.undamped_rad_s);
    return worst;
}

}  // namespace

TEST_CASE("on a hub that does not translate each blade mode whirls at omega +- Omega in the fixed frame",
          "[multiblade]")
{
    // 30 rad/s is above the first edge frequency (about 25 rad/s spinning): its backward whirl, at Omega - omega,
    // turns with the rotor and is still BW.
    for (const double omega : {0.0, 12.0, 30.0}) {
        check_whirls(3, omega);
        check_whirls(4, omega);
    }
}

TEST_CASE("at rest a cyclic pair's two modes are its two whirls, which a slow spin splits", "[multiblade]")
{
    // At Omega = 0 each cyclic pair is one repeated eigenvalue: the modes are taken as its forward and backward
    // whirls, so that each is the mode the slightest spin gives (MAC 1 to it), its label kept.
    const auto model = make_scene_model(blade_with({{"rotor.blades", "3"}}));
    const std::vector<SpinMode> rows = campbell(*model, {0.0, 0.01});
    int whirls = 0;
    for (const SpinMode& r : rows) {
        if (r.omega == 0.0 || r.mode.kind.find("W ") != 1) continue;
        INFO(r.label << " at 0.01 rad/s: " << r.mode.kind << ", MAC " << r.mac);
        CHECK(r.mac > 0.999);
        CHECK(r.label.rfind(r.mode.kind + " ", 0) == 0);
        ++whirls;
    }
    const auto blade = make_scene_model(blade_with({}));
    CHECK(whirls == 2 * static_cast<int>(natural_modes(*blade, steady_spin(*blade, 0.01)).size()));
}

TEST_CASE("a free hub's angle moves with the collective modes alone", "[multiblade]")
{
    // Under a torque, N blades turn the hub as one blade with 1/N of its inertia (docs/model.md section 13): the
    // collective modes are that blade's; the cyclic and differential ones are the held blade's, whirling.
    const double omega = 12.0;
    const auto model = make_scene_model(blade_with({{"rotor.blades", "4"}}, true));
    const auto shared = make_scene_model(blade_with({{"hub.inertia", "10"}}, true));
    const auto held = make_scene_model(blade_with({}));
    const std::vector<NaturalMode> fixed = multiblade_modes(*model, steady_spin(*model, omega));
    const std::vector<NaturalMode> one = natural_modes(*shared, steady_spin(*shared, omega));
    const std::vector<NaturalMode> clamped = natural_modes(*held, steady_spin(*held, omega));
    std::vector<double> collective, whirls;
    for (const NaturalMode& m : fixed) (m.kind.rfind("collective ", 0) == 0 ? collective : whirls).push_back(m.rad_s);
    REQUIRE(collective.size() == one.size());
    for (std::size_t k = 0; k < one.size(); ++k) CHECK(collective[k] == Approx(one[k].rad_s).epsilon(1e-9));
    REQUIRE(whirls.size() == 3 * clamped.size());
    for (const NaturalMode& m : clamped)
        for (const double w : {m.rad_s + omega, std::abs(m.rad_s - omega), m.rad_s})
            CHECK(std::any_of(whirls.begin(), whirls.end(),
                              [&](double x) { return std::abs(x - w) <= 1e-9 * (m.rad_s + omega); }));
}

TEST_CASE("the multi-blade state matrix is the same at every azimuth", "[multiblade]")
{
    // On an anisotropic, damped support, out of the plane under a torque: the periodic rotating-frame matrices
    // transform to one matrix (Bir 2008), the transform's derivative terms included.
    const Scene s =
        ground_with({{"support.stiffness_y", "4500"}, {"support.damping_x", "80"}, {"support.damping_y", "40"}});
    const auto model = make_scene_model(s);
    const double omega = 7.0;
    const SteadySpin steady = steady_spin(*model, omega);
    const StateSpace at0 = multiblade_state_space(*model, steady, 0.0);
    for (const double psi : {0.3, 1.1, 2.5, 4.0}) {
        INFO("azimuth " << psi);
        const StateSpace at = multiblade_state_space(*model, steady, psi);
        CHECK((at.A - at0.A).cwiseAbs().maxCoeff() <= 1e-10 * at0.A.cwiseAbs().maxCoeff());
        CHECK((at.B - at0.B).cwiseAbs().maxCoeff() <= 1e-10 * at0.B.cwiseAbs().maxCoeff());
        CHECK((at.C - at0.C).cwiseAbs().maxCoeff() <= 1e-12 * at0.C.cwiseAbs().maxCoeff());
    }
    // And its eigenvalues are the modes' (the second-order form multiblade_modes solves).
    const test::GeneralEigen eig = test::general_eigen(at0.A, false);
    for (const NaturalMode& m : multiblade_modes(*model, steady)) {
        double nearest = HUGE_VAL;
        for (Eigen::Index k = 0; k < eig.values.size(); ++k)
            nearest = std::min(nearest, std::abs(eig.values[k] - eigenvalue(m)));
        CHECK(nearest <= 1e-8 * std::abs(eigenvalue(m)));
    }
    CHECK(at0.states[1] == "x_h");
    CHECK(std::find(at0.states.begin(), at0.states.end(), "B1_cos1") != at0.states.end());
    CHECK(at0.outputs.front() == "tip_uy_coll");
}

TEST_CASE("on an anisotropic moving hub the multi-blade eigenvalues are the Floquet exponents modulo i Omega",
          "[multiblade][floquet]")
{
    const Scene s =
        ground_with({{"support.stiffness_y", "4500"}, {"support.damping_x", "80"}, {"support.damping_y", "40"}});
    const auto model = make_scene_model(s);
    const double omega = 7.0;
    // Floquet holds the hub at its rate (docs/model.md section 10.1): so do these modes (held: theta is no
    // coordinate of them).
    const std::vector<NaturalMode> fixed = fixed_modes(*model, omega, true);
    const FloquetAnalysis f = floquet(*model, omega);
    REQUIRE(f.modes.size() >= 8);
    for (const FloquetMode& m : f.modes) {
        double nearest = HUGE_VAL;
        for (const NaturalMode& x : fixed)
            for (const std::complex<double> l : {eigenvalue(x), std::conj(eigenvalue(x))}) {
                const double shift = std::round((l.imag() - m.exponent.imag()) / omega);
                nearest = std::min(nearest, std::abs(l - m.exponent - std::complex<double>(0.0, shift * omega)));
            }
        INFO("Floquet exponent " << m.exponent << ", mode " << m.mode.kind << " at " << m.mode.rad_s << " rad/s");
        CHECK(nearest <= 1e-8 * std::abs(eigenvalue(m.mode)));
    }
}

namespace {

/// Where Omega - omega_lag(Omega) meets the support's frequency sqrt(k / (m_hub + N m L)) (the rotor rigid on it),
/// omega_lag the single blade's first edge frequency on a hub that does not move (its own model), by bisection.
double coalescence(double k, double total_mass)
{
    const Scene blade = parse_scene(R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 2.1e-6
youngs_modulus = 1e10
[hub]
radius = 0.3
inertia = 40.0
[motion]
kind = "spin-up"
omega0 = 10.0
duration = 1.0
[discretization]
method = "fem"
ny = 4
nx = 0
[output]
t_end = 1.0
dt_out = 0.1
)",
                                    "blade.toml");
    const auto model = make_scene_model(blade);
    const double support = std::sqrt(k / total_mass);
    const auto gap = [&](double omega) {
        return omega - natural_modes(*model, steady_spin(*model, omega)).front().rad_s - support;
    };
    double lo = 1.0, hi = 30.0;
    REQUIRE(gap(lo) < 0.0);
    REQUIRE(gap(hi) > 0.0);
    while (hi - lo > 1e-6) (gap(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
    return lo;
}

}  // namespace

TEST_CASE(
    "ground resonance: a band of spin where the backward lead-lag whirl meets the support, removed by damping "
    "on both sides only",
    "[multiblade]")
{
    // Coleman and Feingold (1958): three blades soft in-plane (edge 5.0 rad/s at rest, 7.0 at 10 rad/s) on an
    // undamped isotropic support of 3000 N/m under 100 kg of hub and 144 kg of blades (3.51 rad/s, the rotor rigid).
    const auto rotor = make_scene_model(ground_with({}));
    const double centre = coalescence(3000.0, 100.0 + 3 * 1600.0 * 0.005 * 6.0);
    double first = HUGE_VAL, last = -HUGE_VAL;
    for (double omega = 6.0; omega <= 16.0; omega += 0.25)
        if (worst_growth(*rotor, omega) > 1e-6)
            first = std::min(first, omega), last = std::max(last, omega);
        else
            CHECK(worst_growth(*rotor, omega) == 0.0);  // conservative outside: round-off read as none
    INFO("unstable from " << first << " to " << last << " rad/s, the whirl meets the support at " << centre);
    REQUIRE(first < centre);
    REQUIRE(last > centre);
    CHECK(std::abs(0.5 * (first + last) - centre) <= 0.05 * centre);
    CHECK(worst_growth(*rotor, centre) > 0.05);  // the coupled pair: growth a tenth of its frequency
    CHECK(last > first + 2.0);

    // Damping on one side alone leaves it unstable at the coalescence, and beyond the undamped band too: the support's
    // with undamped blades, the blades' (damping in the rotating frame) on an undamped support.
    const auto support_only =
        make_scene_model(ground_with({{"support.damping_x", "342"}, {"support.damping_y", "342"}}));
    const auto blades_only = make_scene_model(ground_with({{"damping.stiffness_proportional", "0.08"}}));
    for (const Model* model : {support_only.get(), blades_only.get()}) {
        CHECK(worst_growth(*model, centre) > 0.01);
        CHECK(worst_growth(*model, last + 1.0) > 1e-4);
    }
    // Both, each large enough (support zeta about 0.2, the blades' about 0.17 at their edge frequency): stable at every
    // rate.
    const auto both = make_scene_model(ground_with(
        {{"support.damping_x", "342"}, {"support.damping_y", "342"}, {"damping.stiffness_proportional", "0.05"}}));
    for (double omega = 0.0; omega <= 20.0; omega += 0.5) {
        INFO("Omega " << omega);
        CHECK(worst_growth(*both, omega) < 0.0);
    }
}

namespace {

/// Coleman and Feingold's characteristic equation, written out for one assumed mode phi per blade (docs/validation.md,
/// "Ground resonance in closed form"): with the hub's complex position z = x_h + i y_h, the cyclic pair's w = eta_c +
/// i eta_s, the modal mass M = int m phi^2, first moment S = int m phi and rotating frequency omega(Omega),
///   (M_T s^2 + c s + k) (M (s - i Omega)^2 + c_eta (s - i Omega) + M omega^2) - N/2 S^2 s^4 = 0,
/// M_T the hub's mass and the blades', c_eta = alpha M + beta K the blade's Rayleigh damping. Shares no code with
/// hubbeam: the mode by its textbook formula, the integrals by Simpson's rule.
struct ColemanRotor {
    double L = 6.0, m = 1600.0 * 0.005, EI = 1e10 * 2.1e-6, a = 0.3, k = 3000.0;
    double M_T = 100.0 + 3 * 1600.0 * 0.005 * 6.0;
    int N = 3;
    double M = 0.0, S = 0.0, K = 0.0, K_G = 0.0;  // K_G: the centrifugal stiffness over Omega^2

    ColemanRotor()
    {
        // The first root of 1 + cos b cosh b = 0, and the clamped-free mode's shape and derivatives.
        double b = 1.875;
        for (int i = 0; i < 50; ++i)
            b -= (1.0 + std::cos(b) * std::cosh(b)) / (std::cosh(b) * -std::sin(b) + std::cos(b) * std::sinh(b));
        const double g = -(std::cos(b) + std::cosh(b)) / (std::sin(b) + std::sinh(b)), B = b / L;
        const auto phi = [&](double x, int d) {
            const double z = B * x, f = std::pow(B, d);
            switch (d) {
            case 0: return std::cos(z) - std::cosh(z) + g * (std::sin(z) - std::sinh(z));
            case 1: return f * (-std::sin(z) - std::sinh(z) + g * (std::cos(z) - std::cosh(z)));
            default: return f * (-std::cos(z) - std::cosh(z) - g * (std::sin(z) + std::sinh(z)));
            }
        };
        const int n = 20000;  // Simpson's rule: its error h^4 L f''''/180 is 1e-14 of these integrals
        const double h = L / n;
        for (int i = 0; i <= n; ++i) {
            const double x = i * h, w = h / 3.0 * (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0);
            const double tension = m * (a * (L - x) + 0.5 * (L * L - x * x));  // over Omega^2
            M += w * m * phi(x, 0) * phi(x, 0);
            S += w * m * phi(x, 0);
            K += w * EI * phi(x, 2) * phi(x, 2);
            K_G += w * tension * phi(x, 1) * phi(x, 1);
        }
    }
    /// The blade's rotating frequency squared at the spin Omega.
    double omega2(double Omega) const { return (K + Omega * Omega * (K_G - M)) / M; }
    /// The four roots of the characteristic equation (the other four are their conjugates).
    std::vector<std::complex<double>> roots(double Omega, double c = 0.0, double alpha = 0.0, double beta = 0.0) const
    {
        using C = std::complex<double>;
        const C iO(0.0, Omega);
        const double c_eta = alpha * M + beta * K;
        const C a2 = M_T, a1 = c, a0 = k;  // the support
        const C b2 = M, b1 = c_eta - 2.0 * iO * M, b0 = M * iO * iO - c_eta * iO + M * omega2(Omega);  // the blades
        const C p[5] = {a0 * b0, a1 * b0 + a0 * b1, a2 * b0 + a1 * b1 + a0 * b2, a2 * b1 + a1 * b2,
                        a2 * b2 - 0.5 * N * S * S};
        Eigen::Matrix4cd companion = Eigen::Matrix4cd::Zero();
        for (int i = 0; i < 4; ++i) companion(i, 3) = -p[i] / p[4];
        for (int i = 1; i < 4; ++i) companion(i, i - 1) = 1.0;
        const Eigen::Vector4cd r = Eigen::ComplexEigenSolver<Eigen::Matrix4cd>(companion, false).eigenvalues();
        return {r.begin(), r.end()};
    }
    /// The largest growth over |lambda| among the roots (the rotor's whirls; its collective modes decay or are
    /// neutral).
    double worst_growth(double Omega, double c = 0.0, double beta = 0.0) const
    {
        double worst = -HUGE_VAL;
        for (const std::complex<double> r : roots(Omega, c, 0.0, beta)) worst = std::max(worst, r.real() / std::abs(r));
        return worst;
    }
};

/// The ground-resonance rotor with one assumed mode per blade (Coleman and Feingold's equivalent blade is its own:
/// a modal mass, first moment and rotating frequency), on the assembled source, with overrides.
std::unique_ptr<Model> one_mode_rotor(Overrides o = {})
{
    o.insert(o.end(), {{"discretization.method", "amm"}, {"discretization.ny", "1"}, {"model.source", "assembled"}});
    return make_scene_model(ground_with(o));
}

}  // namespace

TEST_CASE("a one-mode rotor's fixed-frame modes are the roots of Coleman and Feingold's characteristic equation",
          "[multiblade][ground_resonance]")
{
    const ColemanRotor closed;
    const double alpha = 0.3, beta = 0.05, c = 342.0;
    const auto undamped = one_mode_rotor();
    const auto damped = one_mode_rotor({{"support.damping_x", "342"},
                                        {"support.damping_y", "342"},
                                        {"damping.mass_proportional", "0.3"},
                                        {"damping.stiffness_proportional", "0.05"}});
    for (const bool with_damping : {false, true})
        for (const double Omega : {0.0, 2.0, 5.0, 9.6, 10.7, 12.4, 16.0}) {
            const Model& model = with_damping ? *damped : *undamped;
            const std::vector<NaturalMode> modes = fixed_modes(model, Omega, true);
            REQUIRE(modes.size() == 5);  // the collective mode, the hub's two whirls, the cyclic pair's two
            std::vector<std::complex<double>> expected;
            for (const std::complex<double> r : closed.roots(Omega, with_damping ? c : 0.0, with_damping ? alpha : 0.0,
                                                             with_damping ? beta : 0.0))
                expected.emplace_back(r.real(), std::abs(r.imag()));
            // The collective mode: the blade alone, M s^2 + c_eta s + M omega^2 = 0.
            const double decay = with_damping ? 0.5 * (alpha + beta * closed.K / closed.M) : 0.0;
            expected.emplace_back(-decay, std::sqrt(closed.omega2(Omega) - decay * decay));
            std::vector<bool> used(modes.size(), false);
            for (const std::complex<double> e : expected) {
                INFO((with_damping ? "damped" : "undamped") << " at " << Omega << " rad/s: root " << e);
                std::size_t nearest = modes.size();
                for (std::size_t j = 0; j < modes.size(); ++j)
                    if (!used[j] && (nearest == modes.size() ||
                                     std::abs(eigenvalue(modes[j]) - e) < std::abs(eigenvalue(modes[nearest]) - e)))
                        nearest = j;
                REQUIRE(nearest < modes.size());
                used[nearest] = true;
                INFO("hubbeam's " << modes[nearest].kind << ": " << eigenvalue(modes[nearest]));
                CHECK(std::abs(eigenvalue(modes[nearest]) - e) <= 1e-12 * std::abs(e));
            }
        }
}

TEST_CASE("a one-mode rotor's ground-resonance band and the damping that removes it, from the closed form",
          "[multiblade][ground_resonance]")
{
    const ColemanRotor closed;
    // The band's edges: where the undamped characteristic equation's roots leave the imaginary axis, by bisection on
    // the closed form.
    const auto unstable = [&](double Omega) { return closed.worst_growth(Omega) > 1e-9; };
    REQUIRE(unstable(10.7));
    const auto edge = [&](double stable, double inside) {
        while (std::abs(inside - stable) > 1e-12)
            (unstable(0.5 * (stable + inside)) ? inside : stable) = 0.5 * (stable + inside);
        return stable;
    };
    const double lower = edge(6.0, 10.7), upper = edge(16.0, 10.7);
    INFO("the closed form's band: " << lower << " to " << upper << " rad/s");
    const auto undamped = one_mode_rotor();
    for (const double d : {-1e-4, 1e-4}) {
        CHECK((worst_growth(*undamped, lower + d, true) > 0.0) == (d > 0.0));
        CHECK((worst_growth(*undamped, upper - d, true) > 0.0) == (d > 0.0));
    }
    // The blades' damping that makes the rotor stable at every spin on a support of 342 N s/m (Deutsch's criterion,
    // exactly): the least beta for which no root grows between 0 and 20 rad/s, by bisection on the closed form.
    const double c = 342.0;
    const auto worst_over_spin = [&](double beta, double* at = nullptr) {
        double worst = -HUGE_VAL;
        for (double Omega = 0.0; Omega <= 20.0; Omega += 0.01) {
            const double g = closed.worst_growth(Omega, c, beta);
            if (g > worst) worst = g, at ? *at = Omega : 0.0;
        }
        return worst;
    };
    double lo = 0.0, hi = 0.2;
    REQUIRE(worst_over_spin(lo) > 0.0);
    REQUIRE(worst_over_spin(hi) < 0.0);
    while (hi - lo > 1e-6 * hi) (worst_over_spin(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    double critical = 0.0;
    worst_over_spin(hi, &critical);
    INFO("stable at every spin from beta = " << hi << ", the last to go at " << critical << " rad/s");
    const auto with_beta = [&](double b) {
        return one_mode_rotor({{"support.damping_x", "342"},
                               {"support.damping_y", "342"},
                               {"damping.stiffness_proportional", std::to_string(b)}});
    };
    const auto below = with_beta(0.98 * hi), above = with_beta(1.02 * hi);
    CHECK(worst_growth(*below, critical, true) > 0.0);
    for (double Omega = critical - 1.0; Omega <= critical + 1.0; Omega += 0.05) {
        INFO("Omega " << Omega);
        CHECK(worst_growth(*above, Omega, true) < 0.0);
    }
}

TEST_CASE("multi-blade coordinates refuse a rotor they do not fit, naming why", "[multiblade]")
{
    const auto refusal = [](const Overrides& o) { return multiblade_refusal(*make_scene_model(blade_with(o))); };
    CHECK(refusal({}).find("3 blades or more") != std::string::npos);
    CHECK(refusal({{"rotor.blades", "2"}}).find("3 blades or more") != std::string::npos);
    CHECK(refusal({{"rotor.blades", "3"}, {"rotor.tip_masses", "0, 1, 0"}}).find("blade 2 differs") !=
          std::string::npos);
    CHECK(refusal({{"rotor.blades", "3"}, {"rotor.pitch_offsets", "0, 0, 0.01"}}).find("blade 3 differs") !=
          std::string::npos);
    CHECK(refusal({{"rotor.blades", "3"}, {"gravity.g", "9.81"}}).find("weight in the plane") != std::string::npos);
    CHECK(refusal({{"rotor.blades", "3"}, {"rotor.tip_masses", "2, 2, 2"}}).empty());
    // The library refuses what does not fit; campbell's fixed frame takes the blades' frames there.
    const auto differ = make_scene_model(blade_with({{"rotor.blades", "3"}, {"rotor.tip_masses", "0, 1, 0"}}));
    CHECK_THROWS_WITH(multiblade_modes(*differ, steady_spin(*differ, 3.0)), Catch::Contains("blade 2 differs"));
    const std::vector<SpinMode> rows = campbell(*differ, {3.0});
    CHECK(std::none_of(rows.begin(), rows.end(), [](const SpinMode& r) { return r.mode.kind.find("FW") == 0; }));
    // A moving hub whose blades differ keeps no steady spin: its linearization is periodic (Floquet's).
    const auto uneven = make_scene_model(ground_with({{"rotor.tip_masses", "0, 1, 0"}}));
    CHECK_THROWS_WITH(steady_spin(*uneven, 5.0), Catch::Contains("periodic"));
    const auto even = make_scene_model(ground_with({}));
    const SteadySpin s = steady_spin(*even, 5.0);
    CHECK(s.q[1] == 0.0);
    CHECK(s.q[2] == 0.0);
}

namespace {

/// The hub's largest excursion sqrt(x_h^2 + y_h^2) over the rows with from <= t <= to.
double hub_excursion(std::map<std::string, std::vector<double>>& rows, double from, double to)
{
    double largest = 0.0;
    for (std::size_t i = 0; i < rows["t"].size(); ++i)
        if (rows["t"][i] >= from && rows["t"][i] <= to)
            largest = std::max(largest, std::hypot(rows["hub_x"][i], rows["hub_y"][i]));
    return largest;
}

}  // namespace

TEST_CASE("cases/ground_resonance.toml whirls up in the band and its damped twin stays bounded", "[multiblade]")
{
    // The runs (the integrator, an independent path from the modes): spun up by the torque to 11.2 rad/s, the rotor
    // enters the band at t = 30 s (about 9.6 rad/s).
    auto free =
        hubbeam::test::run_columns(load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/ground_resonance.toml"));
    const double before = hub_excursion(free, 22.0, 28.0), after = hub_excursion(free, 38.0, 40.0);
    INFO("hub whirl " << before << " m before the band, " << after << " m at its middle");
    CHECK(after > 20.0 * before);
    auto damped =
        hubbeam::test::run_columns(load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/ground_resonance_damped.toml"));
    // The imbalance's own whirl, m_t (a + L) / M = 0.01 x 6.3 / 244 = 0.26 mm well above the support's frequency.
    const double forced = 0.01 * 6.3 / (100.0 + 3 * 48.0 + 0.01);
    CHECK(hub_excursion(damped, 30.0, 40.0) == Approx(forced).epsilon(0.35));
    CHECK(hub_excursion(damped, 38.0, 40.0) <= hub_excursion(damped, 22.0, 28.0));
}
