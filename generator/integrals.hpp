// Stage "integrals": pure-number integrals over xi in [0,1] of products of shape functions, their
// derivatives and the coupling shape function H, exact rationals for polynomial bases and converged
// Gauss-Legendre quadrature for AMM.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <utility>
#include <vector>

#include "basis/basis.hpp"

namespace hubbeam::gen {

/// One factor of an integrand: d^deriv phi_i / dxi^deriv of a field, the coupling function
/// H_ij(xi) = int_0^xi phi_yi' phi_yj' dxi' (xi units; docs/model.md section 2) of the in-plane or the flapwise
/// field, or a tabulated profile's section distribution i (SectionDistribution of model/interface.hpp; docs/model.md
/// section 11.2), whose integrals are run-time data. The flapwise field has the transverse basis with nz functions,
/// the twist field the axial basis with nt (docs/model.md section 12).
struct Factor {
    enum class Kind { axial, transverse, coupling, section, flap, flap_coupling, twist } kind;
    int i = 0, j = 0;
    int deriv = 0;
    auto operator<=>(const Factor&) const = default;
};

/// A quadrature result below this fraction of the integral of the integrand's absolute value is taken as an
/// exact zero: the composite rule's round-off is a few hundred ulps of that magnitude, while every integral
/// that is not zero by orthogonality is a sizeable fraction of it. Polynomial bases are integrated exactly
/// and need no bound.
constexpr double cancellation_bound = 1e-13;

class ShapeIntegrals {
public:
    ShapeIntegrals(FieldBasis axial, FieldBasis transverse, FieldBasis flap = {Method::fem, Field::transverse, 0},
                   FieldBasis twist = {Method::fem, Field::axial, 0});

    /// int_0^1 xi^power * prod(factors) dxi: exact when both bases are polynomial.
    GiNaC::numeric integrate(std::vector<Factor> factors, int power);
    /// Whether prod(factors) can be nonzero somewhere on [0, 1] (its pieces all nonzero on one interval): a
    /// profile's integral of it against a section distribution is then a run-time number, else zero.
    bool overlaps(const std::vector<Factor>& factors);
    /// prod(factors) at xi = 1, the beam's tip (a tip body's energies): exact when both bases are polynomial.
    GiNaC::numeric at_tip(const std::vector<Factor>& factors);

private:
    GiNaC::numeric exact(const std::vector<Factor>& factors, int power);
    GiNaC::numeric quadrature(const std::vector<Factor>& factors, int power);
    GiNaC::ex piece(const Factor& f, const GiNaC::numeric& lo, const GiNaC::numeric& hi);
    /// piece() on breaks_[interval], breaks_[interval + 1] as coefficients of 1, xi, xi^2, ... (empty if zero).
    const std::vector<GiNaC::numeric>& piece_coefficients(const Factor& f, std::size_t interval);
    const std::vector<double>& values(const Factor& f);
    const FieldBasis& basis(const Factor& f) const;

    FieldBasis axial_, transverse_, flap_, twist_;
    bool exact_;
    GiNaC::symbol xi_{"xi"};
    std::vector<GiNaC::numeric> breaks_;  // common refinement of the fields' intervals
    std::vector<double> cuts_;            // panel boundaries of the composite rule (quadrature path)
    std::map<std::pair<Factor, int>, GiNaC::ex> pieces_;  // (factor, field interval) -> polynomial
    /// A coupling H_ij at the start of a field interval: the integral of phi_i' phi_j' over the intervals before it.
    std::map<std::pair<Factor, int>, GiNaC::numeric> coupling_starts_;
    std::map<std::pair<Factor, int>, std::vector<GiNaC::numeric>> coefficients_;  // the same, as coefficients
    std::map<std::pair<std::vector<Factor>, int>, GiNaC::numeric> cache_;
    std::vector<double> nodes_, weights_;  // composite rule (quadrature path)
    std::map<Factor, std::vector<double>> node_values_;
};

}  // namespace hubbeam::gen
