// The coordinates the natural modes are over: what natural_modes and the code that reads a mode's shape back into
// coordinates (the blade's mode shapes along the span) share.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/model.hpp>

#include "models/mode_kinds.hpp"

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

/// Whether the variant's weight turns with the beam (in the plane of rotation): then only the held hub is steady.
/// Along the spin axis it does not (section 12): the steady spin holds the sag, found on every elastic row.
bool weight_turns_with_spin(const VariantKey& key, const std::vector<double>& p);

/// Linearized equations M x'' = Qq x + Qqd x' in deviations, each matrix over q's layout (nq x nq): a steady spin's
/// (natural_modes), or the multi-blade coordinates' (multiblade.cpp, laid out as q with component j of the blades'
/// coordinates where blade j + 1's are).
struct LinearEquations {
    Eigen::MatrixXd M, Qq, Qqd;
};

/// How eigen_modes names the modes of a system: separate, if given, turns the vectors (rates over R, columns) of
/// each set of repeated eigenvalues into a basis of modes that each have one kind; kind names a mode that is not
/// overdamped by its rates over R and its frequency.
struct ModeNaming {
    std::function<void(const Eigen::VectorXcd& lambda, Eigen::MatrixXcd& rates)> separate;
    std::function<std::string(const Eigen::VectorXcd& rates, double rad_s)> kind;
    /// Whether the equations dissipate: as the variant (dissipates), or less (a support whose dampers are 0).
    bool damped = true;
};

/// The modes of e over the coordinates R (indices into q; a free hub's angle, cyclic, first of them), unsorted:
/// natural_modes' rules for what is a mode (a free hub's conserved momentum dropped, conjugates once, a divergent or
/// overdamped real eigenvalue, growth round-off without damping), its shape U rates (M over R = U^T U).
std::vector<NaturalMode> eigen_modes(const Model& model, const LinearEquations& e, const std::vector<int>& R,
                                     const ModeNaming& naming);
/// natural_modes' order: by frequency, divergent modes (rad_s 0) first; with damping by undamped frequency, so that an
/// overdamped mode keeps its place among the others. The Floquet modes are ordered alike.
bool mode_before(const NaturalMode& a, const NaturalMode& b, bool damped);
void sort_modes(std::vector<NaturalMode>& modes, bool damped);
/// A mode's frequency rad_s, growth, undamped frequency and damping ratio from its eigenvalue (or Floquet exponent):
/// its imaginary part rad_s (0 for a real one), its real part and its modulus. Without damping the equations are
/// conservative (gyroscopic at most): a real part below 1e-6 of the modulus (at least 1) is round-off, not damping.
void set_rates(NaturalMode& mode, double rad_s, double real, double modulus, bool damped);

/// NaturalMode::shape of a mode with these rates: U rates with U the upper Cholesky factor of M over the same
/// coordinates (mass_factor: M = U^T U), scaled to unit length.
Eigen::VectorXcd weighted_shape(const Eigen::MatrixXd& U, const Eigen::VectorXcd& rates);

}  // namespace hubbeam
