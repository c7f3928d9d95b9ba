// Where a run starts (scene key initial.state, docs/scene.md): the model's coordinates at t = 0, at rest or at the
// equilibrium the scene asks for, found by the linearization's own Newton solves (steady_spin, held_equilibrium).
#pragma once

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>
#include <string>
#include <vector>

namespace hubbeam {

/// The model's coordinates at t = 0 and how they were found.
struct InitialCoordinates {
    std::vector<double> q;  // nq: a torque-driven hub's angle, then the elastic coordinates
    /// For the summary's initial line ("static equilibrium at theta = 0 rad (Newton, residual 3e-16 of the load)");
    /// empty at rest.
    std::string description;
};

/// The coordinates a run of scene on model starts from, all rates 0 but the hub's own (the drive's at t = 0):
/// rest: the beam straight and unloaded, the hub at its initial angle; "static": the elastic coordinates in
/// equilibrium with the constant loads (the weight, the centrifugal load of the hub's initial rate) at the drive's
/// initial angle and rate; "steady": the steady spin at the drive's initial rate (under gravity at rest, the static
/// sag). Throws std::invalid_argument for "steady" where the scene has no steady spin (gravity in the plane of a
/// spinning hub; validate() refuses such a scene first), std::runtime_error where Newton finds no equilibrium.
InitialCoordinates initial_coordinates(const Model& model, const Scene& scene);

}  // namespace hubbeam
