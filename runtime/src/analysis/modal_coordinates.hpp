// The coordinates the natural modes are over: what natural_modes and the code that reads a mode's shape back into
// coordinates (the blade's mode shapes along the span) share.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// The coordinates of the modes about s, indices into q, in the order of NaturalMode::shape's entries:
/// kept_coordinates (all, or all but the quasi-static axial ones), without a held hub's angle (not a degree of
/// freedom there).
std::vector<int> modal_coordinates(const Model& model, const SteadySpin& s, Axial axial);

/// natural_modes' kind and shape of a mode with these rates over the coordinates R (indices into q): its kind by the
/// field that holds most of its kinetic energy under M (nq x nq), or "overdamped"; its shape U rates of unit length,
/// U the upper Cholesky factor of M over R. The Floquet modes (floquet.cpp) are classified by the same rule.
void classify_mode(const Model& model, const Eigen::MatrixXd& M, const Eigen::MatrixXd& U, const std::vector<int>& R,
                   const Eigen::VectorXcd& rates, bool overdamped, NaturalMode& mode);

}  // namespace hubbeam
