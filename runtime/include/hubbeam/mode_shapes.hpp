// A blade's mode shapes along the span and the polynomials ElastoDyn takes for them (BldFl1Sh, BldFl2Sh, BldEdgSh):
// sixth-order polynomials in x/L from x^2 to x^6 whose coefficients sum to 1, fitted by least squares under that
// constraint to the shape normalised to 1 at the tip (the approach of BModes and ModeShapePolyFitting;
// docs/cli.md "ElastoDyn mode shapes").
#pragma once

#include <array>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// A shape phi(xi) fitted by p(xi) = sum_{k=2}^{6} c_k xi^k with sum_k c_k = 1, so that p(0) = p'(0) = 0 (a
/// clamped root) and p(1) = 1: coefficients[k - 2] = c_k. residual is the root mean square of p(xi_i) - phi(xi_i)
/// over the samples, phi normalised to 1 at the tip: a fraction of the tip deflection.
struct PolynomialFit {
    std::array<double, 5> coefficients{};
    double residual = 0.0;
};

/// The constrained least-squares fit of the samples phi at the abscissae xi (x/L in [0, 1]), phi first divided by
/// its value at xi = 1: c_6 = 1 - (c_2 + ... + c_5) eliminates the constraint, and c_2 .. c_5 minimise
/// sum_i (sum_{k=2}^{5} c_k (xi_i^k - xi_i^6) + xi_i^6 - phi_i)^2 (Householder QR). Throws std::invalid_argument
/// for sizes that differ, fewer than 5 samples, an abscissa outside [0, 1] or not finite, no sample at xi = 1, or a
/// value there of 0.
PolynomialFit fit_mode_shape(const std::vector<double>& xi, const std::vector<double>& phi);

/// One mode's shape along the span: its name ("flap 1": kind and order among the modes of its kind that oscillate),
/// its damped frequency, the samples phi(xi) (normalised to 1 at the tip) and their fit.
struct BladeModeShape {
    std::string name;
    double rad_s = 0.0;
    std::vector<double> xi, phi;
    PolynomialFit fit;
};

/// The three shapes an ElastoDyn blade file holds, at the steady spin omega: the first and second flap modes
/// (BldFl1Sh, BldFl2Sh) and the first edge mode (BldEdgSh).
struct ElastoDynShapes {
    double omega = 0.0;
    BladeModeShape flap1, flap2, edge1;
};

/// The open loop's natural modes about the steady spin at omega (natural_modes; theta the held angle of a gravity
/// variant), and of the first two of kind flap and the first of kind edge that oscillate, the shape along the span
/// from the mode's eigenvector: u_z(x) (out of the plane of rotation) of a flap mode, u_y(x) (in it) of an edge
/// mode, the fields' shape functions at the coordinates' rates, divided by the complex value at the tip (a
/// gyroscopic mode's phase) and its real part taken, at samples equally spaced abscissae from root to tip; each
/// fitted by fit_mode_shape. p are the model's parameters (the span L). Throws std::invalid_argument for a variant
/// without flapwise coordinates (nz = 0), fewer than 5 samples or a spin rate without a steady state
/// (steady_spin), std::runtime_error where the modes lack a second flap or a first edge mode.
ElastoDynShapes elastodyn_mode_shapes(const Model& model, const Parameters& p, double omega,
                                      Axial axial = Axial::dynamic, double theta = 0.0, int samples = 201);

/// The BLADE MODE SHAPES section of an ElastoDyn blade file for shapes: its header line, then the 15 lines
/// "VALUE   BldFl1Sh(2) - Flap mode 1, coeff of x^2" ... "BldEdgSh(6)", each coefficient in its shortest
/// round-trip form (so that the written ones sum to 1 as the fitted ones do).
std::string elastodyn_section(const ElastoDynShapes& shapes);

}  // namespace hubbeam
