// Small dense matrix-vector products (small_product.hpp).
#include "dynamics/small_product.hpp"

#include "generated_abi.h"  // HUBBEAM_WIDE_KERNEL

namespace hubbeam {

namespace {

typedef double lanes __attribute__((vector_size(32)));
typedef double lanes_at __attribute__((vector_size(32), aligned(8), may_alias));

/// B groups of four rows of small_product, each with its own sum, over the columns at once.
template <int B>
[[gnu::always_inline]] inline void rows_of(const double* a, int rows, int cols, const double* x, double alpha,
                                           bool add, double* out)
{
    lanes sum[B];
    for (int b = 0; b < B; ++b) sum[b] = lanes{0.0, 0.0, 0.0, 0.0};
    for (int j = 0; j < cols; ++j, a += rows)
        for (int b = 0; b < B; ++b) sum[b] += *reinterpret_cast<const lanes_at*>(a + 4 * b) * x[j];
    for (int b = 0; b < B; ++b) {
        lanes_at& to = *reinterpret_cast<lanes_at*>(out + 4 * b);
        to = (add ? to : lanes{0.0, 0.0, 0.0, 0.0}) + sum[b] * alpha;
    }
}

/// Eigen's matrix-vector product below 128 columns (GeneralMatrixVector.h) sums each row from 0.0 over the columns
/// in order, then multiplies by alpha and adds: so does this, four rows a register, compiled for AVX2 as well (AVX2
/// without fused multiply-adds rounds as SSE2 does). Eigen's dispatch cost 380 instructions a call on the main
/// scene's 8 x 8 and 16 x 16 products.
HUBBEAM_WIDE_KERNEL void product_by_rows(const double* a, int rows, int cols, const double* x, double alpha, bool add,
                                         double* out)
{
    int i = 0;
    for (; i + 16 <= rows; i += 16) rows_of<4>(a + i, rows, cols, x, alpha, add, out + i);
    switch ((rows - i) / 4) {
        case 3: rows_of<3>(a + i, rows, cols, x, alpha, add, out + i); break;
        case 2: rows_of<2>(a + i, rows, cols, x, alpha, add, out + i); break;
        case 1: rows_of<1>(a + i, rows, cols, x, alpha, add, out + i); break;
        default: break;
    }
    for (i += (rows - i) / 4 * 4; i < rows; ++i) {
        double sum = 0.0;
        for (int j = 0; j < cols; ++j) sum += a[j * rows + i] * x[j];
        out[i] = (add ? out[i] : 0.0) + sum * alpha;
    }
}

}  // namespace

void small_product(const Eigen::MatrixXd& A, const double* x, double alpha, bool add, double* out)
{
    const auto rows = A.rows(), cols = A.cols();
    // Eigen takes one row as a dot product, and 128 columns and more in blocks: its own call keeps its bits there.
    if (rows == 1 || cols >= 128) {
        Eigen::Map<Eigen::VectorXd> to(out, rows);
        const Eigen::Map<const Eigen::VectorXd> by(x, cols);
        if (add) to.noalias() += alpha * A * by;
        else to.noalias() = alpha * A * by;
        return;
    }
    product_by_rows(A.data(), static_cast<int>(rows), static_cast<int>(cols), x, alpha, add, out);
}

}  // namespace hubbeam
