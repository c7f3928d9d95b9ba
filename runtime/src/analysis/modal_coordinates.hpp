// The coordinates the natural modes are over: what natural_modes and the code that reads a mode's shape back into
// coordinates (the blade's mode shapes along the span) share.
#pragma once

#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// The coordinates of the modes about s, indices into q, in the order of NaturalMode::shape's entries:
/// kept_coordinates (all, or all but the quasi-static axial ones), without a held hub's angle (not a degree of
/// freedom there).
std::vector<int> modal_coordinates(const Model& model, const SteadySpin& s, Axial axial);

}  // namespace hubbeam
