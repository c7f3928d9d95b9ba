// Eigen's LU and Cholesky factorizations of dense matrices, compiled in factorizations.cpp alone: a file that includes
// this header calls them there instead of compiling them afresh, 1 to 5 s of each such file's compile time
// (docs/performance.md, "Set-up"). They stay Eigen's classes, used as before; only where they are compiled changes.
#pragma once

#include <Eigen/Dense>

extern template class Eigen::PartialPivLU<Eigen::MatrixXd>;
extern template class Eigen::PartialPivLU<Eigen::MatrixXcd>;
// LLT's compute is a member template: its instance for a plain matrix (M.llt(), LLT<MatrixXd>(M)).
extern template Eigen::LLT<Eigen::MatrixXd>& Eigen::LLT<Eigen::MatrixXd>::compute(
    const Eigen::EigenBase<Eigen::MatrixXd>&);
