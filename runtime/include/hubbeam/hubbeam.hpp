// hubbeam as a C++ library: everything a program needs to load or build a scene, run it and receive its rows,
// compute modes and linearized models (docs/development.md "Building"; examples/run_scene).
//
//   hubbeam::Scene scene = hubbeam::load_scene("cases/spinup_omega4.toml", {{"discretization.ny", "8"}});
//   hubbeam::Simulation simulation(scene);
//   hubbeam::RunSummary summary = simulation.run([](const hubbeam::Row& row) { /* row.t, row.tip_uy, ... */ });
#pragma once

#include <hubbeam/fields.hpp>     // BeamFields: fields along the beam
#include <hubbeam/linearize.hpp>  // steady_spin, state_space, natural_modes
#include <hubbeam/mode_shapes.hpp>  // a blade's mode shapes and their ElastoDyn polynomials
#include <hubbeam/scene.hpp>      // Scene, load_scene, parse_scene, validate, scene_keys
#include <hubbeam/simulate.hpp>   // Simulation, Row, RunSummary
