// Stage "specialise": the structure of a variant's equations that the runtime's linear algebra chooses
// from: which entries of M are zero, constant or state-dependent, and Q as a constant matrix times a
// vector of state monomials (so that a constant M^-1 can be folded in once per run).
#pragma once

#include <string>
#include <vector>

#include "poly.hpp"

namespace hubbeam::gen {

/// M's pattern, row-major, one character per entry: '0' structurally zero, 'c' free of every variable,
/// 'v' depends on the coordinates (variable indices q).
std::string mass_pattern(const std::vector<Poly>& M, const std::vector<int>& q);

/// Q = F m: m the distinct state monomials of Q (the constant monomial 1 included where Q has a
/// state-free term), in reading order (by degree, then earlier variables first), and F[i*K + k] the
/// coefficient of m_k in Q_i, free of the state.
struct TermMatrix {
    std::vector<Poly> terms;   // m, length K, each one monomial with coefficient 1
    std::vector<Poly> matrix;  // F, nq x K, row-major, each free of the variables
};
TermMatrix term_matrix(const std::vector<Poly>& Q, std::size_t parameter_count);

}  // namespace hubbeam::gen
