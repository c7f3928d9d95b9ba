// Polynomials in the run-time variables with parameter coefficients: arithmetic, derivatives, and reading and
// writing GiNaC expressions.
#include "poly.hpp"

#include <sstream>
#include <stdexcept>

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

/// c += scale * d, dropping numbers that cancel.
void accumulate(Coefficient& c, const Coefficient& d, const numeric& scale)
{
    for (const auto& [pe, number] : d) {
        auto [it, added] = c.emplace(pe, scale * number);
        if (!added) {
            it->second += scale * number;
            if (it->second.is_zero()) c.erase(it);
        }
    }
}

std::string str(const ex& e)
{
    std::ostringstream s;
    s << e;
    return s.str();
}

}  // namespace

bool Poly::has(int v) const
{
    for (const auto& entry : terms_)
        if (entry.first[static_cast<std::size_t>(v)] != 0) return true;
    return false;
}

void Poly::add(const Exponents& monomial, const Coefficient& c, const numeric& scale)
{
    if (c.empty() || scale.is_zero()) return;
    auto [it, added] = terms_.emplace(monomial, Coefficient{});
    accumulate(it->second, c, scale);
    if (it->second.empty()) terms_.erase(it);
}

Poly Poly::diff(int v) const
{
    Poly d;
    const auto i = static_cast<std::size_t>(v);
    for (const auto& [e, c] : terms_) {
        if (e[i] == 0) continue;
        Exponents lower = e;
        --lower[i];
        d.add(lower, c, e[i]);
    }
    return d;
}

Poly Poly::times(int v) const
{
    Poly p;
    for (const auto& [e, c] : terms_) {
        Exponents higher = e;
        ++higher[static_cast<std::size_t>(v)];
        p.terms_.emplace(std::move(higher), c);
    }
    return p;
}

Poly& Poly::operator+=(const Poly& p)
{
    for (const auto& [e, c] : p.terms_) add(e, c, 1);
    return *this;
}

Poly& Poly::operator-=(const Poly& p)
{
    for (const auto& [e, c] : p.terms_) add(e, c, -1);
    return *this;
}

Poly Poly::of_degree(const std::vector<int>& which, int d) const
{
    Poly p;
    for (const auto& [e, c] : terms_) {
        int degree = 0;
        for (int v : which) degree += e[static_cast<std::size_t>(v)];
        if (degree == d) p.terms_.emplace(e, c);
    }
    return p;
}

PolyReader::PolyReader(const std::vector<symbol>& parameters, const std::vector<symbol>& variables)
    : np_(parameters.size()), nv_(variables.size())
{
    for (std::size_t i = 0; i < parameters.size(); ++i) index_[parameters[i]] = {true, i};
    for (std::size_t i = 0; i < variables.size(); ++i) index_[variables[i]] = {false, i};
}

Poly PolyReader::operator()(const ex& value) const
{
    const ex e = value.expand();
    Poly p;
    if (e.is_zero()) return p;
    for (const ex& term : is_a<add>(e) ? e : lst{e}) {
        numeric number = 1;
        Exponents pe(np_), ve(nv_);
        for (const ex& f : is_a<mul>(term) ? term : lst{term}) {
            if (is_a<numeric>(f)) {
                if (!ex_to<numeric>(f).is_real()) throw std::invalid_argument("poly: non-real number " + str(f));
                number *= ex_to<numeric>(f);
                continue;
            }
            ex base = f;
            int n = 1;
            if (is_a<power>(f)) {
                if (!is_a<numeric>(f.op(1)) || !ex_to<numeric>(f.op(1)).is_integer())
                    throw std::invalid_argument("poly: non-integer power " + str(f));
                base = f.op(0);
                n = ex_to<numeric>(f.op(1)).to_int();
            }
            const auto it = is_a<symbol>(base) ? index_.find(ex_to<symbol>(base)) : index_.end();
            if (it == index_.end()) throw std::invalid_argument("poly: not a polynomial in the inputs: " + str(f));
            const auto [is_parameter, i] = it->second;
            if (!is_parameter && n < 0) throw std::invalid_argument("poly: negative power of a variable " + str(f));
            (is_parameter ? pe : ve)[i] += n;
        }
        p.add(ve, Coefficient{{pe, number}});
    }
    return p;
}

ex to_ex(const Poly& p, const std::vector<symbol>& parameters, const std::vector<symbol>& variables)
{
    exvector sum;
    for (const auto& [ve, c] : p.terms()) {
        ex monomial = 1;
        for (std::size_t i = 0; i < ve.size(); ++i) monomial *= pow(variables[i], ve[i]);
        for (const auto& [pe, number] : c) {
            ex term = number * monomial;
            for (std::size_t i = 0; i < pe.size(); ++i) term *= pow(parameters[i], pe[i]);
            sum.push_back(term);
        }
    }
    return add(sum);
}

}  // namespace hubbeam::gen
