// The bordered band LU of gauss4's Newton matrices in mass form (runtime/src/dynamics/band_lu.*) against Eigen's dense
// LU, on banded matrices whose rows and columns were shuffled and bordered by dense ones, as a free hub's are.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "dynamics/band_lu.hpp"

using namespace hubbeam;

namespace {

/// A random n x n matrix of half-bandwidth p in a shuffled order, its first `border` rows and columns (after the
/// shuffle) dense, made diagonally dominant enough to be well conditioned; its pattern as row-major flags.
Eigen::MatrixXd shuffled_band(int n, int p, int border, std::mt19937& random, std::vector<char>& pattern)
{
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Eigen::MatrixXd band = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - p); j <= std::min(n - 1, i + p); ++j) band(i, j) = value(random);
    for (int b = 0; b < border; ++b)
        for (int j = 0; j < n; ++j) band(b, j) = value(random), band(j, b) = value(random);
    band.diagonal().array() += 2.0 * p + 2.0 * border;
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), random);
    Eigen::MatrixXd A(n, n);
    pattern.assign(static_cast<std::size_t>(n) * n, 0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            A(i, j) = band(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(j)]);
            pattern[static_cast<std::size_t>(i) * n + j] = A(i, j) != 0.0;
        }
    return A;
}

}  // namespace

TEST_CASE("the bordered band LU solves shuffled band matrices with dense rows as a dense LU does", "[structure]")
{
    std::mt19937 random(7);
    for (const int border : {0, 1, 2}) {
        for (const int n : {40, 66, 130}) {
            std::vector<char> pattern;
            const Eigen::MatrixXd A = shuffled_band(n, 3, border, random, pattern);
            BorderedBandLU lu(pattern, n);
            INFO("n = " << n << ", border " << border << ": planned half-widths " << lu.lower() << " and " << lu.upper()
                        << ", border " << lu.border());
            // The plan undoes the shuffle: the band found is as narrow as the one hidden (reverse Cuthill-McKee
            // finds it exactly for a band; the border is found by its rows' fullness).
            CHECK(lu.border() == border);
            CHECK(lu.lower() <= 3);
            CHECK(lu.upper() <= 3);
            CHECK(lu.factor_flops() < 0.25 * 2.0 / 3.0 * n * n * n);  // where gauss4 takes it over the dense LU
            REQUIRE(lu.factor([&](int i, int j) { return A(i, j); }));
            const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
            const Eigen::MatrixXd expected = A.partialPivLu().solve(B);
            for (int c = 0; c < 3; ++c) {
                Eigen::VectorXd x = B.col(c);
                lu.solve(x.data());
                CHECK((x - expected.col(c)).norm() <= 1e-12 * expected.col(c).norm());
            }
        }
    }
}

TEST_CASE("the bordered band LU refuses a singular matrix", "[structure]")
{
    std::mt19937 random(11);
    std::vector<char> pattern;
    Eigen::MatrixXd A = shuffled_band(30, 2, 1, random, pattern);
    A.row(5).setZero();  // a zero row: singular whether it falls in the band or the border
    BorderedBandLU lu(pattern, 30);
    CHECK_FALSE(lu.factor([&](int i, int j) { return A(i, j); }));
}
