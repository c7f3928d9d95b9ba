// Mass-matrix pattern and the term-matrix form of the forces.
#include "structure.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

bool has_any(const ex& e, const std::vector<symbol>& symbols)
{
    for (const symbol& s : symbols)
        if (e.has(s)) return true;
    return false;
}

}  // namespace

std::string mass_pattern(const std::vector<ex>& M, const std::vector<symbol>& q)
{
    std::string pattern;
    for (const ex& m : M) pattern += m.is_zero() ? '0' : has_any(m, q) ? 'v' : 'c';
    return pattern;
}

TermMatrix term_matrix(const std::vector<ex>& Q, const std::vector<symbol>& state)
{
    // Each term of each Q_i splits into a state monomial and a state-free coefficient.
    std::vector<std::map<ex, ex, ex_is_less>> rows(Q.size());
    std::map<ex, std::size_t, ex_is_less> index;
    TermMatrix t;
    for (std::size_t i = 0; i < Q.size(); ++i) {
        const ex e = Q[i].expand();
        if (e.is_zero()) continue;
        for (const ex& term : is_a<add>(e) ? e : lst{e}) {
            ex monomial = 1, coefficient = 1;
            for (const ex& factor : is_a<mul>(term) ? term : lst{term})
                (has_any(factor, state) ? monomial : coefficient) *= factor;
            if (index.emplace(monomial, t.terms.size()).second) t.terms.push_back(monomial);
            rows[i][monomial] += coefficient;
        }
    }
    // Reading order, as the emitter's: by degree, then A1 before A2 before B1 (larger exponents of earlier
    // symbols first).
    const auto exponents = [&](const ex& m) {
        std::vector<int> e;
        for (const symbol& s : state) e.push_back(m.degree(s));
        return e;
    };
    std::stable_sort(t.terms.begin(), t.terms.end(), [&](const ex& x, const ex& y) {
        const std::vector<int> ex_ = exponents(x), ey = exponents(y);
        const int dx = std::accumulate(ex_.begin(), ex_.end(), 0), dy = std::accumulate(ey.begin(), ey.end(), 0);
        return dx != dy ? dx < dy : ex_ > ey;
    });
    for (std::size_t k = 0; k < t.terms.size(); ++k) index[t.terms[k]] = k;
    const std::size_t K = t.terms.size();
    t.matrix.assign(Q.size() * K, 0);
    for (std::size_t i = 0; i < Q.size(); ++i)
        for (const auto& [monomial, coefficient] : rows[i]) t.matrix[i * K + index.at(monomial)] = coefficient;
    return t;
}

}  // namespace hubbeam::gen
