// Shape functions of docs/model.md section 4: the clamped root, the two BSIM constructions spanning one space
// (paper eq. 41-43), the AMM roots and modes, and the smoothness of the piecewise bases at their breakpoints.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "basis/basis.hpp"
#include "eigen_oracles.hpp"

using namespace hubbeam;

namespace {

/// Largest |phi_i| over a grid of [0, 1]: a member that vanished everywhere would pass the clamp vacuously.
double max_abs(const FieldBasis& f, int i)
{
    double r = 0.0;
    for (int j = 0; j <= 200; ++j) r = std::max(r, std::abs(f.at(i, j / 200.0).v));
    return r;
}

/// u_x1(0) = 0 for every axial member.
void check_axial_clamp(Method method, int nx)
{
    const FieldBasis f(method, Field::axial, nx, SplineBasis::open);
    for (int i = 0; i < nx; ++i) {
        INFO("axial count " << nx << ", member " << i);
        CHECK(std::abs(f.at(i, 0.0).v) < 1e-14);
        CHECK(max_abs(f, i) > 1e-3);
    }
}

/// u_y(0) = u_y'(0) = 0 for every transverse member (slope relative to the member's own scale).
void check_transverse_clamp(Method method, int ny, SplineBasis spline = SplineBasis::paper)
{
    const FieldBasis f(method, Field::transverse, ny, spline);
    for (int i = 0; i < ny; ++i) {
        INFO("transverse count " << ny << ", member " << i);
        const Jet<double> root = f.at(i, 0.0);
        const double scale = max_abs(f, i);
        CHECK(scale > 1e-3);
        CHECK(std::abs(root.v) < 1e-13 * scale);
        CHECK(std::abs(root.d1) < 1e-12 * scale * (i + 1) * ny);  // slopes grow with the member's wavenumber
    }
}

/// Values of all members of f at the points (one row per point).
Eigen::MatrixXd sample(const FieldBasis& f, const std::vector<double>& xi)
{
    Eigen::MatrixXd P(xi.size(), f.size());
    for (std::size_t r = 0; r < xi.size(); ++r)
        for (int i = 0; i < f.size(); ++i) P(r, i) = f.at(i, xi[r]).v;
    return P;
}

/// Relative residual of the least-squares fit of the columns of P by the columns of O.
double fit_residual(const Eigen::MatrixXd& O, const Eigen::MatrixXd& P)
{
    const Eigen::MatrixXd c = O.colPivHouseholderQr().solve(P);
    return (O * c - P).norm() / P.norm();
}

/// The textbook clamped-free mode cos - cosh + g (sin - sinh) (docs/model.md section 4), accurate for small b.
double textbook_mode(double b, double xi)
{
    const double g = -(std::cos(b) + std::cosh(b)) / (std::sin(b) + std::sinh(b));
    const double z = b * xi;
    return std::cos(z) - std::cosh(z) + g * (std::sin(z) - std::sinh(z));
}

}  // namespace

TEST_CASE("every basis satisfies the clamped root", "[basis]")
{
    SECTION("AMM")
    {
        for (int n = 1; n <= 8; ++n) check_axial_clamp(Method::amm, n);
        for (int n : {1, 4, 10, 20}) check_transverse_clamp(Method::amm, n);
    }
    SECTION("FEM")
    {
        for (int n = 1; n <= 8; ++n) check_axial_clamp(Method::fem, n);
        for (int n : {2, 4, 8, 16}) check_transverse_clamp(Method::fem, n);
    }
    SECTION("BIM")
    {
        for (int n = 1; n <= 8; ++n) check_axial_clamp(Method::bim, n);
        for (int n : {1, 2, 4, 8, 12}) check_transverse_clamp(Method::bim, n);
    }
    SECTION("BSIM, paper basis (eq. 41)")
    {
        for (int n = 3; n <= 10; ++n) check_axial_clamp(Method::bsim, n);
        for (int n : {4, 5, 8, 16}) check_transverse_clamp(Method::bsim, n, SplineBasis::paper);
    }
    SECTION("BSIM, open-knot basis")
    {
        for (int n : {2, 3, 4, 8, 16}) check_transverse_clamp(Method::bsim, n, SplineBasis::open);
    }
}

TEST_CASE("BSIM paper and open-knot transverse bases span the same space", "[basis]")
{
    std::vector<double> xi;
    for (int j = 0; j <= 400; ++j) xi.push_back(j / 400.0);

    SECTION("each basis fits the other to round-off")
    {
        for (int n = 3; n <= 9; ++n) {
            INFO("n = " << n << " intervals");
            const auto bsim = [n](SplineBasis s) { return FieldBasis(Method::bsim, Field::transverse, n + 1, s); };
            const Eigen::MatrixXd P = sample(bsim(SplineBasis::paper), xi), O = sample(bsim(SplineBasis::open), xi);
            CHECK(O.colPivHouseholderQr().rank() == n + 1);
            CHECK(P.colPivHouseholderQr().rank() == n + 1);
            CHECK(fit_residual(O, P) < 1e-12);
            CHECK(fit_residual(P, O) < 1e-12);
        }
    }
    SECTION("end members carry the end values and slopes (eq. 43)")
    {
        for (int n = 3; n <= 9; ++n) {
            INFO("n = " << n << " intervals");
            // Root members of eq. 41, dropped from the transverse basis: phi_-1(0) = 1, and phi_0 has slope 1 per knot
            // interval (d/deta, eta = n xi): d/dxi = n.
            const Jet<double> root_value = bsim::paper(-1, n, 0, variable(0.0));
            const Jet<double> root_slope = bsim::paper(0, n, 0, variable(0.0));
            CHECK(root_value.v == Approx(1.0).epsilon(1e-14));
            CHECK(std::abs(root_value.d1) < 1e-13);
            CHECK(std::abs(root_slope.v) < 1e-14);
            CHECK(root_slope.d1 == Approx(n).epsilon(1e-14));
            // Tip: phi_n(1) = 1 with zero slope, phi_(n+1) slope 1 per knot interval with zero value, all others vanish
            // with their slopes.
            const FieldBasis f(Method::bsim, Field::transverse, n + 1, SplineBasis::paper);
            for (int i = 0; i <= n; ++i) {
                INFO("member phi_" << i + 1);
                const Jet<double> tip = f.at(i, 1.0);
                CHECK(tip.v == Approx(i == n - 1 ? 1.0 : 0.0).margin(1e-13));
                CHECK(tip.d1 == Approx(i == n ? n : 0.0).margin(1e-12));
            }
        }
    }
}

TEST_CASE("AMM roots and modes", "[basis][amm]")
{
    SECTION("roots of 1 + cos z cosh z = 0")
    {
        const double published[] = {1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349, 14.1371683910};
        for (int i = 1; i <= 5; ++i) CHECK(std::abs(amm::cantilever_root(i) - published[i - 1]) < 1e-9);
        for (int i = 1; i <= 30; ++i) {
            const double z = amm::cantilever_root(i);
            CHECK(std::abs(std::cos(z) + 1.0 / std::cosh(z)) < 1e-14);  // the equation divided by cosh z
            CHECK(std::abs(z - (i - 0.5) * std::numbers::pi) < 0.31);  // the i-th root, not a neighbour
        }
    }
    SECTION("the stable form equals the textbook form where that one is accurate")
    {
        for (int i = 1; i <= 5; ++i) {
            const amm::Mode md = amm::mode(i);
            for (int j = 0; j <= 100; ++j)
                CHECK(std::abs(amm::transverse(md, j / 100.0) - textbook_mode(md.b, j / 100.0)) < 1e-9);
        }
    }
    SECTION("high modes stay bounded")
    {
        const FieldBasis f(Method::amm, Field::transverse, 20);
        double peak = 0.0;
        for (int j = 0; j <= 20000; ++j) peak = std::max(peak, std::abs(f.at(19, j / 20000.0).v));
        CHECK(peak <= 2.01);
        // Normalised clamped-free modes end at |phi(1)| = 2.
        CHECK(std::abs(f.at(19, 1.0).v) == Approx(2.0).epsilon(1e-10));
    }
}

TEST_CASE("piecewise bases are as smooth as their construction", "[basis]")
{
    // Jump of the k-th derivative of member i across the breakpoint between intervals k-1 and k.
    const auto jumps = [](const FieldBasis& f, int i, int k) {
        const double xk = static_cast<double>(k) / f.intervals();
        const Jet<double> left = f.piece(i, k - 1, variable(xk)), right = f.piece(i, k, variable(xk));
        return Eigen::Vector3d(std::abs(right.v - left.v), std::abs(right.d1 - left.d1), std::abs(right.d2 - left.d2));
    };
    SECTION("FEM: C0 axial, C1 transverse with curvature jumps")
    {
        const FieldBasis ax(Method::fem, Field::axial, 6), tr(Method::fem, Field::transverse, 12);
        double max_curvature_jump = 0.0;
        for (int k = 1; k < tr.intervals(); ++k)
            for (int i = 0; i < tr.size(); ++i) {
                const Eigen::Vector3d d = jumps(tr, i, k);
                CHECK(d(0) < 1e-13);
                CHECK(d(1) < 1e-12);
                max_curvature_jump = std::max(max_curvature_jump, d(2));
            }
        CHECK(max_curvature_jump > 1.0);
        for (int k = 1; k < ax.intervals(); ++k)
            for (int i = 0; i < ax.size(); ++i) CHECK(jumps(ax, i, k)(0) < 1e-13);
    }
    SECTION("BSIM: C2 in both constructions and the axial field")
    {
        for (const FieldBasis& f : {FieldBasis(Method::bsim, Field::transverse, 9, SplineBasis::paper),
                                    FieldBasis(Method::bsim, Field::transverse, 9, SplineBasis::open),
                                    FieldBasis(Method::bsim, Field::axial, 9, SplineBasis::open)})
            for (int k = 1; k < f.intervals(); ++k)
                for (int i = 0; i < f.size(); ++i) {
                    const Eigen::Vector3d d = jumps(f, i, k);
                    CHECK(d(0) < 1e-13);
                    CHECK(d(1) < 1e-11);
                    CHECK(d(2) < 1e-9);
                }
    }
}

TEST_CASE("BSIM's transverse mass matrix stays well conditioned as the mesh refines", "[basis]")
{
    // B-splines of one knot spacing form a Riesz basis: the Gram matrix of the uniform translates has eigenvalues
    // between fixed bounds whatever n, once each is scaled by the spacing. Both constructions are fixed combinations
    // of those translates at the ends and the translates themselves inside, so their Gram matrices' condition
    // numbers must tend to a limit as n doubles; a member that shrank with n (an end slope in units of xi, of size
    // 1/n) would make it grow as n^2, four times per doubling.
    const auto condition = [](const FieldBasis& f) {
        const QuadratureRule rule = product_rule(f, f);
        Eigen::MatrixXd G = Eigen::MatrixXd::Zero(f.size(), f.size());
        Eigen::VectorXd phi(f.size());
        for (std::size_t r = 0; r < rule.nodes.size(); ++r) {
            for (int i = 0; i < f.size(); ++i) phi(i) = f.at(i, rule.nodes[r]).v;
            G.noalias() += rule.weights[r] * phi * phi.transpose();
        }
        const Eigen::VectorXd values = test::symmetric_eigen(G, false).values;
        return values.maxCoeff() / values.minCoeff();
    };
    for (const SplineBasis spline : {SplineBasis::paper, SplineBasis::open}) {
        std::vector<double> cond;
        for (const int ny : {8, 16, 32, 64})
            cond.push_back(condition(FieldBasis(Method::bsim, Field::transverse, ny, spline)));
        INFO((spline == SplineBasis::paper ? "paper" : "open")
             << " basis, cond at Ny 8, 16, 32, 64: " << cond[0] << ", " << cond[1] << ", " << cond[2] << ", "
             << cond[3]);
        for (std::size_t k = 1; k < cond.size(); ++k) CHECK(cond[k] <= 1.1 * cond[k - 1]);
        CHECK(cond.back() < 1e3);
    }
}
