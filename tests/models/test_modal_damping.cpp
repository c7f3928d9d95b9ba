// Modal damping of a blade's own modes at rest (docs/model.md section 11.5) against what it must be, computed here: a
// free vibration started in a named mode decays by exp(-2 pi n zeta / sqrt(1 - zeta^2)) over n cycles and an unnamed
// one not at all; the eigenvalues at rest give each named mode its ratio and keep every undamped frequency; Rayleigh's
// closed form adds to it; the exact Jacobian's dQ/dqd is the forces' central differences; each blade of a rotor is
// damped as the blade alone; the keys refuse what they must, naming file and key.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include "dynamics/integrate.hpp"
#include "eigen_oracles.hpp"
#include "runs.hpp"
#include "terms.hpp"
#include "dynamics/stepper.hpp"
#include "models/modal_damping.hpp"

using namespace hubbeam;

namespace {

/// A blade held at rest (a prescribed hub: no hub coordinate), in the plane (FEM, Nx = 4, Ny = 4: a built-in
/// variant, axial modes beside the bending ones) or out of it (flap and twist fields, pitched and pre-twisted so that
/// flap and edge couple, on the hand-assembled path); DAMPING: the [damping] table's lines.
const char* planar_text = R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 4e-5
youngs_modulus = 1e10

[motion]
kind = "held"
angle = 0.0

[damping]
DAMPING

[discretization]
method = "fem"
ny = 4
nx = 4

[output]
t_end = 1.0
)";

const char* out_of_plane_text = R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 4e-5
second_moment_flap = 1e-5
youngs_modulus = 1e10
shear_modulus = 4e9
torsion_constant = 2e-6
pitch = 0.1
twist = 0.3

[motion]
kind = "held"
angle = 0.0

[damping]
DAMPING

[discretization]
method = "fem"
ny = 4
nx = 0
nz = 4
nt = 2

[model]
source = "assembled"

[output]
t_end = 1.0
)";

Scene scene(const char* text, const std::string& damping, const Overrides& o = {})
{
    std::string t = text;
    t.replace(t.find("DAMPING"), 7, damping);
    return parse_scene(t, "modal_test.toml", o);
}

/// The named mode's ratio in modes sorted by frequency (natural_modes): flap[k] to the (k+1)-th flap mode, edge[k]
/// to the (k+1)-th edge or in-plane bending mode, 0 for every other.
std::vector<double> expected_ratios(const std::vector<NaturalMode>& modes, const ModalDamping& d)
{
    std::vector<double> out;
    std::size_t flap = 0, edge = 0;
    for (const NaturalMode& m : modes) {
        double z = 0.0;
        if (m.kind == "flap" && flap++ < d.flap.size()) z = d.flap[flap - 1];
        if ((m.kind == "edge" || m.kind == "bending") && edge++ < d.edge.size()) z = d.edge[edge - 1];
        out.push_back(z);
    }
    return out;
}

/// modes by undamped frequency, those of one frequency (to 1e-8: a round blade's flap and edge pairs) by kind.
std::vector<NaturalMode> by_frequency_and_kind(std::vector<NaturalMode> modes)
{
    std::stable_sort(modes.begin(), modes.end(), [](const NaturalMode& a, const NaturalMode& b) {
        const double fa = a.undamped_rad_s, fb = b.undamped_rad_s;
        return std::abs(fa - fb) <= 1e-8 * fb ? a.kind < b.kind : fa < fb;
    });
    return modes;
}

/// M at rest and K = -dQ/dq at rest by central differences of the forces, as the test's own oracle.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> mass_and_stiffness(const Model& model)
{
    const int n = model.nq();
    const HubInput rest;
    std::vector<double> q(static_cast<std::size_t>(n), 0.0), qd(q), up(q), down(q);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(n, n);
    model.mass(rest, q.data(), M.data());
    Eigen::MatrixXd K(n, n);
    const double h = 1e-6;
    for (int j = 0; j < n; ++j) {
        q[static_cast<std::size_t>(j)] = h;
        model.forces(rest, q.data(), qd.data(), up.data());
        q[static_cast<std::size_t>(j)] = -h;
        model.forces(rest, q.data(), qd.data(), down.data());
        q[static_cast<std::size_t>(j)] = 0.0;
        for (int i = 0; i < n; ++i)
            K(i, j) = -(up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2 * h);
    }
    return {M, 0.5 * (K + K.transpose())};
}

}  // namespace

TEST_CASE("at rest each named mode has its damping ratio and its undamped frequency, every other mode none",
          "[modal_damping]")
{
    // The out-of-plane blade pitched and pre-twisted (flap and edge coupled), and uniform, straight and round
    // (each flap mode at the frequency of an edge mode: the eigen solver's pair is any mix of the two until split).
    const Overrides round = {{"beam.second_moment_flap", "4e-5"}, {"beam.pitch", "0"}, {"beam.twist", "0"}};
    const std::tuple<const char*, std::string, Overrides> cases[] = {
        {planar_text, "edge_ratios = [0.02, 0.05]", {}},
        {out_of_plane_text, "flap_ratios = [0.01, 0.03]\nedge_ratios = [0.04]", {}},
        {out_of_plane_text, "flap_ratios = [0.01, 0.03]\nedge_ratios = [0.04]", round},
    };
    for (const auto& [text, damping, o] : cases) {
        const Scene damped = scene(text, damping, o), undamped = scene(text, "", o);
        const auto model = make_scene_model(damped), reference = make_scene_model(undamped);
        const std::vector<NaturalMode> modes = by_frequency_and_kind(natural_modes(*model, steady_spin(*model, 0.0)));
        const std::vector<NaturalMode> free =
            by_frequency_and_kind(natural_modes(*reference, steady_spin(*reference, 0.0)));
        REQUIRE(modes.size() == free.size());
        const std::vector<double> zeta = expected_ratios(free, damped.modal_damping);
        int named = 0;
        for (std::size_t i = 0; i < modes.size(); ++i) {
            INFO(damping << ": mode " << i + 1 << " (" << free[i].kind << ") at " << free[i].rad_s << " rad/s");
            CHECK(modes[i].kind == free[i].kind);
            // |lambda| of the first-order system's eigen solver, whose spectrum spans four decades (the axial modes):
            // to 3e-10 of it, damped or not.
            CHECK(modes[i].undamped_rad_s == Approx(free[i].rad_s).epsilon(1e-9));
            CHECK(modes[i].damping_ratio == Approx(zeta[i]).margin(1e-10));
            named += zeta[i] > 0.0;
        }
        CHECK(named == static_cast<int>(damped.modal_damping.flap.size() + damped.modal_damping.edge.size()));
    }
}

TEST_CASE("a free vibration started in a named mode decays by exp(-2 pi n zeta / sqrt(1 - zeta^2)) over n cycles",
          "[modal_damping][run]")
{
    // The blade's own modes of (K, M) at rest, mass-normalised, from the model without the damping (the oracle's
    // eigenproblem); each run starts in one of them at rest, and its modal amplitude phi^T M q is sampled at whole
    // damped periods, where the free decay e^(-zeta w t) (cos w_d t + zeta/sqrt(1 - zeta^2) sin w_d t) is its envelope.
    const Scene damped = scene(planar_text, "edge_ratios = [0.05, 0.02]");
    const auto reference = make_scene_model(scene(planar_text, ""));
    const auto model = make_scene_model(damped);
    const auto [M, K] = mass_and_stiffness(*reference);
    const test::SymmetricEigen eig = test::generalized_eigen(K, M);
    const int n = model->nq();
    // The bending modes by increasing frequency (the axial ones of FEM's Nx = 4 are far above, undamped).
    std::vector<int> bending;
    const int axial = model->coordinates().first(FieldKind::axial);
    for (int k = 0; k < n; ++k)
        if (eig.vectors.col(k).segment(axial, 4).norm() < 1e-8) bending.push_back(k);
    REQUIRE(bending.size() == 4);
    const double ratios[] = {0.05, 0.02, 0.0};  // the third bending mode is not named
    for (int m = 0; m < 3; ++m) {
        const Eigen::VectorXd phi = eig.vectors.col(bending[static_cast<std::size_t>(m)]);
        const double w = std::sqrt(eig.values[bending[static_cast<std::size_t>(m)]]), zeta = ratios[m];
        const double period = 2 * std::numbers::pi / (w * std::sqrt(1 - zeta * zeta));
        FirstOrderSystem system(*model, damped.motion);
        REQUIRE(system.size() == 2 * n);
        std::vector<double> y(static_cast<std::size_t>(2 * n), 0.0);
        for (int i = 0; i < n; ++i) y[static_cast<std::size_t>(i)] = phi[i];
        double t = 0.0;
        const auto stepper = make_stepper(system, "rk8pd", t, y.data(), 1e-5, 1e-14, 1e-12);
        for (int cycle = 1; cycle <= 4; ++cycle) {
            const double target = cycle * period;
            while (t < target) REQUIRE(stepper->step(t, target, y.data(), INFINITY) == StepStatus::success);
            const Eigen::Map<const Eigen::VectorXd> q(y.data(), n);
            const double amplitude = phi.dot(M * q), decay = std::exp(-2 * std::numbers::pi * cycle * zeta /
                                                                      std::sqrt(1 - zeta * zeta));
            INFO("bending mode " << m + 1 << " at " << w << " rad/s, cycle " << cycle);
            CHECK(amplitude == Approx(decay).epsilon(1e-10));  // 2e-13 at rk8pd, rtol 1e-12
        }
    }
}

TEST_CASE("modal damping adds to Rayleigh damping: zeta_k + alpha/(2 omega_k) + beta omega_k/2 at rest",
          "[modal_damping]")
{
    const std::string rayleigh = "mass_proportional = 0.15\nstiffness_proportional = 4e-4\n";
    const Scene both = scene(planar_text, rayleigh + "edge_ratios = [0.03]", {{"model.source", "assembled"}});
    const Scene alone = scene(planar_text, "", {{"model.source", "assembled"}});
    const auto model = make_scene_model(both), reference = make_scene_model(alone);
    const std::vector<NaturalMode> modes = natural_modes(*model, steady_spin(*model, 0.0));
    const std::vector<NaturalMode> free = natural_modes(*reference, steady_spin(*reference, 0.0));
    std::vector<double> w, zeta;  // the bending modes': undamped frequency, ratio
    for (const NaturalMode& m : free)
        if (m.kind == "bending") w.push_back(m.rad_s);
    for (const NaturalMode& m : modes)
        if (m.kind == "bending") zeta.push_back(m.damping_ratio);
    REQUIRE(w.size() == 4);
    REQUIRE(zeta.size() == 4);
    for (std::size_t k = 0; k < 2; ++k) {
        const double rayleigh_ratio = 0.15 / (2 * w[k]) + 4e-4 * w[k] / 2;
        INFO("bending mode " << k + 1 << " at " << w[k] << " rad/s");
        CHECK(zeta[k] == Approx((k == 0 ? 0.03 : 0.0) + rayleigh_ratio).epsilon(1e-9));
    }
}

TEST_CASE("the exact Jacobian's dQ/dqd includes the modal damping, as the forces' differences do", "[modal_damping]")
{
    const Scene s = scene(planar_text, "edge_ratios = [0.05, 0.1]");
    const auto model = make_scene_model(s), reference = make_scene_model(scene(planar_text, ""));
    REQUIRE(model->jacobian() != nullptr);
    const int n = model->nq();
    HubInput u;
    u.theta_dot = 3.0;  // spinning: the Coriolis terms are in dQ/dqd too
    u.theta_ddot = 0.4;
    std::vector<double> q(static_cast<std::size_t>(n)), qd(q);
    for (int i = 0; i < n; ++i) {
        q[static_cast<std::size_t>(i)] = 1e-3 * std::sin(1.3 * i + 0.2);
        qd[static_cast<std::size_t>(i)] = 2e-2 * std::cos(0.7 * i + 0.5);
    }
    using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMatrix dq(n, n), dqd(n, n), du(n, 3), plain_dqd(n, n);
    model->jacobian()->force_derivatives(u, q.data(), qd.data(), dq.data(), dqd.data(), du.data());
    reference->jacobian()->force_derivatives(u, q.data(), qd.data(), dq.data(), plain_dqd.data(), du.data());
    Eigen::MatrixXd differences(n, n);
    std::vector<double> up(q.size()), down(q.size());
    for (int j = 0; j < n; ++j) {
        const double h = 1e-4;
        std::vector<double> r = qd;
        r[static_cast<std::size_t>(j)] += h;
        model->forces(u, q.data(), r.data(), up.data());
        r[static_cast<std::size_t>(j)] -= 2 * h;
        model->forces(u, q.data(), r.data(), down.data());
        for (int i = 0; i < n; ++i)
            differences(i, j) = (up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2 * h);
    }
    INFO("dQ/dqd =\n" << dqd << "\ndifferences =\n" << differences);
    CHECK((Eigen::MatrixXd(dqd) - differences).norm() < 1e-7 * differences.norm());
    // What the damping adds is no small part of it.
    CHECK((Eigen::MatrixXd(dqd - plain_dqd)).norm() > 0.1 * differences.norm());
}

TEST_CASE("each blade of a rotor is damped as the blade alone at its own pitch", "[modal_damping][rotor]")
{
    const std::string damping = "flap_ratios = [0.01, 0.03]\nedge_ratios = [0.04]";
    const double offsets[] = {0.0, 0.2, -0.15};
    const Scene rotor = scene(out_of_plane_text, damping + "\n[rotor]\nblades = 3\npitch_offsets = [0.0, 0.2, -0.15]");
    const auto model = make_scene_model(rotor);
    std::vector<NaturalMode> all = natural_modes(*model, steady_spin(*model, 0.0));
    std::vector<std::pair<double, double>> blades;  // (undamped frequency, ratio) of each blade alone
    for (double offset : offsets) {
        const Scene one = scene(out_of_plane_text, damping, {{"beam.pitch", std::to_string(0.1 + offset)}});
        const auto blade = make_scene_model(one);
        const std::vector<NaturalMode> modes = natural_modes(*blade, steady_spin(*blade, 0.0));
        const std::vector<double> zeta = expected_ratios(modes, one.modal_damping);
        for (std::size_t i = 0; i < modes.size(); ++i) {
            CHECK(modes[i].damping_ratio == Approx(zeta[i]).margin(1e-10));
            blades.emplace_back(modes[i].undamped_rad_s, modes[i].damping_ratio);
        }
    }
    std::sort(blades.begin(), blades.end());
    REQUIRE(all.size() == blades.size());
    std::sort(all.begin(), all.end(), [](const NaturalMode& a, const NaturalMode& b) {
        return a.undamped_rad_s < b.undamped_rad_s;
    });
    for (std::size_t i = 0; i < all.size(); ++i) {
        INFO("rotor mode " << i + 1 << " at " << all[i].undamped_rad_s << " rad/s");
        CHECK(all[i].undamped_rad_s == Approx(blades[i].first).epsilon(1e-9));
        CHECK(all[i].damping_ratio == Approx(blades[i].second).margin(1e-9));
    }
}

TEST_CASE("modal damping's keys refuse what the blade cannot take, naming the file and the key", "[modal_damping]")
{
    const auto scene_refused = [](const char* text, const std::string& damping, const Overrides& o,
                                  const std::string& words) {
        try {
            scene(text, damping, o);
        } catch (const SceneError& e) {
            INFO(e.what());
            const std::string what = e.what();
            CHECK(what.find("modal_test.toml") != std::string::npos);
            CHECK(what.find(words) != std::string::npos);
            return true;
        }
        return false;
    };
    CHECK(scene_refused(planar_text, "edge_ratios = [0.01, -0.02]", {},
                        "damping.edge_ratios: expected an array of numbers >= 0"));
    CHECK(scene_refused(out_of_plane_text, "flap_ratios = [-1]", {}, "damping.flap_ratios"));
    CHECK(scene_refused(planar_text, "edge_ratios = [0.01]", {{"output.sensitivities", "E"}},
                        "output.sensitivities"));
    CHECK(scene_refused(planar_text, "edge_ratios = [\"a\"]", {}, "damping.edge_ratios"));
    const auto model_refused = [](const char* text, const std::string& damping, const std::string& words) {
        const Scene s = scene(text, damping);
        try {
            make_scene_model(s);
        } catch (const std::invalid_argument& e) {
            INFO(e.what());
            const std::string what = e.what();
            CHECK(what.find("modal_test.toml: ") == 0);
            CHECK(what.find(words) != std::string::npos);
            return true;
        }
        return false;
    };
    // FEM's Ny = 4 has four in-plane bending modes; a planar blade no flapwise one; ratios of 0 are counted too.
    CHECK(model_refused(planar_text, "edge_ratios = [0, 0, 0, 0, 0.01]",
                        "damping.edge_ratios: expected at most 4 ratios (the blade's in-plane bending modes at rest)"));
    CHECK(model_refused(planar_text, "flap_ratios = [0]",
                        "damping.flap_ratios: expected at most 0 ratios (the blade's flapwise modes at rest: it has "
                        "none), got 1"));
    CHECK(model_refused(out_of_plane_text, "flap_ratios = [0.1, 0.1, 0.1, 0.1, 0.1]",
                        "damping.flap_ratios: expected at most 4 ratios"));
    CHECK_NOTHROW(make_scene_model(scene(planar_text, "edge_ratios = [0, 0, 0, 0.01]")));
}

TEST_CASE("with modal damping alone, E + dissipated - work stays constant, and the run's monitor checks it",
          "[modal_damping][run]")
{
    // docs/model.md section 11.6: d/dt (T + U) = -2 D + tau theta_dot, D = 1/2 qd^T C qd: the paper's torque pulse on
    // a free hub, its first two bending modes damped, no Rayleigh damping (a variant without _damped).
    Scene s = test::paper_scene(Method::amm, 0, 4, test::torque(1.0));
    s.modal_damping.edge = {0.05, 0.02};
    s.output.t_end = 20.0;
    REQUIRE(!dissipates(s.key()));
    const test::Collected r = test::completed_run(s);
    double largest = 0.0, vibration = 0.0;
    for (const Row& row : r.rows) {
        largest = std::max(largest, row.kinetic + row.potential);
        vibration = std::max(vibration, row.potential);
    }
    for (std::size_t i = 0; i < r.rows.size(); ++i) {
        const Row& row = r.rows[i];
        CHECK(std::abs(row.kinetic + row.potential + row.extras.dissipated - row.extras.work) < 1e-7 * largest);
        if (i > 0) CHECK(row.extras.dissipated >= r.rows[i - 1].extras.dissipated);  // D >= 0
    }
    CHECK(r.rows.back().extras.dissipated > 0.1 * vibration);
    CHECK(r.summary.energy_balance);
}

TEST_CASE("a blade's own modes are those without its weight", "[modal_damping]")
{
    // Gravity along the spin axis of a coned blade stiffens or softens it through the foreshortening (docs/model.md
    // section 12); the modes the ratios name are the blade's structure's alone.
    const Overrides weighed = {{"beam.precone", "0.2"}, {"gravity.g", "9.81"}, {"gravity.direction", "axis"}};
    const Overrides weightless = {{"beam.precone", "0.2"}};
    const std::string damping = "flap_ratios = [0.01, 0.03]\nedge_ratios = [0.04]";
    const auto with = make_scene_model(scene(out_of_plane_text, damping, weighed));
    const auto without = make_scene_model(scene(out_of_plane_text, damping, weightless));
    const Scene s = scene(out_of_plane_text, damping, weighed);
    const auto plain = make_scene_model(scene(out_of_plane_text, "", weighed));
    const Eigen::MatrixXd C = added_damping(*with), expected = added_damping(*without);
    const Eigen::MatrixXd weighed_modes = modal_damping_matrix(*plain, s.modal_damping, s.path);
    CHECK((C - expected).norm() < 1e-12 * expected.norm());
    // What the weight would change: 3.6e-4 of the matrix here, so that the check above sees it left in.
    CHECK((weighed_modes - expected).norm() > 1e-5 * expected.norm());
}
