// Eigen's eigen-solvers, the one file that compiles them (eigen_solvers.hpp).
#include "linalg/eigen_solvers.hpp"

#include <Eigen/Eigenvalues>

template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>& Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>::compute(
    const Eigen::EigenBase<Eigen::MatrixXcd>&, int);

namespace hubbeam {

namespace {

int options(bool with_vectors)
{
    return with_vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly;
}

/// A solver's values, and its vectors if they were computed, as Pairs.
template <class Pairs, class Solver>
Pairs pairs_of(const Solver& solver, bool with_vectors)
{
    Pairs out;
    out.converged = solver.info() == Eigen::Success;
    out.values = solver.eigenvalues();
    if (with_vectors) out.vectors = solver.eigenvectors();
    return out;
}

}  // namespace

EigenPairs eigen_pairs(const Eigen::MatrixXd& A, bool with_vectors)
{
    return pairs_of<EigenPairs>(Eigen::EigenSolver<Eigen::MatrixXd>(A, with_vectors), with_vectors);
}

SymmetricPairs symmetric_pairs(const Eigen::MatrixXd& A, bool with_vectors)
{
    return pairs_of<SymmetricPairs>(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, options(with_vectors)),
                                    with_vectors);
}

SymmetricPairs symmetric_pairs(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, bool with_vectors)
{
    return pairs_of<SymmetricPairs>(
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(A, B, options(with_vectors)), with_vectors);
}

HermitianPairs hermitian_pairs(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B)
{
    return pairs_of<HermitianPairs>(Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd>(A, B), true);
}

}  // namespace hubbeam
