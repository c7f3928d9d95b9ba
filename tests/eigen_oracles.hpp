// Eigen's eigen-solvers for the tests' oracles, compiled in eigen_oracles.cpp alone: each solver's templates took 10
// to 15 s to compile in every test file that used one. The tests' own, apart from the library's
// runtime/src/linalg, so that an oracle shares no code of hubbeam's with what it checks.
#pragma once

#include <Eigen/Dense>

namespace hubbeam::test {

/// A general real matrix's eigenvalues and, if asked, eigenvectors (Eigen's EigenSolver).
struct GeneralEigen {
    Eigen::VectorXcd values;
    Eigen::MatrixXcd vectors;  // empty unless asked for
};
GeneralEigen general_eigen(const Eigen::MatrixXd& A, bool with_vectors = true);

/// A symmetric A's eigenvalues, ascending, and if asked its eigenvectors (Eigen's SelfAdjointEigenSolver, reading the
/// lower triangle), or the symmetric-definite pencil K x = lambda M x's (GeneralizedSelfAdjointEigenSolver);
/// converged is false where the solver's iteration did not converge.
struct SymmetricEigen {
    Eigen::VectorXd values;
    Eigen::MatrixXd vectors;  // empty unless asked for
    bool converged = false;
};
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& A, bool with_vectors = true);
SymmetricEigen generalized_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, bool with_vectors = true);

/// A Hermitian H's eigenvalues, ascending, and eigenvectors (SelfAdjointEigenSolver).
struct HermitianEigen {
    Eigen::VectorXd values;
    Eigen::MatrixXcd vectors;
};
HermitianEigen hermitian_eigen(const Eigen::MatrixXcd& H);

}  // namespace hubbeam::test
