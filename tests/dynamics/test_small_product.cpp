// gauss4's small matrix-vector products (runtime/src/dynamics/small_product.*) against Eigen's own, bit for bit: the
// stepper's results must not depend on which of the two computed its Newton corrections.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>

#include "dynamics/small_product.hpp"

using namespace hubbeam;

TEST_CASE("small products give Eigen's bits, whatever the size, scale and start", "[steppers]")
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    // Every size up to 70 rows and columns (four-row groups, their remainders, the single row Eigen takes as a dot
    // product), and 130 columns, beyond which Eigen blocks its columns.
    for (int rows = 1; rows <= 70; ++rows)
        for (int cols : {1, 2, 3, 5, 8, 13, 16, 33, 64, 70, 130}) {
            Eigen::MatrixXd A(rows, cols);
            for (Eigen::Index k = 0; k < A.size(); ++k) A.data()[k] = value(random);
            Eigen::VectorXd x(cols), start(rows);
            for (double& v : x) v = value(random) * 1e3;
            for (double& v : start) v = value(random);
            const double alpha = value(random);

            Eigen::VectorXd expected = start, got = start;
            expected.noalias() += alpha * A * x;
            small_product(A, x.data(), alpha, true, got.data());
            INFO("rows " << rows << ", cols " << cols << ", added");
            CHECK(std::memcmp(expected.data(), got.data(), sizeof(double) * rows) == 0);

            expected.noalias() = A * x;
            got = start;
            small_product(A, x.data(), 1.0, false, got.data());
            INFO("rows " << rows << ", cols " << cols << ", assigned");
            CHECK(std::memcmp(expected.data(), got.data(), sizeof(double) * rows) == 0);
        }
}

TEST_CASE("a small product's row summing to zero is +0, as Eigen's", "[steppers]")
{
    // -0.0 + 0.0 is +0.0: Eigen's sums start from 0.0, so a row of negative zeros gives +0, which a CSV prints as 0.
    Eigen::MatrixXd A(5, 2);
    A.setConstant(-0.0);
    const double x[2] = {1.0, 1.0};
    double out[5];
    small_product(A, x, 1.0, false, out);
    for (double v : out) CHECK(!std::signbit(v));
}
