// The tests' eigen-solvers (eigen_oracles.hpp): Eigen's, instantiated here once.
#include "eigen_oracles.hpp"

#include <Eigen/Eigenvalues>

namespace hubbeam::test {

namespace {

int options(bool with_vectors)
{
    return with_vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly;
}

/// A symmetric solver's values, and its vectors if they were computed.
template <class Solver>
SymmetricEigen symmetric_of(const Solver& solver, bool with_vectors)
{
    SymmetricEigen out;
    out.converged = solver.info() == Eigen::Success;
    out.values = solver.eigenvalues();
    if (with_vectors) out.vectors = solver.eigenvectors();
    return out;
}

}  // namespace

GeneralEigen general_eigen(const Eigen::MatrixXd& A, bool with_vectors)
{
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(A, with_vectors);
    GeneralEigen out;
    out.values = solver.eigenvalues();
    if (with_vectors) out.vectors = solver.eigenvectors();
    return out;
}

SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& A, bool with_vectors)
{
    return symmetric_of(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, options(with_vectors)), with_vectors);
}

SymmetricEigen generalized_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, bool with_vectors)
{
    return symmetric_of(Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(K, M, options(with_vectors)),
                        with_vectors);
}

HermitianEigen hermitian_eigen(const Eigen::MatrixXcd& H)
{
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> solver(H);
    return {solver.eigenvalues(), solver.eigenvectors()};
}

}  // namespace hubbeam::test
