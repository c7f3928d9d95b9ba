// Stage "points": order full's foreshortening terms evaluated at quadrature points instead of expanded into
// polynomials of the coordinates. The terms of |r_dot|^2 that order full keeps beyond order first all hold
// u_x2 = -1/2 B^T H(x) B or its rate, so expanded they are quartic in B (O(Ny^4) terms in M and Q); at G points
// they cost O(G Ny^2). The density is differentiated symbolically (GiNaC) in the point fields, and Lagrange's
// equations follow from it by the chain rule through the fields' gradients; the emitted code loops over the points.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <ginac/ginac.h>

#include "energy.hpp"
#include "variant.hpp"

namespace hubbeam::gen {

/// Where a variant's beam is sampled: xi_g in (0, 1) and the weights of int_0^1 (. ) dxi.
/// Polynomial bases: Gauss-Legendre on every polynomial piece with points enough to be exact for the density's
/// degree (the fields' degrees summed). AMM: one Gauss-Legendre rule whose size converges the highest modes'
/// products to round-off (tests/generator checks it against the composite rule of the integrals stage).
struct PointRule {
    std::vector<double> xi, weight;
    bool exact = false;  // exact for the integrands (polynomial bases), else converged
};
PointRule point_rule(const VariantKey& key);

/// H(xi) = int_0^xi Phi_y'^T Phi_y' dxi (xi units, row-major), by Gauss-Legendre on the pieces: exact for a
/// polynomial basis (d points on a piece of degree d), for AMM the integrals stage's converged composite rule.
std::vector<double> coupling_at(const FieldBasis& transverse, double xi);

/// Whether a variant's order-full terms go to the points: order full on a uniform beam (a tapered or tabulated
/// section keeps the expanded form, whose integrals hold m(x)) with Ny >= 8 (below, the expanded form is cheaper).
bool foreshortening_at_points(const VariantKey& key);

/// The kernels' code for the point terms: tables and a helper (once per source), and the lines each kernel adds to
/// its outputs after its polynomial part; the placeholders $m_L, $inv_L, $m_tip stand for coefficients (parameter
/// expressions) that the emitter replaces by entries of the coefficient pool.
struct PointCode {
    std::string tables;
    std::string mass, forces, energy, momentum;  // bodies appended to the kernels of those names
    std::string forces_q, forces_qd, forces_u, mass_q_product;  // forces_u empty: no point terms (hub torque)
    std::vector<std::pair<std::string, GiNaC::ex>> coefficients;
    /// Entries (row-major, upper triangle) of M that the point terms add to: the runtime must treat them as varying.
    std::vector<int> mass_entries;
};
PointCode point_code(const VariantKey& key, const Symbols& s);

}  // namespace hubbeam::gen
