// Small dense matrix-vector products with Eigen's arithmetic and without its dispatch: gauss4's Newton corrections.
#pragma once

#include <Eigen/Dense>

namespace hubbeam {

/// out = init + alpha (A x), init being out's values (add) or zero: the bits Eigen's `out.noalias() += alpha * A * x`
/// and `out.noalias() = A * x` give, at a fraction of their cost below 128 columns.
void small_product(const Eigen::MatrixXd& A, const double* x, double alpha, bool add, double* out);

}  // namespace hubbeam
