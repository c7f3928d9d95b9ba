// Eigen's eigen-solvers behind plain functions of Eigen's matrices, compiled in eigen_solvers.cpp alone: each
// solver's templates take 10 to 15 s to compile, once here instead of once in every file that solves an
// eigenproblem (docs/performance.md, "Set-up"). The results are the solvers' own, value for value.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

namespace hubbeam {

/// The eigenvalues of a general real matrix and, if asked, its eigenvectors (Eigen's EigenSolver: each vector of
/// unit length, in the values' order); converged is false where the QR iteration did not converge.
struct EigenPairs {
    Eigen::VectorXcd values;
    Eigen::MatrixXcd vectors;  // empty unless asked for
    bool converged = false;
};
EigenPairs eigen_pairs(const Eigen::MatrixXd& A, bool with_vectors = true);

/// The eigenvalues, ascending, and if asked the eigenvectors of the symmetric A (Eigen's SelfAdjointEigenSolver,
/// which reads A's lower triangle), or of the symmetric-definite pencil A x = lambda B x (its
/// GeneralizedSelfAdjointEigenSolver: the vectors B-orthonormal).
struct SymmetricPairs {
    Eigen::VectorXd values;
    Eigen::MatrixXd vectors;  // empty unless asked for
    bool converged = false;
};
SymmetricPairs symmetric_pairs(const Eigen::MatrixXd& A, bool with_vectors = true);
SymmetricPairs symmetric_pairs(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, bool with_vectors = true);

/// The same for a Hermitian pencil A x = lambda B x, B positive definite: real values, complex vectors.
struct HermitianPairs {
    Eigen::VectorXd values;
    Eigen::MatrixXcd vectors;
    bool converged = false;
};
HermitianPairs hermitian_pairs(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B);

}  // namespace hubbeam

// models/mode_kinds.hpp's separate_repeated, a template, solves with SelfAdjointEigenSolver<MatrixXcd> in each file
// that splits repeated modes: a file that includes this header too takes it from eigen_solvers.cpp.
extern template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>::compute(const Eigen::EigenBase<Eigen::MatrixXcd>&, int);
