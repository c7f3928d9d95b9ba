// Mass-matrix pattern and the term-matrix form of the forces.
#include "structure.hpp"

#include <algorithm>
#include <map>

#include "monomial_order.hpp"

namespace hubbeam::gen {

std::string mass_pattern(const std::vector<Poly>& M, const std::vector<int>& q)
{
    std::string pattern;
    for (const Poly& m : M)
        pattern += m.is_zero() ? '0' : std::any_of(q.begin(), q.end(), [&](int v) { return m.has(v); }) ? 'v' : 'c';
    return pattern;
}

TermMatrix term_matrix(const std::vector<Poly>& Q, std::size_t parameter_count)
{
    std::vector<Exponents> monomials;
    for (const Poly& q : Q)
        for (const auto& entry : q.terms()) monomials.push_back(entry.first);
    sort_reading(monomials);  // the emitter's order of temporaries, so that m_k reads as the other kernels do
    monomials.erase(std::unique(monomials.begin(), monomials.end()), monomials.end());
    std::map<Exponents, std::size_t> index;
    TermMatrix t;
    const Coefficient one{{Exponents(parameter_count), GiNaC::numeric(1)}};
    for (const Exponents& e : monomials) {
        index.emplace(e, t.terms.size());
        t.terms.emplace_back().add(e, one);
    }
    const std::size_t K = monomials.size();
    t.matrix.resize(Q.size() * K);
    for (std::size_t i = 0; i < Q.size(); ++i)
        for (const auto& [e, c] : Q[i].terms())
            t.matrix[i * K + index.at(e)].add(Exponents(e.size()), c);
    return t;
}

}  // namespace hubbeam::gen
