// Shape-function integrals: exact piecewise-polynomial integration with GiNaC rationals, or composite
// Gauss-Legendre quadrature for the transcendental AMM modes.
#include "integrals.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "basis/quadrature.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

std::string ex_to_string(const ex& e)
{
    std::ostringstream s;
    s << e;
    return s.str();
}

/// int_lo^hi p(xi) dxi for a polynomial p.
numeric integrate_polynomial(const ex& p, const symbol& xi, const numeric& lo, const numeric& hi)
{
    const ex e = p.expand();
    numeric sum = 0;
    for (int k = e.ldegree(xi); k <= e.degree(xi); ++k) {
        const ex c = e.coeff(xi, k);
        if (c.is_zero()) continue;
        if (!is_a<numeric>(c)) throw std::logic_error("integrals: non-numeric coefficient " + ex_to_string(c));
        sum += ex_to<numeric>(c) * (hi.power(k + 1) - lo.power(k + 1)) / (k + 1);
    }
    return sum;
}

}  // namespace

/// Whether a factor is a coupling function H (of the in-plane or the flapwise field).
static bool is_coupling(const Factor& f)
{
    return f.kind == Factor::Kind::coupling || f.kind == Factor::Kind::flap_coupling;
}

ShapeIntegrals::ShapeIntegrals(FieldBasis axial, FieldBasis transverse, FieldBasis flap, FieldBasis twist)
    : axial_(std::move(axial)),
      transverse_(std::move(transverse)),
      flap_(std::move(flap)),
      twist_(std::move(twist)),
      exact_(axial_.polynomial() && transverse_.polynomial() && (flap_.size() == 0 || flap_.polynomial()) &&
             (twist_.size() == 0 || twist_.polynomial()))
{
    if (exact_) {
        for (const FieldBasis* b : {&axial_, &transverse_, &flap_, &twist_}) {
            if (b->size() == 0) continue;
            for (int k = 0; k <= b->intervals(); ++k) breaks_.push_back(numeric(k, b->intervals()));
        }
        std::sort(breaks_.begin(), breaks_.end(), [](const numeric& a, const numeric& b) { return a < b; });
        breaks_.erase(
            std::unique(breaks_.begin(), breaks_.end(), [](const numeric& a, const numeric& b) { return a == b; }),
            breaks_.end());
        if (breaks_.empty()) breaks_ = {0, 1};
    } else {
        const int panels =
            transcendental_panels(std::max({axial_.size(), transverse_.size(), flap_.size(), twist_.size()}));
        for (int k = 0; k <= panels; ++k) cuts_.push_back(static_cast<double>(k) / panels);
        const QuadratureRule rule = composite_gauss_legendre(cuts_, transcendental_points);
        nodes_ = rule.nodes;
        weights_ = rule.weights;
    }
}

const FieldBasis& ShapeIntegrals::basis(const Factor& f) const
{
    switch (f.kind) {
        case Factor::Kind::axial:
            return axial_;
        case Factor::Kind::flap:
        case Factor::Kind::flap_coupling:
            return flap_;
        case Factor::Kind::twist:
            return twist_;
        default:
            return transverse_;
    }
}

numeric ShapeIntegrals::integrate(std::vector<Factor> factors, int power)
{
    std::sort(factors.begin(), factors.end());
    auto key = std::make_pair(factors, power);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    const numeric r = exact_ ? exact(factors, power) : quadrature(factors, power);
    cache_.emplace(std::move(key), r);
    return r;
}

numeric ShapeIntegrals::at_tip(const std::vector<Factor>& factors)
{
    numeric product = 1;
    for (const Factor& f : factors) {
        if (f.kind == Factor::Kind::section) {
            throw std::logic_error("integrals: a section distribution at the tip is a run-time value");
        } else if (is_coupling(f)) {  // H_ij(1) = int_0^1 phi_i' phi_j' dxi
            const Factor::Kind field = f.kind == Factor::Kind::coupling ? Factor::Kind::transverse : Factor::Kind::flap;
            product *= integrate({{field, f.i, 0, 1}, {field, f.j, 0, 1}}, 0);
        } else if (exact_) {
            const int n = basis(f).intervals();
            product *= ex_to<numeric>(piece(f, numeric(n - 1, n), 1).subs(xi_ == 1));
        } else {
            const Jet<double> j = basis(f).at(f.i, 1.0);
            product *= numeric(f.deriv == 0 ? j.v : f.deriv == 1 ? j.d1 : j.d2);
        }
    }
    return product;
}

ex ShapeIntegrals::piece(const Factor& f, const numeric& lo, const numeric& hi)
{
    const FieldBasis& b = basis(f);
    const int k = b.interval_of(((lo + hi) / 2).to_double());
    auto key = std::make_pair(f, k);
    if (auto it = pieces_.find(key); it != pieces_.end()) return it->second;
    ex p;
    if (!is_coupling(f)) {
        p = b.piece<ex>(f.i, k, xi_).diff(xi_, f.deriv).expand();
    } else {
        // H_ij on interval k: its value at the interval start plus the running integral inside it. The starts
        // are kept, each from the one before it: summed afresh for every interval they cost O(Ny^3) generation
        // (BSIM at Ny = 64: 20 s). Exact rationals, so the sum's order does not change the result.
        const int n = b.intervals();
        int known = k;  // the latest interval whose start is kept (0 starts at 0)
        while (known > 0 && coupling_starts_.find({f, known}) == coupling_starts_.end()) --known;
        numeric start = known == 0 ? numeric(0) : coupling_starts_.at({f, known});
        for (int s = known; s < k; ++s) {
            const ex prod = b.piece<ex>(f.i, s, xi_).diff(xi_) * b.piece<ex>(f.j, s, xi_).diff(xi_);
            start += integrate_polynomial(prod, xi_, numeric(s, n), numeric(s + 1, n));
            coupling_starts_.emplace(std::make_pair(f, s + 1), start);
        }
        const ex prod = (b.piece<ex>(f.i, k, xi_).diff(xi_) * b.piece<ex>(f.j, k, xi_).diff(xi_)).expand();
        ex running = 0;
        const numeric x0(k, n);
        for (int d = prod.ldegree(xi_); d <= prod.degree(xi_); ++d) {
            const ex c = prod.coeff(xi_, d);
            running += c * (pow(xi_, d + 1) - pow(x0, d + 1)) / (d + 1);
        }
        p = (start + running).expand();
    }
    pieces_.emplace(std::move(key), p);
    return p;
}

const std::vector<numeric>& ShapeIntegrals::piece_coefficients(const Factor& f, std::size_t interval)
{
    const numeric &lo = breaks_[interval], &hi = breaks_[interval + 1];
    const FieldBasis& b = basis(f);
    const int k = b.interval_of(((lo + hi) / 2).to_double());
    auto key = std::make_pair(f, k);
    if (auto it = coefficients_.find(key); it != coefficients_.end()) return it->second;
    const ex p = piece(f, lo, hi);
    std::vector<numeric> c;
    if (!p.is_zero()) {
        c.resize(static_cast<std::size_t>(p.degree(xi_)) + 1);
        for (int d = 0; d <= p.degree(xi_); ++d) {
            const ex cd = p.coeff(xi_, d);
            if (!is_a<numeric>(cd)) throw std::logic_error("integrals: non-numeric coefficient " + ex_to_string(cd));
            c[static_cast<std::size_t>(d)] = ex_to<numeric>(cd);
        }
    }
    return coefficients_.emplace(std::move(key), std::move(c)).first->second;
}

bool ShapeIntegrals::overlaps(const std::vector<Factor>& factors)
{
    if (!exact_) return true;  // AMM's modes vanish on no interval
    for (std::size_t s = 0; s + 1 < breaks_.size(); ++s)
        if (std::all_of(factors.begin(), factors.end(),
                        [&](const Factor& f) { return !piece_coefficients(f, s).empty(); }))
            return true;
    return false;
}

numeric ShapeIntegrals::exact(const std::vector<Factor>& factors, int power)
{
    // Dense coefficient vectors in xi, multiplied by convolution: GiNaC's expand of the same products costs
    // ten times more, and order full needs 10^4 of them.
    numeric sum = 0;
    for (std::size_t s = 0; s + 1 < breaks_.size(); ++s) {
        std::vector<numeric> prod(static_cast<std::size_t>(power) + 1, 0);
        prod.back() = 1;
        for (const Factor& f : factors) {
            const std::vector<numeric>& p = piece_coefficients(f, s);
            if (p.empty()) {
                prod.clear();
                break;
            }
            std::vector<numeric> next(prod.size() + p.size() - 1, 0);
            for (std::size_t i = 0; i < prod.size(); ++i) {
                if (prod[i].is_zero()) continue;
                for (std::size_t j = 0; j < p.size(); ++j)
                    if (!p[j].is_zero()) next[i + j] += prod[i] * p[j];
            }
            prod = std::move(next);
        }
        const numeric &lo = breaks_[s], &hi = breaks_[s + 1];
        numeric lo_power = lo, hi_power = hi;  // lo^(d+1), hi^(d+1)
        for (std::size_t d = 0; d < prod.size(); ++d) {
            if (!prod[d].is_zero()) sum += prod[d] * (hi_power - lo_power) / static_cast<int>(d + 1);
            lo_power *= lo;
            hi_power *= hi;
        }
    }
    return sum;
}

const std::vector<double>& ShapeIntegrals::values(const Factor& f)
{
    if (auto it = node_values_.find(f); it != node_values_.end()) return it->second;
    std::vector<double> v(nodes_.size());
    if (!is_coupling(f)) {
        const FieldBasis& b = basis(f);
        for (std::size_t q = 0; q < nodes_.size(); ++q) {
            const Jet<double> j = b.at(f.i, nodes_[q]);
            v[q] = f.deriv == 0 ? j.v : f.deriv == 1 ? j.d1 : j.d2;
        }
    } else {
        // H_ij at each node: whole panels so far plus a Gauss rule on [panel start, node].
        const QuadratureRule rule = gauss_legendre(transcendental_points);
        const int per_panel = transcendental_points;
        const int panels = static_cast<int>(nodes_.size()) / per_panel;
        const FieldBasis& b = basis(f);
        auto slope_product = [&](double x) { return b.at(f.i, x).d1 * b.at(f.j, x).d1; };
        double whole = 0.0;
        for (int p = 0; p < panels; ++p) {
            const double a = static_cast<double>(p) / panels;
            for (int g = 0; g < per_panel; ++g) {
                const std::size_t q = static_cast<std::size_t>(p * per_panel + g);
                const double width = nodes_[q] - a;
                double part = 0.0;
                for (int r = 0; r < per_panel; ++r)
                    part += rule.weights[r] * width * slope_product(a + rule.nodes[r] * width);
                v[q] = whole + part;
            }
            double full = 0.0;
            for (int r = 0; r < per_panel; ++r)
                full += rule.weights[r] / panels * slope_product(a + rule.nodes[r] / panels);
            whole += full;
        }
    }
    return node_values_.emplace(f, std::move(v)).first->second;
}

numeric ShapeIntegrals::quadrature(const std::vector<Factor>& factors, int power)
{
    std::vector<const std::vector<double>*> columns;
    for (const Factor& f : factors) columns.push_back(&values(f));
    double sum = 0.0, magnitude = 0.0;
    for (std::size_t q = 0; q < nodes_.size(); ++q) {
        double term = weights_[q] * std::pow(nodes_[q], power);
        for (const auto* c : columns) term *= (*c)[q];
        sum += term;
        magnitude += std::abs(term);
    }
    // An integral that cancels to round-off of its integrand's own size is zero (orthogonal modes): emitted
    // as 1e-17, it would be a coefficient and make M look dense.
    if (std::abs(sum) <= cancellation_bound * magnitude) return 0;
    return numeric(sum);
}

}  // namespace hubbeam::gen
