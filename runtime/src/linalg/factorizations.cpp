// Eigen's LU and Cholesky factorizations, the one file that compiles them (factorizations.hpp).
#include "linalg/factorizations.hpp"

template class Eigen::PartialPivLU<Eigen::MatrixXd>;
template class Eigen::PartialPivLU<Eigen::MatrixXcd>;
template Eigen::LLT<Eigen::MatrixXd>& Eigen::LLT<Eigen::MatrixXd>::compute(const Eigen::EigenBase<Eigen::MatrixXd>&);
