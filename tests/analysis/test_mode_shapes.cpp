// The blade's mode shapes and ElastoDyn's polynomials (mode_shapes.hpp) against oracles that share no code with
// them: an exact sum-1 polynomial recovered by the fit, the clamped-free beam's closed-form first mode, and its
// least-squares fit computed here by the normal equations.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <hubbeam/make_model.hpp>
#include <hubbeam/mode_shapes.hpp>
#include <hubbeam/scene.hpp>

using namespace hubbeam;

namespace {

/// n abscissae equally spaced from 0 to 1.
std::vector<double> abscissae(int n)
{
    std::vector<double> xi;
    for (int i = 0; i < n; ++i) xi.push_back(static_cast<double>(i) / (n - 1));
    return xi;
}

/// The clamped-free uniform beam's first mode at xi = x/L, 1 at the tip: cosh(b x) - cos(b x) - sigma (sinh(b x) -
/// sin(b x)), b L = 1.8751040687, sigma = (cosh bL + cos bL) / (sinh bL + sin bL).
double cantilever_mode(double xi)
{
    const double bl = 1.8751040687119611664453082410782141625701117335310699882454;
    const double sigma = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
    const auto raw = [&](double x) {
        return std::cosh(bl * x) - std::cos(bl * x) - sigma * (std::sinh(bl * x) - std::sin(bl * x));
    };
    return raw(xi) / raw(1.0);
}

/// The oracle's fit: the constrained least squares by a Lagrange multiplier and the normal equations, in long
/// double (KKT system [[2 V^T V, 1], [1^T, 0]] [c; mu] = [2 V^T phi; 1], V_ik = xi_i^k).
std::vector<double> lagrange_fit(const std::vector<double>& xi, const std::vector<double>& phi)
{
    using Matrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
    Matrix K = Matrix::Zero(6, 6);
    Eigen::Matrix<long double, Eigen::Dynamic, 1> rhs = Eigen::Matrix<long double, Eigen::Dynamic, 1>::Zero(6);
    for (std::size_t i = 0; i < xi.size(); ++i)
        for (int j = 0; j < 5; ++j) {
            const long double vj = std::pow(static_cast<long double>(xi[i]), j + 2);
            for (int k = 0; k < 5; ++k) K(j, k) += 2.0L * vj * std::pow(static_cast<long double>(xi[i]), k + 2);
            rhs(j) += 2.0L * vj * phi[i];
        }
    for (int j = 0; j < 5; ++j) K(j, 5) = K(5, j) = 1.0L;
    rhs(5) = 1.0L;
    const Eigen::Matrix<long double, Eigen::Dynamic, 1> c = K.fullPivLu().solve(rhs);
    return {static_cast<double>(c(0)), static_cast<double>(c(1)), static_cast<double>(c(2)),
            static_cast<double>(c(3)), static_cast<double>(c(4))};
}

/// The polynomial sum_k c[k - 2] xi^k.
double polynomial(const std::array<double, 5>& c, double xi)
{
    double p = 0.0;
    for (int k = 2; k <= 6; ++k) p += c[static_cast<std::size_t>(k - 2)] * std::pow(xi, k);
    return p;
}

}  // namespace

TEST_CASE("the mode shape fit recovers a polynomial of sum 1 and divides the shape by its tip value",
          "[modes][elastodyn]")
{
    const std::array<double, 5> exact = {0.3, -1.2, 2.5, -1.4, 0.8};  // sums to 1
    const std::vector<double> xi = abscissae(201);
    for (const double scale : {1.0, -3.7, 1e-6}) {  // an eigenvector's size and sign are arbitrary
        INFO("the shape times " << scale);
        std::vector<double> phi;
        for (const double x : xi) phi.push_back(scale * polynomial(exact, x));
        const PolynomialFit fit = fit_mode_shape(xi, phi);
        for (std::size_t k = 0; k < 5; ++k) CHECK(std::abs(fit.coefficients[k] - exact[k]) < 1e-10);
        CHECK(fit.residual < 1e-13);
    }
    // Not a polynomial of the family (x alone): the fit is off by its residual, the RMS of p - phi computed here.
    std::vector<double> phi;
    for (const double x : xi) phi.push_back(x);
    const PolynomialFit fit = fit_mode_shape(xi, phi);
    double squares = 0.0;
    for (std::size_t i = 0; i < xi.size(); ++i) squares += std::pow(polynomial(fit.coefficients, xi[i]) - phi[i], 2);
    CHECK(fit.residual == Approx(std::sqrt(squares / static_cast<double>(xi.size()))).epsilon(1e-12));
    CHECK(fit.residual > 1e-3);
}

TEST_CASE("the clamped-free beam's first mode fits with a residual below 1e-3, coefficients summing to 1",
          "[modes][elastodyn]")
{
    const std::vector<double> xi = abscissae(201);
    std::vector<double> phi;
    for (const double x : xi) phi.push_back(cantilever_mode(x));
    const PolynomialFit fit = fit_mode_shape(xi, phi);
    CHECK(fit.residual < 1e-3);
    CHECK(std::accumulate(fit.coefficients.begin(), fit.coefficients.end(), 0.0) == Approx(1.0).margin(1e-12));
    // The same minimum as the Lagrange multiplier's normal equations (another formulation, in long double).
    const std::vector<double> oracle = lagrange_fit(xi, phi);
    for (std::size_t k = 0; k < 5; ++k) CHECK(fit.coefficients[k] == Approx(oracle[k]).margin(1e-8));
}

TEST_CASE("the mode shape fit refuses samples it cannot fit", "[modes][elastodyn]")
{
    const std::vector<double> xi = abscissae(11), zero(11, 0.0);
    CHECK_THROWS_AS(fit_mode_shape(xi, zero), std::invalid_argument);  // 0 at the tip: nothing to normalise by
    CHECK_THROWS_AS(fit_mode_shape({0.0, 0.5, 1.0}, {0.0, 0.3, 1.0}), std::invalid_argument);
    CHECK_THROWS_AS(fit_mode_shape(abscissae(10), std::vector<double>(11, 1.0)), std::invalid_argument);
    std::vector<double> no_tip = xi;
    no_tip.back() = 0.99;
    CHECK_THROWS_AS(fit_mode_shape(no_tip, xi), std::invalid_argument);
}

TEST_CASE("a uniform blade's flap 1 and edge 1 at rest are the clamped-free beam's first mode", "[modes][elastodyn]")
{
    // AMM's flapwise and in-plane bases are the clamped-free modes, so its shapes are the closed form's but for
    // round-off; FEM's Hermite cubics (Nz = 16: 8 elements) differ by their discretization error.
    for (const char* method : {"amm", "fem"}) {
        INFO(method);
        const bool fem = std::string(method) == "fem";
        const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/tests/scenes/uniform_blade.toml",
                                       {{"discretization.method", method},
                                        {"discretization.ny", fem ? "16" : "4"},
                                        {"discretization.nz", fem ? "16" : "4"}});
        const auto model = make_model(scene.key(), scene.parameters, scene.source);
        const ElastoDynShapes shapes = elastodyn_mode_shapes(*model, scene.parameters, 0.0);
        CHECK(shapes.flap1.name == "flap 1");
        CHECK(shapes.flap2.name == "flap 2");
        CHECK(shapes.edge1.name == "edge 1");
        // The shape error of 8 cubic elements: cubic Hermite interpolation's, h^4 / 384 max|phi^(4)| with h = 1/8
        // (of L) and phi^(4) = (bL)^4 phi, |phi| <= 1 (7.9e-6 of the tip), twice for the eigenvector's own error
        // of the same order; AMM's, round-off of its Gauss-Legendre integrals.
        const double bl = 1.8751040687;
        const double shape_tolerance = fem ? 2.0 * std::pow(1.0 / 8.0, 4) / 384.0 * std::pow(bl, 4) : 1e-9;
        for (const BladeModeShape* s : {&shapes.flap1, &shapes.edge1}) {
            INFO(s->name);
            REQUIRE(s->xi.size() == s->phi.size());
            REQUIRE(s->xi.back() == 1.0);
            CHECK(s->phi.back() == Approx(1.0).margin(1e-14));  // normalised to the tip
            double worst = 0.0;
            for (std::size_t i = 0; i < s->xi.size(); ++i)
                worst = std::max(worst, std::abs(s->phi[i] - cantilever_mode(s->xi[i])));
            CHECK(worst < shape_tolerance);
        }
        // flap 1 at 1.87510407^2 sqrt(EI_flap / (m L^4)).
        const Parameters& p = scene.parameters;
        CHECK(shapes.flap1.rad_s ==
              Approx(std::pow(1.8751040687, 2) * std::sqrt(p.E * p.I_flap / (p.rho * p.S * std::pow(p.L, 4))))
                  .epsilon(fem ? 1e-5 : 1e-9));
    }
}

TEST_CASE("a blade without flapwise coordinates has no flap mode shapes", "[modes][elastodyn]")
{
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/spinup_omega4.toml");
    const auto model = make_model(scene.key(), scene.parameters, scene.source);
    CHECK_THROWS_AS(elastodyn_mode_shapes(*model, scene.parameters, 0.0), std::invalid_argument);
}
