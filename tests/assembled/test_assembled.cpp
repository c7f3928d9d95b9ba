// The hand-assembled path (runtime/src/models/assembled/assembled.*, runtime/src/models/fields.cpp) against independent computations and the
// physics of docs/model.md section 7: coefficient matrices, cantilever frequencies, the mass matrix, steady spin,
// energy and Lagrange consistency of the forces, and the beam fields under static tip loads.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <hubbeam/fields.hpp>
#include "eigen_oracles.hpp"
#include "models/assembled/assembled.hpp"
#include "shared_oracles.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double pi = std::numbers::pi;

/// The beam of Kane, Ryan & Banerjee (docs/model.md section 6).
Parameters paper_beam()
{
    Parameters p;
    p.L = 8.0;
    p.S = 7.2968e-5;
    p.I = 8.2189e-9;
    p.rho = 2.7667e3;
    p.E = 6.8952e10;
    p.a = 0.0;
    p.J_oh = 30.0;
    return p;
}

double mass_per_length(const Parameters& p) { return p.rho * p.S; }

/// i-th root of 1 + cos z cosh z = 0 by bisection on cos z + 1/cosh z over [(i-1) pi, i pi]: independent of
/// the Newton iteration in the basis code.
double bisected_root(int i)
{
    double lo = (i - 1) * pi, hi = i * pi;
    const auto f = [](double z) { return std::cos(z) + 1.0 / std::cosh(z); };
    const double f_lo = f(lo);
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) * f_lo > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Non-rotating cantilever frequencies (docs/model.md section 7), rad/s.
double bending_frequency(int i, const Parameters& p)
{
    const double b = bisected_root(i);
    return b * b * std::sqrt(p.E * p.I / (mass_per_length(p) * std::pow(p.L, 4)));
}
double axial_frequency(int i, const Parameters& p) { return (2 * i - 1) * pi / (2.0 * p.L) * std::sqrt(p.E / p.rho); }

/// sqrt of the generalized eigenvalues of (K, M), ascending.
VectorXd frequencies(const MatrixXd& K, const MatrixXd& M)
{
    const test::SymmetricEigen es = test::generalized_eigen(K, M, false);
    REQUIRE(es.converged);
    return es.values.cwiseSqrt();
}

VariantKey make_key(Method method, int nx, int ny, Drive drive = Drive::prescribed, Order order = Order::first,
                    SplineBasis spline = SplineBasis::paper)
{
    return {.method = method, .nx = nx, .ny = ny, .order = order, .drive = drive, .spline = spline, .extras = {}};
}

/// The five transverse discretizations with a representative Ny.
struct Discretization {
    const char* name;
    Method method;
    SplineBasis spline;
    int ny;
};
const Discretization discretizations[] = {{"AMM", Method::amm, SplineBasis::paper, 4},
                                          {"FEM", Method::fem, SplineBasis::paper, 4},
                                          {"BIM", Method::bim, SplineBasis::paper, 4},
                                          {"BSIM paper", Method::bsim, SplineBasis::paper, 4},
                                          {"BSIM open", Method::bsim, SplineBasis::open, 4}};

/// Every variant of d the assembled path serves: both drives, nx in {0, 4}, orders zero and first.
std::vector<VariantKey> assembled_variants(const Discretization& d)
{
    std::vector<VariantKey> keys;
    for (Drive drive : {Drive::prescribed, Drive::torque})
        for (int nx : {0, 4})
            for (Order order : {Order::zero, Order::first})
                keys.push_back(make_key(d.method, nx, d.ny, drive, order, d.spline));
    return keys;
}

/// A random but physically sized state: displacements of centimetres (axial: millimetres), rates of order one.
struct State {
    HubInput u;
    VectorXd q, qd;
};
State random_state(const VariantKey& k, std::mt19937& rng)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    State s;
    s.u = {5.0 * unit(rng), 3.0 * unit(rng), 2.0 * unit(rng)};
    s.q.resize(k.nq());
    s.qd.resize(k.nq());
    for (int i = 0; i < k.nq(); ++i) {
        const FieldKind kind = coordinate_layout(k).field_of(i).kind;
        const bool axial = kind == FieldKind::axial, hub = kind == FieldKind::hub_angle;
        s.q(i) = (hub ? 3.0 : axial ? 1e-3 : 0.2) * unit(rng);
        s.qd(i) = (hub ? 3.0 : axial ? 0.1 : 0.5) * unit(rng);
    }
    return s;
}

MatrixXd mass_of(const Model& model, const State& s)
{
    const int n = model.nq();
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(n, n);
    model.mass(s.u, s.q.data(), M.data());
    return M;
}

VectorXd forces_of(const Model& model, const State& s)
{
    VectorXd Q(model.nq());
    model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
    return Q;
}

/// T = T2 + T1 + T0 split by degree in the rates qd (docs/model.md section 5.4, section 9): scaling the rates
/// by lambda must scale each part by its own power, T_k(lambda qd) = lambda^k T_k(qd), and leave U alone.
/// This is what defines the split, so it holds whichever part the model assigns a term to.
void check_degree_split(const Model& model, const State& s)
{
    const Energy e = model.energy(s.u, s.q.data(), s.qd.data());
    const double scale = std::abs(e.T2) + std::abs(e.T1) + std::abs(e.T0);
    REQUIRE(scale > 0.0);
    for (double lambda : {-1.0, 0.5, 3.0}) {
        INFO("rates scaled by " << lambda);
        const VectorXd qd = lambda * s.qd;
        const Energy l = model.energy(s.u, s.q.data(), qd.data());
        const double margin = 1e-13 * scale * lambda * lambda;
        CHECK(l.T2 == Approx(lambda * lambda * e.T2).epsilon(1e-12).margin(margin));
        CHECK(l.T1 == Approx(lambda * e.T1).epsilon(1e-12).margin(margin));
        CHECK(l.T0 == Approx(e.T0).epsilon(1e-12).margin(margin));
        CHECK(l.U == e.U);
    }
}

/// Stiffness of the B equations at steady spin Omega (prescribed form, A absent, B_dot = 0): -dQ_B/dB,
/// exact by columns since Q_B is linear in B.
MatrixXd spin_stiffness(const Model& model, double omega)
{
    const int n = model.nq();
    State s;
    s.u = {0.0, omega, 0.0};
    s.q = VectorXd::Zero(n);
    s.qd = VectorXd::Zero(n);
    const VectorXd Q0 = forces_of(model, s);
    MatrixXd K(n, n);
    for (int j = 0; j < n; ++j) {
        s.q = VectorXd::Unit(n, j);
        K.col(j) = Q0 - forces_of(model, s);
    }
    return K;
}

/// Relative errors of the first bending frequency over a sequence of Ny.
std::vector<double> bending_errors(Method method, SplineBasis spline, const std::vector<int>& nys)
{
    const Parameters p = paper_beam();
    std::vector<double> err;
    for (int ny : nys) {
        const BeamMatrices c = assemble_matrices(make_key(method, 0, ny, Drive::prescribed, Order::first, spline), p);
        err.push_back(frequencies(c.K2, c.M2)(0) / bending_frequency(1, p) - 1.0);
    }
    return err;
}

/// Relative errors of the first axial frequency over a sequence of Nx.
std::vector<double> axial_errors(Method method, const std::vector<int>& nxs)
{
    const Parameters p = paper_beam();
    std::vector<double> err;
    for (int nx : nxs) {
        const BeamMatrices c = assemble_matrices(make_key(method, nx, 4), p);
        err.push_back(frequencies(c.K1, c.M1)(0) / axial_frequency(1, p) - 1.0);
    }
    return err;
}

/// Errors positive (Rayleigh-Ritz bounds from above) and strictly decreasing.
void check_monotone_from_above(const std::vector<double>& err)
{
    for (std::size_t i = 0; i < err.size(); ++i) {
        INFO("step " << i << ": error " << err[i]);
        CHECK(err[i] > 0.0);
        if (i > 0) CHECK(err[i] < err[i - 1]);
    }
}

}  // namespace

TEST_CASE("coefficient matrices against independent constructions", "[assembled]")
{
    const Parameters p = paper_beam();
    const double m = mass_per_length(p), L = p.L, EI = p.E * p.I, ES = p.E * p.S;

    SECTION("AMM: orthonormal modes give M2 = m L I and K2 = EI/L^3 diag(b_i^4)")
    {
        const BeamMatrices c = assemble_matrices(make_key(Method::amm, 6, 10), p);
        for (int i = 0; i < 10; ++i)
            for (int j = 0; j < 10; ++j) {
                const double b_i = bisected_root(i + 1), b_j = bisected_root(j + 1);
                const double K_ii = EI / (L * L * L) * std::pow(b_i, 4), K_jj = EI / (L * L * L) * std::pow(b_j, 4);
                CHECK(std::abs(c.M2(i, j) - (i == j ? m * L : 0.0)) < 1e-12 * m * L);
                CHECK(std::abs(c.K2(i, j) - (i == j ? K_ii : 0.0)) < 1e-12 * std::sqrt(K_ii * K_jj));
            }
        // Axial sines: int sin^2 = 1/2, stiffness ES/L ((2i-1) pi/2)^2 / 2.
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) {
                const double k_i = (2 * i + 1) * pi / 2, k_j = (2 * j + 1) * pi / 2;
                CHECK(std::abs(c.M1(i, j) - (i == j ? m * L / 2 : 0.0)) < 1e-12 * m * L);
                CHECK(std::abs(c.K1(i, j) - (i == j ? ES / L * k_i * k_i / 2 : 0.0)) < 1e-12 * ES / L * k_i * k_j);
            }
    }
    SECTION("FEM: the classical Hermite and linear element matrices")
    {
        const int n = 3;
        const double l = L / n;
        MatrixXd Me(4, 4), Ke(4, 4);
        Me << 156, 22 * l, 54, -13 * l,
              22 * l, 4 * l * l, 13 * l, -3 * l * l,
              54, 13 * l, 156, -22 * l,
              -13 * l, -3 * l * l, -22 * l, 4 * l * l;
        Ke << 12, 6 * l, -12, 6 * l,
              6 * l, 4 * l * l, -6 * l, 2 * l * l,
              -12, -6 * l, 12, -6 * l,
              6 * l, 2 * l * l, -6 * l, 4 * l * l;
        Me *= m * l / 420.0;
        Ke *= EI / (l * l * l);
        // Global DOFs (w_0, theta_0, ..., w_n, theta_n) with theta = dw/dx; ours drop node 0 and use L theta.
        MatrixXd M_full = MatrixXd::Zero(2 * n + 2, 2 * n + 2), K_full = M_full;
        for (int e = 0; e < n; ++e) {
            M_full.block(2 * e, 2 * e, 4, 4) += Me;
            K_full.block(2 * e, 2 * e, 4, 4) += Ke;
        }
        VectorXd scale(2 * n);
        for (int i = 0; i < 2 * n; ++i) scale(i) = i % 2 == 0 ? 1.0 : 1.0 / L;
        const MatrixXd M2 = scale.asDiagonal() * M_full.bottomRightCorner(2 * n, 2 * n) * scale.asDiagonal();
        const MatrixXd K2 = scale.asDiagonal() * K_full.bottomRightCorner(2 * n, 2 * n) * scale.asDiagonal();

        MatrixXd M1_full = MatrixXd::Zero(n + 1, n + 1), K1_full = M1_full;
        for (int e = 0; e < n; ++e) {
            M1_full.block(e, e, 2, 2) += m * l / 6.0 * (MatrixXd(2, 2) << 2, 1, 1, 2).finished();
            K1_full.block(e, e, 2, 2) += ES / l * (MatrixXd(2, 2) << 1, -1, -1, 1).finished();
        }

        const BeamMatrices c = assemble_matrices(make_key(Method::fem, n, 2 * n), p);
        CHECK((c.M2 - M2).norm() < 1e-13 * M2.norm());
        CHECK((c.K2 - K2).norm() < 1e-13 * K2.norm());
        CHECK((c.M1 - M1_full.bottomRightCorner(n, n)).norm() < 1e-13 * M1_full.norm());
        CHECK((c.K1 - K1_full.bottomRightCorner(n, n)).norm() < 1e-13 * K1_full.norm());
    }
    SECTION("C, D and H(L) as the double integrals of their definitions")
    {
        Parameters q = p;
        q.a = 1.5;
        const VariantKey key = make_key(Method::bim, 3, 5);
        const FieldBasis tr = key.transverse_basis();
        const BeamMatrices c = assemble_matrices(key, q);
        // H(x) = int_0^x Phi_y'^T Phi_y' ds with an inner rule on [0, x]: C = int m H dx, D = int m x H dx.
        const QuadratureRule rule = gauss_legendre(12);  // exact: H has degree <= 11, x H degree <= 12 < 24
        const auto H = [&](double x) {
            MatrixXd h = MatrixXd::Zero(5, 5);
            for (int k = 0; k < 12; ++k) {
                const double s = x * rule.nodes[k];
                VectorXd d(5);
                for (int i = 0; i < 5; ++i) d(i) = tr.at(i, s / q.L).d1 / q.L;
                h += x * rule.weights[k] * d * d.transpose();
            }
            return h;
        };
        MatrixXd C = MatrixXd::Zero(5, 5), D = C;
        for (int k = 0; k < 12; ++k) {
            const double x = q.L * rule.nodes[k];
            C += m * q.L * rule.weights[k] * H(x);
            D += m * q.L * rule.weights[k] * x * H(x);
        }
        CHECK((c.C - C).norm() < 1e-12 * C.norm());
        CHECK((c.D - D).norm() < 1e-12 * D.norm());
        CHECK((c.G - (q.a * C + D)).norm() < 1e-12 * D.norm());
        const MatrixXd H_L = BeamFields(key, q).H_L();
        CHECK((H_L - H(q.L)).norm() < 1e-12 * H_L.norm());
        // J_ob = int_0^L m (a + x)^2 dx by the same rule (exact for degree 2), not the closed form the code uses.
        double J_ob = 0.0;
        for (int k = 0; k < 12; ++k) J_ob += m * q.L * rule.weights[k] * std::pow(q.a + q.L * rule.nodes[k], 2);
        CHECK(c.J_ob == Approx(J_ob).epsilon(1e-13));
    }
}

TEST_CASE("non-rotating cantilever frequencies", "[assembled][physics]")
{
    const Parameters p = paper_beam();
    // docs/model.md section 7's numbers for this beam.
    REQUIRE(bending_frequency(1, p) == Approx(2.911).epsilon(1e-3));
    REQUIRE(axial_frequency(1, p) == Approx(980.0).epsilon(1e-3));

    SECTION("AMM: exact for every mode")
    {
        const BeamMatrices c = assemble_matrices(make_key(Method::amm, 8, 8), p);
        const VectorXd bending = frequencies(c.K2, c.M2), axial = frequencies(c.K1, c.M1);
        for (int i = 0; i < 8; ++i) {
            CHECK(bending(i) == Approx(bending_frequency(i + 1, p)).epsilon(1e-9));
            CHECK(axial(i) == Approx(axial_frequency(i + 1, p)).epsilon(1e-9));
        }
    }
    SECTION("FEM: h^4 in bending, h^2 axially")
    {
        const std::vector<double> e = bending_errors(Method::fem, SplineBasis::paper, {4, 8, 10, 12, 16, 20});
        check_monotone_from_above(e);
        CHECK(std::log2(e[2] / e[5]) == Approx(4.0).margin(0.1));  // Ny 10 -> 20 halves the element
        CHECK(e[5] < 1e-6);
        const std::vector<double> a = axial_errors(Method::fem, {5, 10, 20, 40});
        check_monotone_from_above(a);
        CHECK(std::log2(a[2] / a[3]) == Approx(2.0).margin(0.05));
        // Linear elements: omega_h = omega (1 + (k h)^2 / 24 + ...), k h = pi / (2 Nx).
        CHECK(a[3] == Approx(std::pow(pi / 80.0, 2) / 24.0).epsilon(1e-2));
    }
    SECTION("BIM: spectral convergence down to round-off")
    {
        const std::vector<double> e = bending_errors(Method::bim, SplineBasis::paper, {2, 3, 4, 5, 6});
        check_monotone_from_above(e);
        for (std::size_t i = 1; i < e.size(); ++i) CHECK(e[i] < e[i - 1] / 10.0);
        CHECK(std::abs(bending_errors(Method::bim, SplineBasis::paper, {12})[0]) < 1e-8);
        const std::vector<double> a = axial_errors(Method::bim, {1, 2, 3, 4, 5});
        check_monotone_from_above(a);
        CHECK(std::abs(axial_errors(Method::bim, {8})[0]) < 1e-10);
    }
    SECTION("BSIM: h^4 in bending, h^6 axially, the same in both constructions")
    {
        for (SplineBasis spline : {SplineBasis::paper, SplineBasis::open}) {
            INFO("spline basis " << to_string(spline));
            const std::vector<double> e = bending_errors(Method::bsim, spline, {4, 6, 9, 12, 16, 17});
            check_monotone_from_above(e);
            CHECK(std::log2(e[2] / e[5]) == Approx(4.0).margin(0.1));  // n = 8 -> 16 intervals
            CHECK(e[4] < 1e-6);
        }
        const std::vector<double> a = axial_errors(Method::bsim, {4, 6, 10});  // n_x = 2, 4, 8
        check_monotone_from_above(a);
        CHECK(std::log2(a[1] / a[2]) == Approx(6.0).margin(0.3));
        for (int ny = 4; ny <= 12; ++ny) {
            const BeamMatrices cp = assemble_matrices(make_key(Method::bsim, 0, ny), p);
            const BeamMatrices co =
                assemble_matrices(make_key(Method::bsim, 0, ny, Drive::prescribed, Order::first, SplineBasis::open), p);
            const VectorXd fp = frequencies(cp.K2, cp.M2), fo = frequencies(co.K2, co.M2);
            for (int i = 0; i < 4; ++i) CHECK(fo(i) == Approx(fp(i)).epsilon(1e-9));
        }
    }
    SECTION("one space, one answer: clamped cubics by FEM, BIM and BSIM")
    {
        // Ny = 2 spans the cubics with u(0) = u'(0) = 0 in FEM (one element), BIM (degree 3), BSIM (one interval).
        const double fem = bending_errors(Method::fem, SplineBasis::paper, {2})[0];
        CHECK(bending_errors(Method::bim, SplineBasis::paper, {2})[0] == Approx(fem).epsilon(1e-9));
        CHECK(bending_errors(Method::bsim, SplineBasis::open, {2})[0] == Approx(fem).epsilon(1e-9));
    }
}

TEST_CASE("assembled mass matrix is symmetric positive definite", "[assembled]")
{
    const Parameters p = paper_beam();
    std::mt19937 rng(20240917);
    for (const Discretization& d : discretizations) {
        SECTION(d.name)
        {
            for (const VariantKey& key : assembled_variants(d)) {
                INFO(key.name());
                const auto model = make_assembled_model(key, p);
                for (int trial = 0; trial < 5; ++trial) {
                    const MatrixXd M = mass_of(*model, random_state(key, rng));
                    CHECK(M == M.transpose());
                    CHECK(test::symmetric_eigen(M, false).values(0) > 0.0);
                    CHECK(Eigen::LLT<MatrixXd>(M).info() == Eigen::Success);
                }
            }
        }
    }
}

TEST_CASE("steady spin: stiffening in first order, loss of stability in zero order", "[assembled][physics]")
{
    const Parameters p = paper_beam();
    const double omega1 = bending_frequency(1, p);
    for (const Discretization& d : discretizations) {
        SECTION(d.name)
        {
            const int ny = d.ny + 2;
            const auto model = [&](Order order) {
                return make_assembled_model(make_key(d.method, 0, ny, Drive::prescribed, order, d.spline), p);
            };
            const auto first = model(Order::first), zero = model(Order::zero);
            State rest;
            rest.q = rest.qd = VectorXd::Zero(ny);
            const MatrixXd M2 = mass_of(*first, rest);
            // First order: K2 + Omega^2 (G - M2); the in-plane frequency rises with the spin.
            double previous = 0.0;
            for (double omega : {0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0}) {
                INFO("Omega = " << omega);
                const double f = frequencies(spin_stiffness(*first, omega), M2)(0);
                CHECK(f > previous);
                previous = f;
            }
            // Zero order: K2 - Omega^2 M2 is positive definite below the first bending frequency only.
            const auto min_eigenvalue = [&](double omega) {
                return test::generalized_eigen(spin_stiffness(*zero, omega), M2, false).values(0);
            };
            CHECK(min_eigenvalue(0.99 * omega1) > 0.0);
            CHECK(min_eigenvalue(1.01 * omega1) < 0.0);
        }
    }
    SECTION("in-plane = out-of-plane^2 - Omega^2 against the rotating-cantilever table")
    {
        // First flapwise frequency of a uniform rotating cantilever, zero hub radius, in units of
        // sqrt(EI/(m L^4)) at spin lambda = Omega L^2 sqrt(m/EI) = 0..12 (Wright, Smith, Thresher & Wang 1982;
        // Hodges & Rutkowski 1981).
        const double flap[] = {3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495, 7.3604,
                               8.2996, 9.2568, 10.2257, 11.2023, 12.1843, 13.1702};
        const double unit = std::sqrt(p.E * p.I / (mass_per_length(p) * std::pow(p.L, 4)));
        const auto model = make_assembled_model(make_key(Method::bim, 0, 12), p);
        State rest;
        rest.q = rest.qd = VectorXd::Zero(12);
        const MatrixXd M2 = mass_of(*model, rest);
        for (int lambda = 0; lambda <= 12; ++lambda) {
            const double in_plane = frequencies(spin_stiffness(*model, lambda * unit), M2)(0) / unit;
            CHECK(std::sqrt(in_plane * in_plane + lambda * lambda) == Approx(flap[lambda]).margin(1e-4));
        }
    }
}

TEST_CASE("energy and momentum agree with the mass matrix", "[assembled]")
{
    const Parameters p = paper_beam();
    std::mt19937 rng(7);
    for (const Discretization& d : discretizations) {
        SECTION(d.name)
        {
            for (int nx : {0, 4})
                for (Order order : {Order::zero, Order::first}) {
                    {
                        const VariantKey key = make_key(d.method, nx, d.ny, Drive::torque, order, d.spline);
                        INFO(key.name());
                        const auto model = make_assembled_model(key, p);
                        for (int trial = 0; trial < 5; ++trial) {
                            const State s = random_state(key, rng);
                            const MatrixXd M = mass_of(*model, s);
                            const Energy e = model->energy(s.u, s.q.data(), s.qd.data());
                            // theta_dot is one of the rates: T = 1/2 qd^T M qd, all of it of degree 2.
                            CHECK(e.kinetic() == Approx(0.5 * s.qd.dot(M * s.qd)).epsilon(1e-12));
                            check_degree_split(*model, s);
                            CHECK(model->momentum(s.u, s.q.data(), s.qd.data()) ==
                                  Approx(M.row(0).dot(s.qd)).epsilon(1e-12));
                        }
                    }
                    {
                        const VariantKey key = make_key(d.method, nx, d.ny, Drive::prescribed, order, d.spline);
                        INFO(key.name());
                        const auto model = make_assembled_model(key, p);
                        for (int trial = 0; trial < 5; ++trial) {
                            const State s = random_state(key, rng);
                            const Energy e = model->energy(s.u, s.q.data(), s.qd.data());
                            CHECK(e.T2 == Approx(0.5 * s.qd.dot(mass_of(*model, s) * s.qd)).epsilon(1e-12));
                            // T is quadratic in theta_dot: a unit-step central difference is dT/dtheta_dot.
                            HubInput up = s.u, down = s.u;
                            up.theta_dot += 1.0;
                            down.theta_dot -= 1.0;
                            const double dT = 0.5 * (model->energy(up, s.q.data(), s.qd.data()).kinetic() -
                                                     model->energy(down, s.q.data(), s.qd.data()).kinetic());
                            CHECK(model->momentum(s.u, s.q.data(), s.qd.data()) == Approx(dT).epsilon(1e-10));
                            // T1 linear in the flexible rates, T0 free of them.
                            check_degree_split(*model, s);
                        }
                    }
                }
        }
    }
}

TEST_CASE("forces follow from the energy by Lagrange's equations", "[assembled]")
{
    const Parameters p = [] {
        Parameters q = paper_beam();
        q.a = 0.7;  // exercise G = a C + D
        return q;
    }();
    std::mt19937 rng(11);
    for (const Discretization& d : discretizations) {
        SECTION(d.name)
        {
            for (const VariantKey& key : assembled_variants(d)) {
                INFO(key.name());
                const auto model = make_assembled_model(key, p);
                for (int trial = 0; trial < 3; ++trial) {
                    const State s = random_state(key, rng);
                    const VectorXd Q = forces_of(*model, s), Q_ref = test::lagrange_forces(*model, s);
                    CHECK((Q - Q_ref).lpNorm<Eigen::Infinity>() <= 1e-9 * Q_ref.lpNorm<Eigen::Infinity>());
                }
            }
        }
    }
}

TEST_CASE("hand-assembled model interface", "[assembled]")
{
    const Parameters p = paper_beam();
    const auto prescribed = make_assembled_model(make_key(Method::fem, 0, 4), p);
    const auto torque = make_assembled_model(make_key(Method::fem, 4, 4, Drive::torque), p);
    CHECK(std::string(prescribed->source()) == "assembled");
    CHECK(prescribed->mass_is_constant());
    CHECK_FALSE(torque->mass_is_constant());
    CHECK(torque->nq() == 9);
    CHECK_THROWS_AS(make_assembled_model(make_key(Method::amm, 0, 4, Drive::torque, Order::full), p),
                    std::invalid_argument);
    CHECK_THROWS_AS(make_assembled_model(make_key(Method::fem, 0, 3), p), std::invalid_argument);
    CHECK_THROWS_AS(assemble_matrices(make_key(Method::bsim, 0, 3), p), std::invalid_argument);
}

TEST_CASE("beam fields under static tip loads", "[fields][physics]")
{
    const Parameters p = paper_beam();
    const double L = p.L, EI = p.E * p.I, ES = p.E * p.S;
    const double P = 2.0, F = 500.0;  // tip force across and along the beam (N)
    // Euler-Bernoulli cantilever: u_y = P x^2 (3L - x) / (6 EI), moment P (L - x); bar: u_x1 = F x / ES.
    const auto uy_exact = [&](double x) { return P * x * x * (3 * L - x) / (6 * EI); };
    // Foreshortening -1/2 int (u_y')^2 dx = -P^2 L^5 / (15 EI^2).
    const double ux2_tip = -P * P * std::pow(L, 5) / (15 * EI * EI);

    struct Polynomial {
        const char* name;
        VariantKey key;
    };
    // Every one of these spaces contains the exact (cubic, linear) static solutions.
    const Polynomial cases[] = {
        {"FEM", make_key(Method::fem, 3, 4)},
        {"BIM", make_key(Method::bim, 1, 2)},
        {"BSIM paper", make_key(Method::bsim, 3, 4)},
        {"BSIM open", make_key(Method::bsim, 3, 2, Drive::prescribed, Order::first, SplineBasis::open)},
    };
    for (const Polynomial& c : cases) {
        SECTION(c.name)
        {
            const BeamMatrices m = assemble_matrices(c.key, p);
            const VectorXd B = m.K2.llt().solve(P * BeamFields(c.key, p).Phi_y_L().transpose());
            const VectorXd A = m.K1.llt().solve(F * BeamFields(c.key, p).Phi_x_L().transpose());
            const BeamFields fields(c.key, p);
            for (int j = 0; j <= 16; ++j) {
                const double x = L * j / 16.0;
                INFO("x = " << x);
                CHECK(fields.uy(B.data(), x) == Approx(uy_exact(x)).margin(1e-10 * uy_exact(L)));
                CHECK(fields.bending_moment(B.data(), x) == Approx(P * (L - x)).margin(1e-8 * P * L));
                CHECK(fields.ux1(A.data(), x) == Approx(F * x / ES).margin(1e-10 * F * L / ES));
                CHECK(fields.axial_force(A.data(), x) == Approx(F).epsilon(1e-9));
            }
            const Tip tip = fields.tip(A.data(), B.data());
            CHECK(tip.uy == Approx(P * L * L * L / (3 * EI)).epsilon(1e-10));
            CHECK(tip.ux1 == Approx(F * L / ES).epsilon(1e-10));
            CHECK(tip.ux == Approx(F * L / ES + ux2_tip).epsilon(1e-10));
        }
    }
    SECTION("AMM converges to the tip deflection")
    {
        double previous = 1.0;
        for (int ny : {2, 4, 8, 16}) {
            const VariantKey key = make_key(Method::amm, 0, ny);
            const BeamMatrices m = assemble_matrices(key, p);
            const VectorXd B = m.K2.llt().solve(P * BeamFields(key, p).Phi_y_L().transpose());
            const double tip = BeamFields(key, p).tip(nullptr, B.data()).uy;
            const double err = std::abs(tip / (P * L * L * L / (3 * EI)) - 1.0);
            INFO("Ny = " << ny << ": error " << err);
            CHECK(err < previous);
            previous = err;
        }
        CHECK(previous < 1e-4);
    }
    SECTION("no axial coordinates, and abscissas off the beam")
    {
        const VariantKey key = make_key(Method::fem, 0, 4);
        const BeamFields fields(key, p);
        const double B[4] = {0.01, 0.002, 0.03, 0.004};
        const Tip tip = fields.tip(nullptr, B);
        CHECK(tip.ux1 == 0.0);
        CHECK(tip.ux < 0.0);
        CHECK(tip.uy == Approx(0.03).epsilon(1e-14));  // the tip node's deflection DOF
        CHECK(fields.axial_force(nullptr, 1.0) == 0.0);
        CHECK(fields.ux1(nullptr, 1.0) == 0.0);
        CHECK_THROWS_AS(fields.uy(B, -0.1), std::out_of_range);
        CHECK_THROWS_AS(fields.uy(B, L + 0.1), std::out_of_range);
    }
}
