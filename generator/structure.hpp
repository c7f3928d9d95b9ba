// Stage "specialise": the structure of a variant's equations that the runtime's linear algebra chooses
// from: which entries of M are zero, constant or state-dependent, and Q as a constant matrix times a
// vector of state monomials (so that a constant M^-1 can be folded in once per run).
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

namespace hubbeam::gen {

/// M's pattern, row-major, one character per entry: '0' structurally zero, 'c' free of every state symbol,
/// 'v' depends on the coordinates q.
std::string mass_pattern(const std::vector<GiNaC::ex>& M, const std::vector<GiNaC::symbol>& q);

/// Q = F m: m the distinct state monomials of Q (the constant monomial 1 included where Q has a
/// state-free term), F[i*K + k] the coefficient of m_k in Q_i, free of the state.
struct TermMatrix {
    std::vector<GiNaC::ex> terms;   // m, length K
    std::vector<GiNaC::ex> matrix;  // F, nq x K, row-major
};
TermMatrix term_matrix(const std::vector<GiNaC::ex>& Q, const std::vector<GiNaC::symbol>& state);

}  // namespace hubbeam::gen
