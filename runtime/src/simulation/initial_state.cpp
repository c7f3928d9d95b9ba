// initial_coordinates: a run's start at rest, at a static equilibrium or at a steady spin (initial_state.hpp).
#include "simulation/initial_state.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <hubbeam/linearize.hpp>
#include <stdexcept>

#include <hubbeam/shortest.hpp>

namespace hubbeam {

namespace {

/// The largest elastic force |Q_e| at the hub's input u and coordinates q, all elastic rates 0 (the hub's as in qd).
double elastic_force(const Model& model, const HubInput& u, const std::vector<double>& q, const std::vector<double>& qd)
{
    std::vector<double> Q(q.size());
    model.forces(u, q.data(), qd.data(), Q.data());
    const int e0 = model.coordinates().first_elastic();
    double largest = 0.0;
    for (std::size_t i = static_cast<std::size_t>(e0); i < Q.size(); ++i) largest = std::max(largest, std::abs(Q[i]));
    return largest;
}

}  // namespace

InitialCoordinates initial_coordinates(const Model& model, const Scene& scene)
{
    const VariantKey& key = model.key();
    const double theta = scene.motion.initial_theta(), rate = scene.initial_theta_dot();
    InitialCoordinates start;
    start.q.assign(static_cast<std::size_t>(model.nq()), 0.0);
    if (key.drive == Drive::torque) start.q[0] = theta;
    if (scene.initial == InitialState::rest) return start;

    // The one rule of which spins are steady (linearize.hpp): weight in the plane of rotation turns with the beam.
    const std::string unsteady = unsteady_spin(key, scene.parameters.packed(), rate);
    const bool steady = scene.initial == InitialState::steady;
    if (steady && !unsteady.empty())
        throw std::invalid_argument("initial.state \"steady\": " + unsteady + "; use \"static\" or \"rest\"");
    // Where the spin is steady, its equilibrium (at rest under gravity, the held hub's sag); else, for "static", the
    // equilibrium of the first instant, the weight at the initial angle and the centrifugal load of the initial rate.
    const SteadySpin s = unsteady.empty() ? steady_spin(model, rate, theta) : held_equilibrium(model, theta, rate);
    // The residual against the load the straight beam feels there: how well the elastic rows balance.
    const double load = elastic_force(model, s.u, start.q, s.qd), residual = elastic_force(model, s.u, s.q, s.qd);
    const double hub = start.q[0];  // steady_spin leaves a free hub's cyclic angle at 0
    start.q = s.q;
    if (key.drive == Drive::torque) start.q[0] = hub;
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "(Newton, residual %.2g of the load)", load > 0.0 ? residual / load : 0.0);
    const std::string at = steady ? "steady spin at theta_dot = " + shortest(rate) + " rad/s"
                                  : "static equilibrium at theta = " + shortest(theta) + " rad" +
                                        (rate != 0.0 ? ", theta_dot = " + shortest(rate) + " rad/s" : "");
    start.description = at + (load > 0.0 ? " " + std::string(numbers) : ": the straight beam (no constant load)");
    return start;
}

}  // namespace hubbeam
