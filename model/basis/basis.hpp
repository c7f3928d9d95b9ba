// The shape functions of one field (axial or transverse) for any method and count: the single source of
// basis functions for the generator (exact, symbolic) and the runtime (numeric values and derivatives).
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "amm.hpp"
#include "bim.hpp"
#include "bsim.hpp"
#include "fem.hpp"
#include "jet.hpp"
#include "quadrature.hpp"

namespace hubbeam {

enum class Method { amm, fem, bim, bsim };
enum class Field { axial, transverse };
/// Construction of BSIM's transverse basis; both span the same space. The axial field always uses the
/// open-knot basis: the paper's axial basis is in error (docs/model.md section 8) and eq. 41 needs n >= 3.
enum class SplineBasis { paper, open };

/// Phi_x or Phi_y of docs/model.md section 4 as functions of xi in [0, 1], given piece by piece.
class FieldBasis {
public:
    FieldBasis(Method method, Field field, int count, SplineBasis spline = SplineBasis::paper)
        : method_(method), field_(field), count_(count), spline_(spline)
    {
        if (method == Method::amm && field == Field::transverse)
            for (int i = 1; i <= count; ++i) modes_.push_back(amm::mode(i));
    }

    Method method() const { return method_; }
    Field field() const { return field_; }
    int size() const { return count_; }

    /// Number of equal intervals of [0, 1] on each of which every function is one polynomial (or, for
    /// AMM, one analytic function).
    int intervals() const
    {
        if (count_ == 0) return 1;
        switch (method_) {
        case Method::fem: return field_ == Field::transverse ? count_ / 2 : count_;
        case Method::bsim: return field_ == Field::transverse ? count_ - 1 : count_ - 2;
        default: return 1;
        }
    }
    bool polynomial() const { return method_ != Method::amm; }

    /// Degree of the polynomial pieces (docs/model.md section 4); 0 for an empty basis. Not for AMM.
    int degree() const
    {
        if (count_ == 0) return 0;
        const bool tr = field_ == Field::transverse;
        switch (method_) {
        case Method::fem: return tr ? 3 : 1;
        case Method::bim: return tr ? count_ + 1 : count_;
        case Method::bsim: return 3;
        case Method::amm: break;
        }
        throw std::logic_error("FieldBasis::degree: not a polynomial basis");
    }

    /// The interval holding xi (the last one for xi = 1).
    int interval_of(double xi) const
    {
        const int n = intervals();
        const int k = static_cast<int>(xi * n);
        return k < 0 ? 0 : k >= n ? n - 1 : k;
    }

    /// Function i (0-based) restricted to interval k, evaluated at xi (of any scalar type).
    template <class T> T piece(int i, int k, const T& xi) const
    {
        const int n = intervals();
        const bool ax = field_ == Field::axial;
        switch (method_) {
        case Method::amm: return ax ? amm::axial(i + 1, xi) : amm::transverse(modes_[i], xi);
        case Method::fem: return ax ? fem::axial(i, n, k, xi) : fem::transverse(i, n, k, xi);
        case Method::bim: return ax ? bim::axial(i, count_, xi) : bim::transverse(i, count_, xi);
        case Method::bsim:
            if (ax) return bsim::open(i + 1, n, k, xi);
            return spline_ == SplineBasis::paper ? bsim::paper(i + 1, n, k, xi) : bsim::open(i + 2, n, k, xi);
        }
        throw std::logic_error("FieldBasis: unknown method");
    }

    /// phi_i, dphi_i/dxi and d2phi_i/dxi2 at a point.
    Jet<double> at(int i, double xi) const { return piece(i, interval_of(xi), variable(xi)); }

private:
    Method method_;
    Field field_;
    int count_;
    SplineBasis spline_;
    std::vector<amm::Mode> modes_;
};

/// Nodes and weights on xi in [0, 1] for integrals of products of two members of a and b (and their
/// derivatives) times a polynomial of degree <= 2 in xi: Gauss-Legendre on every interval of the common
/// refinement of both bases' intervals, exact for polynomial bases; for AMM a composite rule converged to
/// round-off. extra_cuts (a tabulated profile's stations) are interval boundaries too, so that an integrand with a
/// kink there stays exact (polynomial bases) or converged (AMM).
inline QuadratureRule product_rule(const FieldBasis& a, const FieldBasis& b, const std::vector<double>& extra_cuts = {})
{
    std::vector<double> cuts{0.0, 1.0};
    if (!a.polynomial() || !b.polynomial()) {
        if (extra_cuts.empty()) return transcendental_rule(std::max(a.size(), b.size()));
        const int panels = transcendental_panels(std::max(a.size(), b.size()));
        for (int k = 1; k < panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    } else {
        for (const FieldBasis* f : {&a, &b})
            for (int k = 1; k < f->intervals(); ++k) cuts.push_back(static_cast<double>(k) / f->intervals());
    }
    cuts.insert(cuts.end(), extra_cuts.begin(), extra_cuts.end());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-14; }), cuts.end());
    cuts.back() = 1.0;
    if (!a.polynomial() || !b.polynomial()) return composite_gauss_legendre(cuts, transcendental_points);
    // Two pieces times at most a quadratic in xi: degree <= 2 max + 2, and n points are exact to 2n - 1.
    return composite_gauss_legendre(cuts, std::max(a.degree(), b.degree()) + 2);
}

}  // namespace hubbeam
