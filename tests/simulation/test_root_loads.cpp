// A blade's root loads by force summation (docs/model.md section 13.2) against closed forms of a rigid or stiff blade
// (steady spin, the weight held horizontal or along the spin axis, a spin-up), against the curvature's moment as the
// mesh refines, blade by blade against single blades at their azimuths, and against the hub's momentum balance on a
// moving support (the model's own equation for x_h, y_h: no code of the force summation in it).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/fields.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>

#include "csv_file.hpp"
#include "models/root_loads.hpp"
#include "runs.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;
using hubbeam::test::run_columns;

namespace {

/// A short stiff blade (first bending near 60 Hz), hub radius a, a tip mass, on the assembled path (no compiler).
const char* stiff_blade = R"(
[beam]
length = 2.0
density = 2700.0
area = 1e-3
second_moment = 2e-7
second_moment_flap = 1e-7
youngs_modulus = 7e10

[hub]
radius = 0.4
inertia = 5.0

MOTION
[tip]
mass = 0.6
inertia = 0.01

[discretization]
method = "fem"
ny = 4
nx = 2

[model]
source = "assembled"

[solver]
rtol = 1e-11
atol = 1e-13
error_check = "off"

[output]
t_end = 1.0
dt_out = 0.05
loads = "root"
)";

/// The blade with overrides o, its [motion] the table text motion (held horizontal by default).
Scene blade(const Overrides& o, const std::string& motion = "[motion]\nkind = \"held\"\nangle = 0.0\n")
{
    std::string text = stiff_blade;
    text.replace(text.find("MOTION"), 6, motion);
    return parse_scene(text, "root_loads_test.toml", o);
}

double peak(const std::vector<double>& v)
{
    double p = 0.0;
    for (double x : v) p = std::max(p, std::abs(x));
    return p;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b)
{
    REQUIRE(a.size() == b.size());
    double d = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

/// The model's accelerations at (u, q, qd), solved here from M and Q (not by the run's solve).
std::vector<double> accelerations(const Model& model, const HubInput& u, const std::vector<double>& q,
                                  const std::vector<double>& qd)
{
    const int n = model.nq();
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd Q(n);
    std::vector<double> m(static_cast<std::size_t>(n * n));
    model.mass(u, q.data(), m.data());
    model.forces(u, q.data(), qd.data(), Q.data());
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) M(i, j) = m[static_cast<std::size_t>(i * n + j)];
    const Eigen::VectorXd qdd = M.ldlt().solve(Q);
    return {qdd.data(), qdd.data() + n};
}

/// Each blade's loads of scene's model at (u, q, qd).
std::vector<RootLoads> loads_of(const Scene& scene, const Model& model, const HubInput& u, const std::vector<double>& q,
                                const std::vector<double>& qd)
{
    std::vector<BladeLoads> blades;
    for (int b = 0; b < scene.rotor.blades; ++b) blades.emplace_back(scene.key(), scene.rotor.blade(scene.parameters, b));
    const std::vector<double> qdd = accelerations(model, u, q, qd);
    return blade_root_loads(model, blades, u, q.data(), qd.data(), qdd.data());
}

double mass_per_length(const Parameters& p) { return p.rho * p.S; }

}  // namespace

TEST_CASE("root loads at a steady spin: the centrifugal tension, no shear or moment", "[root_loads]")
{
    // A stiff beam (E 1000 times aluminium's): its stretch rho Omega^2 L^2 / (3 E) is below 1e-8 of L, which bounds
    // the tension's departure from the rigid value m Omega^2 (a L + L^2/2) + m_t Omega^2 (a + L).
    const Scene s = blade({{"beam.youngs_modulus", "7e13"}, {"tip.inertia", "0"}});
    const std::unique_ptr<Model> model = make_scene_model(s);
    const double omega = 12.0;
    const SteadySpin steady = steady_spin(*model, omega);
    const RootLoads l = loads_of(s, *model, steady.u, steady.q, steady.qd).at(0);
    const Parameters& p = s.parameters;
    const double m = mass_per_length(p), w2 = omega * omega;
    const double tension = m * w2 * (p.a * p.L + p.L * p.L / 2.0) + p.m_tip * w2 * (p.a + p.L);
    CHECK(l.axial_force == Approx(tension).epsilon(1e-7));
    CHECK(std::abs(l.shear_edge) < 1e-10 * tension);
    CHECK(std::abs(l.shear_flap) < 1e-10 * tension);
    CHECK(std::abs(l.edge_moment) < 1e-10 * tension * p.L);
    CHECK(std::abs(l.flap_moment) < 1e-10 * tension * p.L);
}

TEST_CASE("root loads of a blade held horizontal under its weight: m g L and m g L^2/2, the curvature's moment "
          "converging to it",
          "[root_loads]")
{
    // Force summation: the weight's resultant exactly, its moment to the sag's order (E 100 times aluminium's: sag / L
    // about 2e-5, so the arm's change u_x2 is 4e-10 of L). EI u''(0) of FEM's cubics misses the quadratic moment by
    // about q h^2 / 12.
    double previous_gap = 0.0;
    for (const int ny : {2, 4, 8, 16}) {
        const Scene s = blade({{"gravity.g", "9.81"},
                               {"beam.youngs_modulus", "7e12"},
                               {"tip.inertia", "0"},
                               {"discretization.ny", std::to_string(ny)},
                               {"discretization.nx", "0"}});
        const std::unique_ptr<Model> model = make_scene_model(s);
        const SteadySpin held = held_equilibrium(*model, 0.0);
        const RootLoads l = loads_of(s, *model, held.u, held.q, held.qd).at(0);
        const Parameters& p = s.parameters;
        const double m = mass_per_length(p), g = p.g;
        const double shear = m * g * p.L + p.m_tip * g, moment = m * g * p.L * p.L / 2.0 + p.m_tip * g * p.L;
        INFO("ny = " << ny);
        CHECK(l.shear_edge == Approx(-shear).epsilon(1e-10));  // the blade pulls the hub down (a sum of 100 terms)
        CHECK(l.edge_moment == Approx(-moment).epsilon(1e-7));
        CHECK(std::abs(l.axial_force) < 1e-9 * shear);
        const BeamFields fields(s.key(), p);
        const double curvature_moment =
            fields.bending_moment(held.q.data() + model->coordinates().first(FieldKind::inplane), 0.0);
        const double gap = std::abs(curvature_moment - l.edge_moment);
        if (ny > 2) CHECK(gap < 0.3 * previous_gap);  // h^2: a quarter per halving
        previous_gap = gap;
    }
}

TEST_CASE("root loads of a stiff blade spun up: edgewise shear and moment from theta_ddot, tension from theta_dot^2",
          "[root_loads]")
{
    // Paper eq. 58 to Omega0 = 3 rad/s in T_s = 1 s; the blade 1000 times stiffer than aluminium moves as a rigid one
    // (its deflection relative to L about 1e-6, no axial coordinates), with J_t turned with the hub and, with twist
    // coordinates, the sections' rotary inertia j_n = rho I about the spin axis (pitch 0: the twist stays 0). The
    // drive's jerk rings the blade at its own 2000 rad/s, whose inertial load is of the order of the quasi-static
    // elastic one: 1e-5 of the peak shear, within the margins (J_t and j_n are 1e-3 of the moment, well outside).
    const Scene s = blade({{"beam.youngs_modulus", "7e13"},
                           {"discretization.nx", "0"},
                           {"discretization.nt", "2"},
                           {"beam.shear_modulus", "2.7e10"},
                           {"beam.torsion_constant", "1e-7"}});
    Scene spun = s;
    spun.motion = Motion{Motion::Kind::spin_up, 3.0, 1.0, 0.0, 10.0};
    const auto c = run_columns(spun);
    const Parameters& p = s.parameters;
    const double m = mass_per_length(p), L = p.L, a = p.a;
    const double first = m * (a * L + L * L / 2.0) + p.m_tip * (a + L);
    const double second = m * (a * L * L / 2.0 + L * L * L / 3.0) + p.m_tip * L * (a + L) + p.J_tip + p.rho * p.I * L;
    const double Ts = 1.0, W = 3.0, two_pi = 2.0 * std::numbers::pi;
    const std::vector<double>& t = c.at("t");
    double largest = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double tt = std::min(t[i], Ts);
        const double rate = t[i] < Ts ? W * (tt / Ts - std::sin(two_pi * tt / Ts) / two_pi) : W;
        const double accel = t[i] < Ts ? W / Ts * (1.0 - std::cos(two_pi * tt / Ts)) : 0.0;
        INFO("t = " << t[i]);
        CHECK(c.at("root_shear_edge")[i] == Approx(-first * accel).margin(1e-4 * first * W));
        CHECK(c.at("root_edge_moment")[i] == Approx(-second * accel).margin(1e-4 * second * W));
        CHECK(c.at("root_axial_force")[i] == Approx(first * rate * rate).margin(1e-4 * first * W * W));
        CHECK(std::abs(c.at("root_shear_flap")[i]) < 1e-9 * first * W * W);
        largest = std::max(largest, std::abs(c.at("root_shear_edge")[i]));
    }
    CHECK(largest == Approx(2.0 * first * W / Ts).epsilon(0.01));  // the peak of theta_ddot, 2 Omega0 / T_s
}

TEST_CASE("root loads out of the plane: the weight along the spin axis on a coned blade, flap shear and moment",
          "[root_loads]")
{
    // Held, gravity along -k, precone beta_c: the weight -(m g L + m_t g) k has the components -W sin beta_c along e1
    // and -W cos beta_c along e3; its moment about the root bends the blade down: -(m g L^2/2 + m_t g L) cos beta_c,
    // to the sag's order (E 1000 times aluminium's: the sag u_z is 4e-6 of L, its arm u_z tan beta_c).
    const double cone = 0.2;
    const Scene s = blade({{"gravity.g", "9.81"},
                           {"beam.youngs_modulus", "7e13"},
                           {"gravity.direction", "axis"},
                           {"beam.precone", std::to_string(cone)},
                           {"discretization.nz", "4"},
                           {"motion.angle", "0.7"}});
    const std::unique_ptr<Model> model = make_scene_model(s);
    const SteadySpin held = held_equilibrium(*model, 0.7);
    const RootLoads l = loads_of(s, *model, held.u, held.q, held.qd).at(0);
    const Parameters& p = s.parameters;
    const double m = mass_per_length(p), g = p.g_axis;
    const double W = m * g * p.L + p.m_tip * g, moment = m * g * p.L * p.L / 2.0 + p.m_tip * g * p.L;
    CHECK(l.shear_flap == Approx(-W * std::cos(cone)).epsilon(1e-12));
    CHECK(l.axial_force == Approx(-W * std::sin(cone)).epsilon(1e-12));
    CHECK(l.flap_moment == Approx(-moment * std::cos(cone)).epsilon(1e-5));
    CHECK(std::abs(l.shear_edge) < 1e-12 * W);
    CHECK(std::abs(l.edge_moment) < 1e-9 * moment);
}

TEST_CASE("a rotor's root loads, blade by blade, are the single blade's at its azimuth", "[root_loads]")
{
    // A prescribed spin-up under the weight in the plane: the blades do not interact, and the weight makes each
    // blade's loads depend on its azimuth (checked to differ), a pitch increment on blade 2 its own.
    const std::string spin = "[motion]\nkind = \"spin-up\"\nomega0 = 6.0\nduration = 0.5\n";
    const Overrides common = {{"gravity.g", "9.81"}, {"beam.youngs_modulus", "7e9"}, {"discretization.nz", "2"}};
    Overrides o = common;
    o.insert(o.end(), {{"rotor.blades", "3"}, {"rotor.pitch_offsets", "[0.0, 0.1, 0.0]"}});
    auto rotor = run_columns(blade(o, spin));
    REQUIRE(rotor.count("root_edge_moment_3") == 1);
    REQUIRE(rotor.count("root_edge_moment") == 0);
    for (int b = 1; b <= 3; ++b) {
        Overrides one = common;
        one.push_back({"motion.theta0", std::to_string(2.0 * std::numbers::pi * (b - 1) / 3.0)});
        if (b == 2) one.push_back({"beam.pitch", "0.1"});
        auto alone = run_columns(blade(one, spin + "theta0 = 0.0\n"));
        for (const LoadColumn& c : root_load_columns) {
            const std::string mine = std::string(c.name) + "_" + std::to_string(b);
            INFO(mine);
            CHECK(max_difference(rotor[mine], alone[c.name]) <= 1e-7 * peak(alone[c.name]) + 1e-9);
        }
    }
    CHECK(max_difference(rotor["root_shear_edge_1"], rotor["root_shear_edge_3"]) > 1e-2 * peak(rotor["root_shear_edge_1"]));
}

TEST_CASE("a rotor's root forces balance its hub on a moving support: sum of the blades' forces + support force = m_h "
          "a_h",
          "[root_loads]")
{
    // The hub's own equations (Lagrange's for x_h, y_h) say m_h a_h = F_support + the blades' pull, to the model's
    // order: the order `first` drops the foreshortening's share of the blades' momentum, a second-order term, so the
    // balance's residual falls as eps^2 with the disturbance eps from a steady spin while the forces fall as eps.
    const std::string torque = "[motion]\nkind = \"torque\"\ntau0 = 0.0\nduration = 1.0\n";
    const Scene s = blade({{"rotor.blades", "3"},
                           {"hub.mass", "20.0"},
                           {"support.stiffness_x", "2e4"},
                           {"support.stiffness_y", "3e4"},
                           {"support.damping_x", "40.0"},
                           {"support.damping_y", "10.0"},
                           {"beam.youngs_modulus", "7e9"},
                           {"tip.mass", "0"},
                           {"tip.inertia", "0"},
                           {"model.source", "auto"}},  // the assembled path has no moving hub
                          torque);
    const std::unique_ptr<Model> model = make_scene_model(s);
    // About the straight rotor spinning at 8 rad/s on a hub at rest, where the three blades' pulls cancel.
    const int n = model->nq();
    std::vector<double> q0(static_cast<std::size_t>(n), 0.0), qd0 = q0;
    qd0[0] = 8.0;
    const HubInput u{};  // no torque
    const CoordinateLayout& c = model->coordinates();
    const int ix = c.first(FieldKind::hub_x), iy = c.first(FieldKind::hub_y);
    const Parameters& p = s.parameters;
    std::vector<double> residual, force;
    for (const double eps : {1e-3, 5e-4}) {
        std::vector<double> q = q0, qd = qd0;
        for (std::size_t i = 1; i < q.size(); ++i) {  // a fixed disturbance of every coordinate but theta
            q[i] += eps * std::sin(1.7 * static_cast<double>(i) + 0.3);
            qd[i] += 10.0 * eps * std::cos(2.3 * static_cast<double>(i));
        }
        const std::vector<double> qdd = accelerations(*model, u, q, qd);
        const std::vector<RootLoads> loads = loads_of(s, *model, u, q, qd);
        double fx = -(p.k_x * q[ix] + p.c_x * qd[ix]), fy = -(p.k_y * q[iy] + p.c_y * qd[iy]);
        double scale = std::hypot(fx, fy);  // the first-order forces' size: the support's and each blade's
        for (int b = 0; b < 3; ++b) {
            // No precone: e1 = i_b, e2 = j_b; the blade's pull turned to the fixed frame.
            const RootLoads& l = loads[static_cast<std::size_t>(b)];
            const double psi = q[0] + 2.0 * std::numbers::pi * b / 3.0;
            scale += std::hypot(l.axial_force, l.shear_edge);
            fx += l.axial_force * std::cos(psi) - l.shear_edge * std::sin(psi);
            fy += l.axial_force * std::sin(psi) + l.shear_edge * std::cos(psi);
        }
        residual.push_back(std::hypot(fx - p.m_hub * qdd[static_cast<std::size_t>(ix)],
                                      fy - p.m_hub * qdd[static_cast<std::size_t>(iy)]));
        force.push_back(scale);
    }
    INFO("residual " << residual[0] << " then " << residual[1] << ", forces " << force[0]);
    CHECK(residual[0] < 1e-3 * force[0]);
    // Second order and nothing of the first: a quarter per halving (a first-order error, such as a Coriolis term's
    // 1 N against the 3.7 N of the second order's here, moves the ratio towards 2).
    CHECK(residual[0] / residual[1] == Approx(4.0).epsilon(0.05));
}

TEST_CASE("a rotor's fields CSV has every blade's lines, each with its blade's number, and one blade's no blade column",
          "[root_loads]")
{
    // Three blades whose in-plane coordinates differ (blade b's scaled by b): each blade's u_y along the span is its
    // own coordinates' combination of the shape functions, and its tip value the rotor's tip of that blade.
    Scene s = blade({{"rotor.blades", "3"}, {"discretization.nx", "0"}, {"tip.inertia", "0"}});
    const std::unique_ptr<Model> model = make_scene_model(s);
    const CoordinateLayout& layout = model->coordinates();
    std::vector<double> q(static_cast<std::size_t>(model->nq()), 0.0);
    for (int b = 0; b < 3; ++b) {
        const CoordinateField& f = *layout.find(FieldKind::inplane, b);
        for (int i = 0; i < f.count; ++i) q[static_cast<std::size_t>(f.first + i)] = 1e-3 * (b + 1) * (i % 2 == 0 ? 1 : 0.1);
    }
    const TempFolder folder("rotor-fields");
    const std::string path = (folder.path / "fields.csv").string();
    FieldRecorder recorder(s.key(), s.parameters, {0.0}, 5, path, s.rotor);
    recorder.state(0.0, q.data());
    REQUIRE(recorder.finish());
    const test::Csv csv = test::read_csv(path);
    REQUIRE(csv.names.size() > 2);
    CHECK(csv.names[0] == "t");
    CHECK(csv.names[1] == "blade");
    const std::size_t blade_at = csv.column("blade"), x_at = csv.column("x"), uy_at = csv.column("uy");
    std::vector<int> lines(4, 0);
    for (const std::vector<double>& row : csv.rows) {
        const int b = static_cast<int>(row[blade_at]);
        REQUIRE((b >= 1 && b <= 3));
        ++lines[static_cast<std::size_t>(b)];
        if (row[x_at] == s.parameters.L) CHECK(row[uy_at] == Approx(blade_tip(*model, q.data(), b - 1).uy).epsilon(1e-12));
    }
    CHECK(lines[1] >= 5);  // 5 points and both sides of FEM's node
    CHECK(lines[2] == lines[1]);
    CHECK(lines[3] == lines[1]);
    // One blade: the single blade's header, as ever.
    const Scene one = blade({{"discretization.nx", "0"}});
    const std::string single = (folder.path / "single.csv").string();
    FieldRecorder alone(one.key(), one.parameters, {0.0}, 5, single, one.rotor);
    std::vector<double> q1(static_cast<std::size_t>(make_scene_model(one)->nq()), 0.0);
    alone.state(0.0, q1.data());
    REQUIRE(alone.finish());
    CHECK(test::read_csv(single).names[1] == "x");
}

TEST_CASE("root loads of a flexible blade spun up balance the rate of the run's angular momentum", "[root_loads]")
{
    // The hub turns the blade by the opposite of the blade's moment about the axis, root_edge_moment + a
    // root_shear_edge, so d(momentum)/dt = J_oh theta_ddot - (root_edge_moment + a root_shear_edge): the momentum
    // column is the model's dT/dtheta_dot, differenced here over the rows (central, dt_out 1 ms), and the blade rings
    // at its first frequency (63 rad/s), whose elastic accelerations are in the loads. To the order first keeps
    // and the differences' h^2: 1e-4 of the largest moment (2.7e-5 measured).
    Scene s = blade({{"discretization.nx", "0"}}, "[motion]\nkind = \"spin-up\"\nomega0 = 3.0\nduration = 0.5\n");
    s.output.t_end = 1.0;
    s.output.dt_out = 1e-3;
    const auto c = run_columns(s);
    const Parameters& p = s.parameters;
    const std::vector<double>&t = c.at("t"), &H = c.at("momentum"), &w = c.at("theta_dot");
    const std::vector<double>&M = c.at("root_edge_moment"), &F = c.at("root_shear_edge");
    double worst = 0.0, largest = 0.0, ringing = 0.0;
    for (std::size_t i = 1; i + 1 < t.size(); ++i) {
        const double dH = (H[i + 1] - H[i - 1]) / (t[i + 1] - t[i - 1]);
        const double dw = (w[i + 1] - w[i - 1]) / (t[i + 1] - t[i - 1]);
        const double blade = M[i] + p.a * F[i];
        worst = std::max(worst, std::abs(dH - (p.J_oh * dw - blade)));
        largest = std::max(largest, std::abs(blade));
        if (t[i] > 0.5) ringing = std::max(ringing, std::abs(blade));  // the drive is steady: what is left rings
    }
    INFO("worst " << worst << " of " << largest << ", ringing " << ringing);
    CHECK(ringing > 1e-2 * largest);
    CHECK(worst < 1e-4 * largest);
}

TEST_CASE("root loads turn a blade's mass moments by their principal axes' angle, not by the chord's",
          "[root_loads][profile]")
{
    // With equal flap and edge stiffness the chord's angle turns nothing of the energies: a table with its principal
    // inertia axes at beta_i and its chord at beta is the table with both at beta_i, state for state, so are their
    // root loads. A pitched, spinning, twisting blade, whose section inertia drives the flap and edge moments.
    VariantKey key{.method = Method::fem, .nx = 0, .ny = 4, .order = Order::first, .drive = Drive::torque};
    key.nz = 4, key.nt = 2;
    key.extras.tabulated = key.extras.pitch = true;
    const auto table = [](std::array<double, 2> chord, std::array<double, 2> axes) {
        Parameters p;
        p.L = 2.0, p.a = 0.3, p.pitch = 0.25, p.J_oh = 4.0;
        p.stations = {0.0, 1.0};
        for (std::size_t k = 0; k < 2; ++k)
            p.profile.insert(p.profile.end(), {2.0, 500.0, 1e6, 500.0, 80.0, chord[k], 0.05, 0.3, axes[k]});
        p.rho = 2.0, p.S = 1.0, p.E = 1e6, p.I = p.I_flap = 5e-4;
        return p;
    };
    const Parameters turned = table({0.3, -0.2}, {0.9, 0.4}), along = table({0.9, 0.4}, {0.9, 0.4});
    const Parameters chord = table({0.3, -0.2}, {0.3, -0.2});  // the inertia along the chord: another blade
    const int nq = key.nq();
    std::vector<double> q(static_cast<std::size_t>(nq)), qd(q.size());
    for (int k = 0; k < nq; ++k) {
        q[static_cast<std::size_t>(k)] = 0.02 * std::sin(1.3 * k + 0.5);
        qd[static_cast<std::size_t>(k)] = 0.4 * std::cos(0.7 * k);
    }
    qd[0] = 6.0;
    const auto loads = [&](const Parameters& p) {
        const auto model = make_model(key, p, ModelSource::assembled);
        const std::vector<double> qdd = accelerations(*model, HubInput{}, q, qd);
        return blade_root_loads(*model, {BladeLoads(key, p)}, HubInput{}, q.data(), qd.data(), qdd.data()).at(0);
    };
    const RootLoads a = loads(turned), b = loads(along), c = loads(chord);
    for (double RootLoads::*member : root_load_members) {
        const double scale = std::max(std::abs(b.*member), 1.0);
        INFO("turned " << a.*member << ", along " << b.*member << ", with the chord " << c.*member);
        CHECK(std::abs(a.*member - b.*member) < 1e-10 * scale);
    }
    CHECK(std::abs(a.flap_moment - c.flap_moment) > 1e-3 * std::abs(b.flap_moment));
    CHECK(std::abs(a.edge_moment - c.edge_moment) > 1e-3 * std::abs(b.edge_moment));
}

TEST_CASE("root loads of a blade whose inertia axes turn along the span balance the hub's torque equation",
          "[root_loads][profile]")
{
    // At rest in the blade's own frame (q = 0, spinning, a torque on the hub) the hub's equation is exact at any order:
    // tau - J_oh theta_ddot = -(root_edge_moment + a root_shear_edge). The section's mass moments enter the hub's
    // inertia as the model takes them, their deviator's components linear between stations; inertia axes that turn
    // 1.2 rad between two stations make that integral 2.1 times the one of the angle taken linear (sin 2.4 / 2.4 against
    // (1 + cos 2.4) / 2), so loads that read the section otherwise miss the balance by 3 to 16 % of the torque.
    // A uniform blade pre-twisted by as much (its chord the inertia axes) holds the same balance.
    for (const bool tabulated : {true, false})
    for (const double pitch : {0.0, 0.25, -0.4}) {
        VariantKey key{.method = Method::fem, .nx = 0, .ny = 4, .order = Order::first, .drive = Drive::torque};
        key.nz = 4, key.nt = 2;
        key.extras.pitch = true;
        (tabulated ? key.extras.tabulated : key.extras.twist) = true;
        Parameters p;
        p.L = 2.0, p.a = 0.3, p.pitch = pitch, p.J_oh = 0.05;
        p.rho = 2.0, p.S = 1.0, p.E = 1e6, p.I = 5e-4, p.I_flap = 1e-4;
        if (tabulated) {
            p.I_flap = p.I;
            p.stations = {0.0, 1.0};
            for (const double axes : {0.0, 1.2})
                p.profile.insert(p.profile.end(), {2.0, 500.0, 1e6, 800.0, 80.0, 0.1, 0.05, 0.3, axes});
        } else {
            p.twist = 1.2;
        }
        const auto model = make_model(key, p, ModelSource::assembled);
        std::vector<double> q(static_cast<std::size_t>(key.nq())), qd(q.size());
        qd[0] = 3.0;
        const HubInput u{.tau = 2.0};
        const std::vector<double> qdd = accelerations(*model, u, q, qd);
        const RootLoads r = blade_root_loads(*model, {BladeLoads(key, p)}, u, q.data(), qd.data(), qdd.data()).at(0);
        INFO((tabulated ? "a table" : "a uniform blade") << " at pitch " << pitch << ": theta_ddot " << qdd[0] << ", edge moment " << r.edge_moment);
        CHECK(std::abs(u.tau - p.J_oh * qdd[0] + r.edge_moment + p.a * r.shear_edge) < 1e-12 * u.tau);
    }
}
