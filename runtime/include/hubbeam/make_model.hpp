// Model selection: which implementation serves a variant (generated kernels: built in, cached or compiled on
// demand; or the hand-assembled docs/model.md section 5), as a scene's model.source asks.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// Told one line about slow or surprising choices (an on-demand compilation, a fallback to the assembled path).
using ModelNote = std::function<void(const std::string&)>;

/// generated: built in, else cached, else compiled now (on_demand.hpp); automatic: the same, else (no compiler)
/// assembled, with a note. Throws std::invalid_argument if none can serve, CompileError if a compilation failed.
std::unique_ptr<Model> make_model(const VariantKey& key, const Parameters& p,
                                  ModelSource source = ModelSource::automatic, const ModelNote& note = {});

/// The model a scene runs: its variant's (make_model), or for a rotor of several blades ([rotor] blades > 1) one
/// model of the variant per blade, each at its blade's parameters and azimuth, joined through the hub (rotor_model.hpp).
std::unique_ptr<Model> make_scene_model(const Scene& scene, const ModelNote& note = {});
/// The same with another discretization of the scene's beam (a convergence study's key), the rest the scene's.
std::unique_ptr<Model> make_scene_model(const Scene& scene, const VariantKey& key, const ModelNote& note = {});

/// Blade b's tip (b 0-based) at coordinates q of a scene's model: the model's tip for a single blade.
Tip blade_tip(const Model& model, const double* q, int b);
/// The number of blades of a scene's model (1 for every model but a rotor's).
int blade_count(const Model& model);

}  // namespace hubbeam
