// The Floquet analysis of a periodic linearization (docs/model.md section 10.1) against what is known without it:
// without weight in the plane of rotation the coefficients are constant and its modes are the eigen-analysis's
// (natural_modes, an independent path: one eigenproblem of the state matrix, no orbit, no integration); as the weight
// goes to zero its exponents go to those modes and its periodic motion to the steady state, linearly in g; the
// periodic motion is what the library's own simulation (GSL's or hubbeam's steppers, from rest, spun up) settles into;
// and hubbeam modes on the wind turbine's blade, spinning under its weight, prints the Floquet modes, within a few
// percent of the blade's without gravity.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include "modes.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

const std::string wind_turbine = std::string(HUBBEAM_SOURCE_DIR) + "/cases/wind_turbine_blade.toml";

std::complex<double> eigenvalue(const NaturalMode& m)
{
    return {m.growth, m.rad_s};
}

/// The natural mode whose eigenvalue lies nearest lambda, and the distance relative to |lambda|.
std::pair<const NaturalMode*, double> nearest(const std::vector<NaturalMode>& modes, std::complex<double> lambda)
{
    const NaturalMode* best = nullptr;
    double distance = HUGE_VAL;
    for (const NaturalMode& m : modes)
        if (const double d = std::abs(eigenvalue(m) - lambda); d < distance) distance = d, best = &m;
    return {best, distance / std::abs(lambda)};
}

/// Checks that the Floquet analysis at omega, forced on a model whose coefficients are constant (no weight in the
/// plane of rotation), gives the eigen-analysis's modes about the steady spin: each exponent is an eigenvalue modulo
/// i omega, and with its harmonic the same eigenvalue, frequency, damping and kind, to 1e-8 of |lambda|; and each
/// mode that one revolution resolves (a multiplier of 1e-6 or more) is among them. reference: the modes of the
/// steady spin (natural_modes, of this model or of one whose modes are the same).
void check_constant(const Model& model, double omega, const std::vector<NaturalMode>& reference)
{
    const FloquetAnalysis f = floquet(model, omega);
    const double period = 2.0 * M_PI / omega;
    REQUIRE_FALSE(f.modes.empty());
    for (const FloquetMode& m : f.modes) {
        const std::complex<double> lambda = eigenvalue(m.mode);
        const auto [match, distance] = nearest(reference, lambda);
        INFO("Omega " << omega << ": Floquet mode " << m.mode.kind << " " << m.mode.rad_s << " rad/s, growth "
                      << m.mode.growth << ", harmonic " << m.harmonic << "; nearest natural mode " << match->kind << " "
                      << match->rad_s << " rad/s, growth " << match->growth);
        CHECK(distance <= 1e-8);
        // The exponent is the eigenvalue modulo i omega: the harmonic restores the multiple.
        const std::complex<double> shifted = m.exponent + std::complex<double>(0.0, m.harmonic * omega);
        CHECK(std::abs(shifted - eigenvalue(*match)) <= 1e-8 * std::abs(lambda));
        CHECK(m.exponent.imag() > -0.5 * omega - 1e-12);
        CHECK(m.exponent.imag() <= 0.5 * omega + 1e-12);
        // The multiplier exp(lambda T), to the eigenvalue's accuracy: d mu = mu T d lambda.
        CHECK(std::abs(m.multiplier - std::exp(eigenvalue(*match) * period)) <= 1e-8 * std::abs(lambda) * period);
        CHECK(m.mode.kind == match->kind);
        CHECK(m.mode.damping_ratio == Approx(match->damping_ratio).margin(1e-8));
        CHECK(std::abs(mac(m.mode, *match) - 1.0) <= 1e-6);
    }
    for (const NaturalMode& n : reference) {
        if (std::exp(n.growth * period) < 1e-6) continue;
        INFO("Omega " << omega << ": natural mode " << n.kind << " " << n.rad_s << " rad/s, growth " << n.growth);
        double distance = HUGE_VAL;
        for (const FloquetMode& m : f.modes) distance = std::min(distance, std::abs(eigenvalue(m.mode) - eigenvalue(n)));
        CHECK(distance <= 1e-8 * std::abs(eigenvalue(n)));
    }
}

std::unique_ptr<Model> model_of(const Scene& s)
{
    return make_model(s.key(), s.parameters, s.source);
}

/// The largest deviation of the orbit's coordinates from those of state, over 64 instants of a period.
double deviation(const PeriodicOrbit& orbit, const std::vector<double>& state)
{
    double largest = 0.0;
    std::vector<double> q, qd;
    HubInput u;
    for (int j = 0; j < 64; ++j) {
        orbit.state(orbit.period * j / 64.0, q, qd, u);
        for (const int c : orbit.coordinates)
            largest = std::max(largest, std::abs(q[static_cast<std::size_t>(c)] - state[static_cast<std::size_t>(c)]));
    }
    return largest;
}

}  // namespace

TEST_CASE("without weight in the plane of rotation the Floquet modes are the eigen-analysis's", "[floquet][modes]")
{
    // The wind turbine's blade (FEM, flap, edge and twist, pitched, pre-twisted, coned, damped): without gravity, and
    // with its weight along the spin axis (which does not turn: a steady sag), its linearization about the spin has
    // constant coefficients, the monodromy matrix is exp(A T), and the periodic eigenvector of a mode of frequency w
    // is a single harmonic, k = (w - Im(exponent)) / Omega.
    for (const char* direction : {"none", "axis"}) {
        const Scene s = direction == std::string("none") ? load_scene(wind_turbine, {{"gravity.g", "0"}})
                                                         : load_scene(wind_turbine, {{"gravity.direction", "axis"}});
        const auto model = model_of(s);
        for (const double omega : {1.2, 3.0}) {
            INFO("gravity " << direction);
            REQUIRE(unsteady_spin(model->key(), model->parameters(), omega).empty());
            check_constant(*model, omega, natural_modes(*model, steady_spin(*model, omega)));
        }
    }
}

TEST_CASE("a free hub's Floquet modes are those of its hub held at the spin rate", "[floquet][modes]")
{
    // Under a torque drive the analysis holds the hub at the constant rate (theta = Omega t; its angle and rate no
    // degrees of freedom): without gravity, the modes of the same blade under a prescribed rotation at Omega. With its
    // weight in the plane, the same periodic problem, whichever drive the variant has.
    // The blade's scene with its spin-up replaced by a torque drive.
    const TempFolder folder("floquet-torque");
    std::string text;
    {
        std::ifstream in(wind_turbine);
        text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const std::size_t motion = text.find("[motion]"), next = text.find("\n[", motion + 1);
    REQUIRE(next != std::string::npos);
    const std::string torque_path =
        folder.write("torque.toml", text.substr(0, motion) + "[motion]\nkind = \"torque\"\ntau0 = 0.0\nduration = 1.0\n" + text.substr(next + 1));
    const Scene prescribed = load_scene(wind_turbine, {{"gravity.g", "0"}});
    const Scene torque = load_scene(torque_path, {{"gravity.g", "0"}, {"hub.inertia", "1000"}});
    REQUIRE(torque.key().drive == Drive::torque);
    const auto spun = model_of(prescribed), free = model_of(torque);
    check_constant(*free, 2.0, natural_modes(*spun, steady_spin(*spun, 2.0)));

    const Scene weighed = load_scene(wind_turbine), weighed_free = load_scene(torque_path, {{"hub.inertia", "1000"}});
    const FloquetAnalysis a = floquet(*model_of(weighed), 2.0), b = floquet(*model_of(weighed_free), 2.0);
    REQUIRE(a.modes.size() == b.modes.size());
    for (std::size_t i = 0; i < a.modes.size(); ++i) {
        INFO("mode " << i + 1 << ": " << a.modes[i].mode.rad_s << " and " << b.modes[i].mode.rad_s << " rad/s");
        CHECK(std::abs(eigenvalue(a.modes[i].mode) - eigenvalue(b.modes[i].mode)) <=
              1e-8 * std::abs(eigenvalue(a.modes[i].mode)));
        CHECK(a.modes[i].harmonic == b.modes[i].harmonic);
    }
}

TEST_CASE("as the weight in the plane goes to zero the Floquet modes go to the eigen-analysis's and the periodic motion "
          "to the steady spin, linearly in g",
          "[floquet][modes]")
{
    // The wind turbine's blade at 1.2 rad/s with its weight in the plane scaled by s: the motion is periodic for any
    // s > 0. Its exponents differ from the weightless blade's eigenvalues by O(g^2) (the weight's once-per-revolution
    // stiffness averages out over a revolution), and its deviation from the weightless steady state is O(g).
    const double omega = 1.2;
    const Scene weightless = load_scene(wind_turbine, {{"gravity.g", "0"}});
    const auto reference_model = model_of(weightless);
    const SteadySpin steady = steady_spin(*reference_model, omega);
    const std::vector<NaturalMode> reference = natural_modes(*reference_model, steady);
    std::vector<double> gap, amplitude;
    const std::vector<double> scales = {1.0, 0.1, 0.01, 0.02};
    for (const double scale : scales) {
        const Scene s = load_scene(wind_turbine, {{"gravity.g", std::to_string(9.81 * scale)}});
        const auto model = model_of(s);
        REQUIRE_FALSE(unsteady_spin(model->key(), model->parameters(), omega).empty());
        const FloquetAnalysis f = floquet(*model, omega);
        double largest = 0.0;
        for (const FloquetMode& m : f.modes) {
            if (std::abs(m.multiplier) < 1e-3) continue;  // the modes well resolved in one revolution
            largest = std::max(largest, nearest(reference, eigenvalue(m.mode)).second);
        }
        gap.push_back(largest);
        amplitude.push_back(deviation(f.orbit, steady.q));
    }
    INFO("largest relative gap to the weightless eigenvalues at g * 1, 0.1, 0.01, 0.02: " << gap[0] << ", " << gap[1]
                                                                                           << ", " << gap[2] << ", "
                                                                                           << gap[3]);
    INFO("deviation from the weightless steady state: " << amplitude[0] << ", " << amplitude[1] << ", "
                                                        << amplitude[2] << ", " << amplitude[3] << " m");
    // Continuity: the gap shrinks with g, as g^2: a hundredth for a tenth of the weight, four times for twice.
    CHECK(gap[0] > 1e-7);  // the weight is felt
    CHECK(gap[1] / gap[0] == Approx(0.01).epsilon(0.05));
    CHECK(gap[3] / gap[2] == Approx(4.0).epsilon(0.05));
    // The periodic motion's deviation from the steady state is linear in g: twice the weight, twice the swing.
    CHECK(amplitude[3] / amplitude[2] == Approx(2.0).epsilon(1e-6));
    CHECK(amplitude[1] / amplitude[2] == Approx(10.0).epsilon(1e-5));
}

TEST_CASE("the periodic motion is the one a simulation spun up from rest settles into", "[floquet][modes]")
{
    // An independent path: the library's Simulation (its stepper, its right-hand side), from rest, spun up to
    // Omega0 = 4 rad/s in 2 s, heavily damped (alpha = 4 1/s: every mode decays as exp(-2 t)), so that by t = 14 s
    // the start is forgotten below 1e-10. The beam under its weight in the plane, its coordinates at the rows against
    // the periodic motion at the same angle theta = Omega0 (t - T_s / 2): they repeat, revolution after revolution,
    // and they are the periodic motion, to 1e-8 of its swing.
    const TempFolder folder("floquet");
    const std::string path = folder.write("beam.toml", R"([beam]
length = 1.0
density = 2.7667e3
area = 7.2968e-5
second_moment = 8.2189e-9
youngs_modulus = 6.8952e10
[hub]
radius = 0.1
[gravity]
g = 9.81
[damping]
mass_proportional = 4.0
[motion]
kind = "spin-up"
omega0 = 4.0
duration = 2.0
[discretization]
method = "fem"
ny = 4
nx = 0
[model]
source = "assembled"
[solver]
rtol = 1e-12
atol = 1e-15
[output]
t_end = 20.0
dt_out = 0.0490873852123405
)");
    const Scene s = load_scene(path);
    const double omega = s.motion.omega0;
    const auto model = model_of(s);
    const PeriodicOrbit orbit = periodic_orbit(*model, omega);
    REQUIRE(orbit.period == Approx(2.0 * M_PI / omega).epsilon(1e-15));
    // dt_out is a 32nd of the period: every row has one a revolution before.
    REQUIRE(s.output.dt_out * 32 == Approx(orbit.period).epsilon(1e-14));
    std::vector<std::pair<double, std::vector<double>>> states;
    Simulation simulation(s);
    simulation.check_error(false);
    simulation.observe_states([&](double t, const double* q) { states.emplace_back(t, std::vector<double>(q, q + model->nq())); });
    REQUIRE(simulation.run([](const Row&) {}).completed);
    double swing = 0.0, repeat = 0.0, off = 0.0;
    std::vector<double> q, qd;
    HubInput u;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const auto& [t, state] = states[i];
        if (t < 14.0) continue;
        orbit.state(t - s.motion.spin_time / 2.0, q, qd, u);
        for (const int c : orbit.coordinates) {
            const auto k = static_cast<std::size_t>(c);
            swing = std::max(swing, std::abs(q[k] - orbit.coefficients(c - orbit.coordinates.front(), 0).real()));
            off = std::max(off, std::abs(state[k] - q[k]));
            if (const auto before = std::find_if(states.begin(), states.end(), [&](const auto& row) {
                    return std::abs(row.first - (t - orbit.period)) <= 1e-9;
                });
                before != states.end())
                repeat = std::max(repeat, std::abs(state[k] - before->second[k]));
        }
    }
    INFO("swing " << swing << ", simulation against the periodic motion " << off << ", against itself a revolution "
                  << "before " << repeat);
    CHECK(swing > 1e-5);
    CHECK(repeat <= 1e-8 * swing);
    CHECK(off <= 1e-8 * swing);
}

TEST_CASE("hubbeam modes takes the wind turbine's blade spinning under its weight by Floquet, near its modes without "
          "gravity",
          "[floquet][modes][cli]")
{
    // Gravity is a small perturbation for this blade: its weight swings the tip by centimetres on a 10 m blade, and
    // the tension it adds and takes away once a revolution is small against the bending stiffness, so that the lowest
    // flap and edge frequencies at 1.2 rad/s (the --omega of docs/cli.md's example; the scene spins up to 3 rad/s)
    // stay within 1 % of the weightless blade's (they agree to 1e-5). The weightless scene is steady: the
    // eigen-analysis as before, no Floquet line.
    const TempFolder folder("floquet-cli");
    const auto run = [&](const Scene& scene, const std::string& csv) {
        ModesArgs args;
        args.omega = "1.2";
        args.output = (folder.path / csv).string();
        args.harmonics = "none";
        std::ostringstream out;
        run_modes(scene, parse_modes_options(args, scene), out);
        std::map<std::string, double> lowest;  // kind -> the lowest frequency of that kind
        std::ifstream in(args.output);
        std::string line, header;
        std::getline(in, header);
        std::vector<std::string> names;
        for (std::istringstream h(header); std::getline(h, line, ',');) names.push_back(line);
        while (std::getline(in, line)) {
            std::map<std::string, std::string> row;
            std::istringstream fields(line);
            for (const std::string& name : names) std::getline(fields, row[name], ',');
            const double rad_s = std::stod(row.at("rad_s"));
            if (!lowest.count(row.at("kind")) || rad_s < lowest[row.at("kind")]) lowest[row.at("kind")] = rad_s;
        }
        return std::pair{out.str(), lowest};
    };
    const auto [printed, weighed] = run(load_scene(wind_turbine), "weighed.csv");
    const auto [printed_weightless, weightless] = run(load_scene(wind_turbine, {{"gravity.g", "0"}}), "weightless.csv");
    INFO(printed);
    CHECK(printed.rfind("analysis    Floquet over one revolution (period 5.23599 s at 1.2 rad/s)", 0) == 0);
    CHECK(printed_weightless.find("Floquet") == std::string::npos);
    for (const char* kind : {"flap", "edge"}) {
        INFO(kind << " 1: " << weighed.at(kind) << " rad/s under the weight, " << weightless.at(kind) << " without");
        CHECK(weighed.at(kind) == Approx(weightless.at(kind)).epsilon(0.01));
    }
}
