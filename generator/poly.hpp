// Stage "poly": the equations as polynomials in the kernels' run-time variables (u, q, qd) whose coefficients are
// sums of number * parameter monomial, and their derivatives. Lagrange's equations and their Jacobians are
// differentiated in this form: a derivative costs one pass over the terms, where GiNaC re-canonicalises a whole
// expression of up to 10^5 terms per derivative.
#pragma once

#include <map>
#include <vector>

#include <ginac/ginac.h>

namespace hubbeam::gen {

/// Exponents over a list of symbols (the parameters, or the run-time variables).
using Exponents = std::vector<int>;
/// Sum of number * parameter monomial; no zero number is stored.
using Coefficient = std::map<Exponents, GiNaC::numeric>;

/// Sum of coefficient * variable monomial; no zero coefficient is stored, so that zero is the empty map.
class Poly {
public:
    const std::map<Exponents, Coefficient>& terms() const { return terms_; }
    /// The terms, moved out (for a consumer that needs no Poly afterwards).
    std::map<Exponents, Coefficient> release() && { return std::move(terms_); }
    bool is_zero() const { return terms_.empty(); }
    /// Whether a term holds variable v.
    bool has(int v) const;
    /// d/d(variable v).
    Poly diff(int v) const;
    /// This polynomial times variable v.
    Poly times(int v) const;
    /// Adds c * monomial.
    void add(const Exponents& monomial, const Coefficient& c, const GiNaC::numeric& scale = 1);
    Poly& operator+=(const Poly& p);
    Poly& operator-=(const Poly& p);
    /// The terms whose degree in the variables `which` is d (e.g. T2: degree 2 in the rates).
    Poly of_degree(const std::vector<int>& which, int d) const;

private:
    std::map<Exponents, Coefficient> terms_;
};

/// Reads expanded GiNaC polynomials over the parameter and variable symbols into Polys; throws EmitError-like
/// std::invalid_argument for anything else (a non-integer power, a variable in a denominator, an unknown symbol).
class PolyReader {
public:
    PolyReader(const std::vector<GiNaC::symbol>& parameters, const std::vector<GiNaC::symbol>& variables);
    Poly operator()(const GiNaC::ex& e) const;

private:
    std::map<GiNaC::symbol, std::pair<bool, std::size_t>, GiNaC::ex_is_less> index_;
    std::size_t np_ = 0, nv_ = 0;
};

/// The GiNaC expression of p over the same symbols (for tests that compare with the expression route).
GiNaC::ex to_ex(const Poly& p, const std::vector<GiNaC::symbol>& parameters, const std::vector<GiNaC::symbol>& variables);

}  // namespace hubbeam::gen
