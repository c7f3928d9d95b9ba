// Every method's model against an oracle that shares no code with model/ or runtime/: the shape functions written
// here from the textbook formulas (Hermite cubics on elements of length L/n, Bernstein polynomials, clamped cubic
// B-splines by Cox-de Boor, the clamped-free modes in their textbook form), their integrals by Gauss-Legendre rules
// computed here, and closed-form beam solutions (the static tip deflection under the hub's angular acceleration,
// the steady axial stretch of a spinning beam, the roots of 1 + cos z cosh z). The shared basis (model/basis) feeds
// the generator, the hand-assembled path and the other tests' oracles alike, so only a check like these sees a
// fault in it. The models are read through their public interface only: M from mass(), K, G, S and M3 from
// differences of forces() (Q is exactly quadratic in the hub rate and linear in q, qd at order first).
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include "eigen_oracles.hpp"
#include "gauss_legendre.hpp"

using namespace hubbeam;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// ---- Shape functions, in x in [0, L] ----------------------------------------------------------------------------

/// A member's value and first two derivatives in x.
struct Value {
    double f = 0.0, d1 = 0.0, d2 = 0.0;
};

/// One field's basis: the members at x (never asked at a breakpoint) and the breakpoints between which every
/// member is smooth.
struct Basis {
    int size = 0;
    std::vector<double> breaks;
    std::function<std::vector<Value>(double)> at;
};

std::vector<double> uniform_breaks(double L, int n)
{
    std::vector<double> b;
    for (int k = 0; k <= n; ++k) b.push_back(L * k / n);
    return b;
}

/// Hermite cubics on n elements of length h = L/n, root node removed: at each node a deflection and a slope
/// coordinate. The slope coordinate is du_y/dxi = L du_y/dx (so that M and K do not scale with L), which makes its
/// shape function the textbook slope function h (s - 2 s^2 + s^3) divided by L.
Basis hermite(double L, int n)
{
    const double h = L / n;
    return {2 * n, uniform_breaks(L, n), [=](double x) {
                std::vector<Value> v(static_cast<std::size_t>(2 * n));
                const int e = std::min(static_cast<int>(x / h), n - 1);
                const double s = x / h - e;
                const Value N1{1 - 3 * s * s + 2 * s * s * s, (-6 * s + 6 * s * s) / h, (-6 + 12 * s) / (h * h)};
                const Value N2{h * (s - 2 * s * s + s * s * s), 1 - 4 * s + 3 * s * s, (-4 + 6 * s) / h};
                const Value N3{3 * s * s - 2 * s * s * s, (6 * s - 6 * s * s) / h, (6 - 12 * s) / (h * h)};
                const Value N4{h * (-s * s + s * s * s), -2 * s + 3 * s * s, (-2 + 6 * s) / h};
                const auto slope = [L](Value N) { return Value{N.f / L, N.d1 / L, N.d2 / L}; };
                if (e >= 1) {  // the element's left node e is node e of the mesh, coordinates 2(e-1), 2(e-1)+1
                    v[static_cast<std::size_t>(2 * (e - 1))] = N1;
                    v[static_cast<std::size_t>(2 * (e - 1) + 1)] = slope(N2);
                }
                v[static_cast<std::size_t>(2 * e)] = N3;
                v[static_cast<std::size_t>(2 * e + 1)] = slope(N4);
                return v;
            }};
}

/// Linear hat functions on n elements, root node removed.
Basis hats(double L, int n)
{
    const double h = L / n;
    return {n, uniform_breaks(L, n), [=](double x) {
                std::vector<Value> v(static_cast<std::size_t>(n));
                const int e = std::min(static_cast<int>(x / h), n - 1);
                const double s = x / h - e;
                if (e >= 1) v[static_cast<std::size_t>(e - 1)] = {1 - s, -1 / h, 0};
                v[static_cast<std::size_t>(e)] = {s, 1 / h, 0};
                return v;
            }};
}

/// Bernstein polynomials J_{m,i}(xi) = C(m,i) xi^i (1-xi)^(m-i), i = first..m, with J' = m (J_{m-1,i-1} - J_{m-1,i}).
Basis bernstein(double L, int m, int first)
{
    const auto J = [](int deg, int i, double xi) {
        if (i < 0 || i > deg) return 0.0;
        double c = 1.0;
        for (int k = 1; k <= i; ++k) c = c * (deg - i + k) / k;
        return c * std::pow(xi, i) * std::pow(1.0 - xi, deg - i);
    };
    return {m - first + 1, {0.0, L}, [=](double x) {
                const double xi = x / L;
                std::vector<Value> v;
                for (int i = first; i <= m; ++i)
                    v.push_back({J(m, i, xi), m * (J(m - 1, i - 1, xi) - J(m - 1, i, xi)) / L,
                                 m * (m - 1.0) * (J(m - 2, i - 2, xi) - 2 * J(m - 2, i - 1, xi) + J(m - 2, i, xi)) / (L * L)});
                return v;
            }};
}

/// The n + 3 clamped cubic B-splines on knots 0,0,0,0,h,...,(n-1)h,L,L,L,L, without the first `drop` members:
/// Cox-de Boor's recursion for the values, N'_{i,p} = p (N_{i,p-1}/(t_{i+p}-t_i) - N_{i+1,p-1}/(t_{i+p+1}-t_{i+1}))
/// for the derivatives.
Basis splines(double L, int n, int drop)
{
    std::vector<double> t(4, 0.0);
    for (int k = 1; k < n; ++k) t.push_back(L * k / n);
    for (int k = 0; k < 4; ++k) t.push_back(L);
    const int count = n + 3;
    return {count - drop, uniform_breaks(L, n), [=](double x) {
                const int knots = static_cast<int>(t.size());
                // N[p][i] and its first two derivatives, 0/0 taken as 0.
                std::vector<std::vector<double>> N(4, std::vector<double>(static_cast<std::size_t>(knots), 0.0));
                auto D1 = N, D2 = N;
                for (int i = 0; i + 1 < knots; ++i) N[0][i] = t[i] <= x && x < t[i + 1] ? 1.0 : 0.0;
                const auto over = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
                for (int p = 1; p <= 3; ++p)
                    for (int i = 0; i + p + 1 < knots; ++i) {
                        const double l = t[i + p] - t[i], r = t[i + p + 1] - t[i + 1];
                        N[p][i] = over(x - t[i], l) * N[p - 1][i] + over(t[i + p + 1] - x, r) * N[p - 1][i + 1];
                        D1[p][i] = p * (over(N[p - 1][i], l) - over(N[p - 1][i + 1], r));
                        D2[p][i] = p * (over(D1[p - 1][i], l) - over(D1[p - 1][i + 1], r));
                    }
                std::vector<Value> v;
                for (int i = drop; i < count; ++i) v.push_back({N[3][i], D1[3][i], D2[3][i]});
                return v;
            }};
}

/// The i-th root of 1 + cos z cosh z = 0 by bisection on its bracket around (i - 1/2) pi.
double cantilever_root(int i)
{
    const auto f = [](double z) { return 1.0 + std::cos(z) * std::cosh(z); };
    double lo = i == 1 ? 1.0 : (i - 0.5) * std::numbers::pi - 0.5, hi = (i - 0.5) * std::numbers::pi + 0.5;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(lo) * f(mid) <= 0.0 ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

/// The clamped-free modes in the textbook form cos - cosh + g (sin - sinh), g = -(cos b + cosh b)/(sin b + sinh b),
/// whose mean square over the beam is 1 (accurate to 1e-10 up to mode 5, where cosh b is 7e5).
Basis cantilever_modes(double L, int count)
{
    std::vector<double> b, g;
    for (int i = 1; i <= count; ++i) {
        b.push_back(cantilever_root(i));
        g.push_back(-(std::cos(b.back()) + std::cosh(b.back())) / (std::sin(b.back()) + std::sinh(b.back())));
    }
    return {count, uniform_breaks(L, 64), [=](double x) {
                std::vector<Value> v;
                for (std::size_t i = 0; i < b.size(); ++i) {
                    const double k = b[i] / L, z = k * x, c = std::cos(z), ch = std::cosh(z), s = std::sin(z), sh = std::sinh(z);
                    v.push_back({c - ch + g[i] * (s - sh), k * (-s - sh + g[i] * (c - ch)), k * k * (-c - ch + g[i] * (-s - sh))});
                }
                return v;
            }};
}

/// Axial modes sin((2i - 1) pi x / (2L)).
Basis sines(double L, int count)
{
    return {count, uniform_breaks(L, 64), [=](double x) {
                std::vector<Value> v;
                for (int i = 1; i <= count; ++i) {
                    const double k = (2 * i - 1) * std::numbers::pi / (2 * L);
                    v.push_back({std::sin(k * x), k * std::cos(k * x), -k * k * std::sin(k * x)});
                }
                return v;
            }};
}

/// Phi_x and Phi_y of a variant, built here from docs/model.md section 4.
struct Fields {
    Basis axial, transverse;
};

Fields fields_of(const VariantKey& key, double L)
{
    Fields f;
    switch (key.method) {
    case Method::amm: f = {sines(L, key.nx), cantilever_modes(L, key.ny)}; break;
    case Method::fem: f = {hats(L, std::max(key.nx, 1)), hermite(L, key.ny / 2)}; break;
    case Method::bim: f = {bernstein(L, std::max(key.nx, 1), 1), bernstein(L, key.ny + 1, 2)}; break;
    case Method::bsim: f = {splines(L, std::max(key.nx - 2, 1), 1), splines(L, key.ny - 1, 2)}; break;
    }
    if (key.nx == 0) f.axial = {0, {0.0, L}, [](double) { return std::vector<Value>{}; }};
    return f;
}

/// int_0^L w(x) d^da a_i d^db b_j dx by a 16-point Gauss rule on every interval between the breakpoints of both
/// bases (exact for polynomial pieces of degree up to 14 against a quadratic weight).
MatrixXd integral(const Basis& a, int da, const Basis& b, int db, const std::function<double(double)>& w)
{
    std::vector<double> cuts = a.breaks;
    cuts.insert(cuts.end(), b.breaks.begin(), b.breaks.end());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-12; }), cuts.end());
    static const test::GaussRule rule = test::gauss_legendre(16);
    const auto pick = [](const Value& v, int d) { return d == 0 ? v.f : d == 1 ? v.d1 : v.d2; };
    MatrixXd out = MatrixXd::Zero(a.size, b.size);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double mid = 0.5 * (cuts[k] + cuts[k + 1]), half = 0.5 * (cuts[k + 1] - cuts[k]);
        for (std::size_t g = 0; g < rule.x.size(); ++g) {
            const double x = mid + half * rule.x[g];
            const std::vector<Value> va = a.at(x), vb = b.at(x);
            for (int i = 0; i < a.size; ++i)
                for (int j = 0; j < b.size; ++j)
                    out(i, j) += half * rule.w[g] * w(x) * pick(va[static_cast<std::size_t>(i)], da) * pick(vb[static_cast<std::size_t>(j)], db);
        }
    }
    return out;
}

/// The constant matrices of docs/model.md section 5 from the oracle's shape functions.
struct Matrices {
    MatrixXd M1, M2, M3, K1, K2, G, H;  // H = H(L) = int Phi_y'^T Phi_y'
    VectorXd Sx, Sy, tip_x, tip_y;      // tip_*: Phi(L)
};

Matrices oracle(const VariantKey& key, const Parameters& p)
{
    const Fields f = fields_of(key, p.L);
    const double m = p.rho * p.S, EI = p.E * p.I, ES = p.E * p.S, L = p.L, a = p.a;
    const Basis one{1, {0.0, L}, [](double) { return std::vector<Value>{{1.0, 0.0, 0.0}}; }};
    const auto mass = [m](double) { return m; };
    Matrices o;
    o.M1 = integral(f.axial, 0, f.axial, 0, mass);
    o.M2 = integral(f.transverse, 0, f.transverse, 0, mass);
    o.M3 = integral(f.axial, 0, f.transverse, 0, mass);
    o.K1 = integral(f.axial, 1, f.axial, 1, [ES](double) { return ES; });
    o.K2 = integral(f.transverse, 2, f.transverse, 2, [EI](double) { return EI; });
    // G = a C + D with C = int m (L - x) Phi_y'^T Phi_y', D = int m (L^2 - x^2)/2 Phi_y'^T Phi_y'.
    o.G = integral(f.transverse, 1, f.transverse, 1, [=](double x) { return m * (a * (L - x) + (L * L - x * x) / 2); });
    o.H = integral(f.transverse, 1, f.transverse, 1, [](double) { return 1.0; });
    o.Sx = integral(one, 0, f.axial, 0, [=](double x) { return m * (a + x); }).row(0).transpose();
    o.Sy = integral(one, 0, f.transverse, 0, [=](double x) { return m * (a + x); }).row(0).transpose();
    // Phi(L) from the left of the last breakpoint, where every member is the polynomial it is on the last piece.
    const auto at_tip = [L](const Basis& b) {
        VectorXd v(b.size);
        const double x = L * (1.0 - 1e-15);
        const std::vector<Value> all = b.at(x);
        for (int i = 0; i < b.size; ++i) v[i] = all[static_cast<std::size_t>(i)].f;
        return v;
    };
    o.tip_x = at_tip(f.axial);
    o.tip_y = at_tip(f.transverse);
    return o;
}

// ---- The model's matrices through its public interface ----------------------------------------------------------

/// max |a - b| relative to the largest entry of b.
double mismatch(const MatrixXd& a, const MatrixXd& b)
{
    if (b.size() == 0) return a.size() == 0 ? 0.0 : 1.0;
    return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

/// Q(u, q, qd) of a model with prescribed rotation.
VectorXd forces(const Model& model, double theta_dot, double theta_ddot, const VectorXd& q, const VectorXd& qd)
{
    HubInput u;
    u.theta_dot = theta_dot;
    u.theta_ddot = theta_ddot;
    VectorXd Q(model.nq());
    model.forces(u, q.data(), qd.data(), Q.data());
    return Q;
}

/// The matrices of docs/model.md section 5 read off a prescribed-rotation, order-first model: M = diag(M1, M2);
/// Q = theta_dot^2 (S_x + M1 A; (M2 - G) B) - (K1 A; K2 B) + 2 theta_dot (M3 B_dot; -M3^T A_dot)
///     - theta_ddot (-M3 B; S_y + M3^T A).
Matrices read_off(const Model& model)
{
    const int n = model.nq(), nx = model.key().nx, ny = model.key().ny;
    const VectorXd zero = VectorXd::Zero(n);
    const auto unit = [n](int k) { return VectorXd(VectorXd::Unit(n, k)); };
    Matrices r;
    MatrixXd M(n, n);
    model.mass(HubInput{}, zero.data(), M.data());
    r.M1 = M.topLeftCorner(nx, nx);
    r.M2 = M.bottomRightCorner(ny, ny);
    if (nx > 0) CHECK(M.topRightCorner(nx, ny).cwiseAbs().maxCoeff() == 0.0);
    // The hub rate w is large enough that w^2 M stands well above the round-off of K q in Q.
    const double w = 100.0;
    MatrixXd K(n, n), Kw(n, n), coriolis(n, n), euler(n, n);
    const VectorXd spin = forces(model, w, 0.0, zero, zero), push = forces(model, 0.0, 1.0, zero, zero);
    for (int k = 0; k < n; ++k) {
        K.col(k) = -forces(model, 0.0, 0.0, unit(k), zero);
        Kw.col(k) = (forces(model, w, 0.0, unit(k), zero) - spin + K.col(k)) / (w * w);  // (M1; M2 - G) e_k
        coriolis.col(k) = (forces(model, w, 0.0, zero, unit(k)) - spin) / (2.0 * w);
        euler.col(k) = -forces(model, 0.0, 1.0, unit(k), zero) - K.col(k) + push;
    }
    r.K1 = K.topLeftCorner(nx, nx);
    r.K2 = K.bottomRightCorner(ny, ny);
    r.G = r.M2 - Kw.bottomRightCorner(ny, ny);
    r.M3 = coriolis.topRightCorner(nx, ny);
    if (nx > 0) {  // the same M1 and M3 where they enter Q a second time
        CHECK(mismatch(Kw.topLeftCorner(nx, nx), r.M1) < 1e-10);
        CHECK(mismatch(-coriolis.bottomLeftCorner(ny, nx).transpose(), r.M3) < 1e-10);
        CHECK(mismatch(-euler.topRightCorner(nx, ny), r.M3) < 1e-10);
    }
    r.Sx = spin.head(nx) / (w * w);
    r.Sy = -push.tail(ny);
    r.tip_x.resize(nx);
    r.tip_y.resize(ny);
    for (int k = 0; k < nx; ++k) r.tip_x[k] = model.tip(unit(k).data()).ux1;
    for (int k = 0; k < ny; ++k) r.tip_y[k] = model.tip(unit(nx + k).data()).uy;
    return r;
}

VariantKey key_of(Method method, int nx, int ny, Drive drive = Drive::prescribed, SplineBasis spline = SplineBasis::open)
{
    return {.method = method, .nx = nx, .ny = ny, .order = Order::first, .drive = drive, .spline = spline, .extras = {}};
}

Parameters with_hub_radius(double a)
{
    Parameters p;
    p.a = a;  // a != 0 separates G's two parts, a C and D
    return p;
}

/// The variants checked: the built-in sizes and others that only the hand-assembled path serves quickly.
struct Case {
    VariantKey key;
    ModelSource source;
};

std::vector<Case> cases()
{
    std::vector<Case> out;
    for (Method m : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        out.push_back({key_of(m, 4, 4), ModelSource::generated});
        out.push_back({key_of(m, 4, 4), ModelSource::assembled});
    }
    out.push_back({key_of(Method::amm, 3, 5), ModelSource::assembled});
    out.push_back({key_of(Method::fem, 3, 8), ModelSource::assembled});
    out.push_back({key_of(Method::bim, 6, 7), ModelSource::assembled});
    out.push_back({key_of(Method::bsim, 5, 6), ModelSource::assembled});
    out.push_back({key_of(Method::bsim, 3, 3), ModelSource::assembled});
    return out;
}

}  // namespace

TEST_CASE("the oracle's own shape functions reproduce the closed forms they must", "[oracle]")
{
    // The cantilever modes are orthogonal with mean square 1 and K2 = EI b^4 / L^3 on the diagonal; the axial sines
    // have mean square 1/2 and K1 = ES k^2 L / 2. The Hermite cubics and the splines must reproduce a cubic exactly:
    // the oracle is checked before it checks anything.
    const Parameters p;
    const VariantKey key = key_of(Method::amm, 3, 5);
    const Matrices o = oracle(key, p);
    const double m = p.rho * p.S, EI = p.E * p.I, ES = p.E * p.S, L = p.L;
    MatrixXd K2 = MatrixXd::Zero(5, 5), K1 = MatrixXd::Zero(3, 3);
    for (int i = 0; i < 5; ++i) K2(i, i) = EI * std::pow(cantilever_root(i + 1), 4) / std::pow(L, 3);
    for (int i = 0; i < 3; ++i) K1(i, i) = ES * std::pow((2 * i + 1) * std::numbers::pi / 2, 2) / (2 * L);
    CHECK(mismatch(o.M2, m * L * MatrixXd::Identity(5, 5)) < 1e-10);
    CHECK(mismatch(o.K2, K2) < 1e-10);
    CHECK(mismatch(o.M1, m * L / 2 * MatrixXd::Identity(3, 3)) < 1e-13);
    CHECK(mismatch(o.K1, K1) < 1e-13);
    for (int i = 0; i < 5; ++i) CHECK(std::abs(o.tip_y[i]) == Approx(2.0).epsilon(1e-9));  // |phi_i(L)| = 2
    // A cubic with a clamped root, u = x^2 (x - 3L) / L^3 (zero value and slope at 0), is its own interpolation in
    // the Hermite basis from nodal values and slopes.
    const Basis h = hermite(L, 3);
    const auto u = [L](double x) { return x * x * (x - 3 * L) / (L * L * L); };
    const auto du = [L](double x) { return (3 * x * x - 6 * L * x) / (L * L * L); };
    VectorXd c(6);
    for (int node = 1; node <= 3; ++node) {
        c[2 * (node - 1)] = u(node * L / 3);
        c[2 * (node - 1) + 1] = L * du(node * L / 3);  // the slope coordinate is du/dxi
    }
    for (double x : {0.3, 2.9, 5.5, 7.9}) {
        double sum = 0.0;
        const std::vector<Value> v = h.at(x);
        for (int i = 0; i < 6; ++i) sum += c[i] * v[static_cast<std::size_t>(i)].f;
        CHECK(sum == Approx(u(x)).epsilon(1e-13));
    }
    // The clamped splines sum to 1 (partition of unity) and their first members vanish at the root.
    const Basis s = splines(L, 5, 0);
    for (double x : {0.1, 3.3, 7.95}) {
        double sum = 0.0;
        for (const Value& v : s.at(x)) sum += v.f;
        CHECK(sum == Approx(1.0).epsilon(1e-14));
    }
}

TEST_CASE("every method's matrices are the integrals of its textbook shape functions", "[oracle]")
{
    for (double a : {0.0, 0.5}) {
        const Parameters p = with_hub_radius(a);
        for (const Case& c : cases()) {
            const auto model = make_model(c.key, p, c.source);
            const Matrices o = oracle(c.key, p), r = read_off(*model);
            INFO(c.key.name() << " " << model->source() << " a = " << a);
            // AMM's textbook modes are good to about 1e-10 (cosh b ~ 7e5 at mode 5); polynomials to round-off.
            const double tol = c.key.method == Method::amm ? 1e-9 : 1e-11;
            CHECK(mismatch(r.M1, o.M1) < tol);
            CHECK(mismatch(r.M2, o.M2) < tol);
            CHECK(mismatch(r.M3, o.M3) < tol);
            CHECK(mismatch(r.K1, o.K1) < tol);
            CHECK(mismatch(r.K2, o.K2) < tol);
            CHECK(mismatch(r.G, o.G) < tol);
            CHECK(mismatch(r.Sx, o.Sx) < tol);
            CHECK(mismatch(r.Sy, o.Sy) < tol);
            CHECK(mismatch(r.tip_x, o.tip_x) < tol);
            CHECK(mismatch(r.tip_y, o.tip_y) < tol);
        }
    }
}

TEST_CASE("the paper's spline basis carries the tip deflection in its last but one member", "[oracle]")
{
    // Paper eq. (43): of the kept members phi_1 .. phi_(n+1), phi_n is 1 at the tip and phi_(n+1) carries the tip's
    // slope (zero deflection there); all others vanish at the tip.
    const Parameters p;
    for (const ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
        const auto model = make_model(key_of(Method::bsim, 0, 4, Drive::prescribed, SplineBasis::paper), p, source);
        INFO(model->source());
        CHECK(mismatch(read_off(*model).tip_y, VectorXd::Unit(4, 2)) < 1e-14);
    }
}

TEST_CASE("the foreshortened tip and the hub row of the free hub follow the oracle at random states", "[oracle]")
{
    // u_x(L) = Phi_x(L) A - 1/2 B^T H(L) B and M11 = J_oh + J_ob + 2 S_x A + A^T M1 A + B^T (M2 - G) B, M13 = S_y + A^T M3,
    // M12 = -(M3 B)^T, with J_ob = m ((a + L)^3 - a^3) / 3 (docs/model.md section 5).
    const Parameters p = with_hub_radius(0.5);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-0.05, 0.05);
    for (const Case& c : cases()) {
        VariantKey key = c.key;
        key.drive = Drive::torque;
        const auto model = make_model(key, p, c.source);
        const Matrices o = oracle(key, p);
        INFO(key.name() << " " << model->source());
        const int n = model->nq(), nx = key.nx, ny = key.ny;
        VectorXd q(n);
        for (int k = 0; k < n; ++k) q[k] = U(rng);
        const VectorXd A = q.segment(1, nx), B = q.tail(ny);
        const Tip tip = model->tip(q.data());
        const double ux1 = o.tip_x.dot(A), uy = o.tip_y.dot(B);
        const double tol = key.method == Method::amm ? 1e-9 : 1e-11;
        CHECK(tip.uy == Approx(uy).epsilon(tol).margin(1e-14));
        CHECK(tip.ux1 == Approx(ux1).epsilon(tol).margin(1e-14));
        CHECK(tip.ux == Approx(ux1 - 0.5 * B.dot(o.H * B)).epsilon(1e-9).margin(1e-14));
        MatrixXd M(n, n);
        model->mass(HubInput{}, q.data(), M.data());
        const double m = p.rho * p.S, J_ob = m * (std::pow(p.a + p.L, 3) - std::pow(p.a, 3)) / 3;
        const double M11 = p.J_oh + J_ob + 2 * o.Sx.dot(A) + A.dot(o.M1 * A) + B.dot((o.M2 - o.G) * B);
        CHECK(M(0, 0) == Approx(M11).epsilon(1e-12));
        CHECK(mismatch(M.block(0, 1, 1, nx).transpose(), -o.M3 * B) < 1e-9);
        CHECK(mismatch(M.block(0, 1 + nx, 1, ny).transpose(), o.Sy + o.M3.transpose() * A) < 1e-9);
    }
}

TEST_CASE("the static tip deflection under the hub's angular acceleration is the closed form", "[oracle]")
{
    // A beam at rest on a hub accelerating at alpha carries the load -m alpha (a + x): a uniform part -m alpha a and a
    // triangular part growing to -m alpha L at the tip. Euler-Bernoulli's cantilever deflects at its tip by
    // q L^4 / (8 EI) under a uniform q and by 11 q1 L^4 / (120 EI) under a triangular load growing to q1. The static
    // state solves K q = Q(alpha) with K and Q read off the model. A Ritz basis that holds the tip load's deflection,
    // a cubic, gives the exact tip deflection under any load (Galerkin orthogonality against that cubic): FEM, BIM
    // and BSIM at every size, to round-off. The assumed modes hold no cubic and converge as Ny^-4.
    const Parameters p = with_hub_radius(0.5);
    const double m = p.rho * p.S, EI = p.E * p.I, L = p.L, alpha = 1.0;
    const double exact = -m * alpha * (p.a * std::pow(L, 4) / 8 + 11 * std::pow(L, 5) / 120) / EI;
    const auto static_tip = [&](const VariantKey& key) {
        const auto model = make_model(key, p, ModelSource::assembled);
        const int n = model->nq();
        const VectorXd zero = VectorXd::Zero(n);
        MatrixXd K(n, n);
        for (int k = 0; k < n; ++k) K.col(k) = -forces(*model, 0.0, 0.0, VectorXd::Unit(n, k), zero);
        const VectorXd q = K.llt().solve(forces(*model, 0.0, alpha, zero, zero));
        return model->tip(q.data()).uy;
    };
    for (int ny : {2, 4, 8}) CHECK(static_tip(key_of(Method::fem, 0, ny)) == Approx(exact).epsilon(1e-10));
    for (int ny : {2, 5, 9}) CHECK(static_tip(key_of(Method::bim, 0, ny)) == Approx(exact).epsilon(1e-10));
    for (int ny : {2, 4, 8}) CHECK(static_tip(key_of(Method::bsim, 0, ny)) == Approx(exact).epsilon(1e-10));
    double previous = 1.0;
    for (int ny : {4, 8, 16}) {
        const double error = std::abs(static_tip(key_of(Method::amm, 0, ny)) / exact - 1.0);
        INFO("AMM Ny " << ny << " relative error " << error);
        CHECK(error < previous / 8.0);
        CHECK(error < 1e-3);
        previous = error;
    }
    CHECK(static_tip(key_of(Method::bsim, 0, 6, Drive::prescribed, SplineBasis::paper)) == Approx(exact).epsilon(1e-10));
}

TEST_CASE("the steady axial stretch of a spinning beam is the closed form", "[oracle]")
{
    // ES u'' + m Omega^2 (a + x + u) = 0, u(0) = 0, u'(L) = 0 (docs/model.md section 5, Q_A = 0 at B = 0), with
    // k^2 = rho Omega^2 / E: u = -(a + x) + a cos kx + (1 + a k sin kL) sin kx / (k cos kL). Every method but AMM holds
    // the dominant cubic part of u exactly, so they agree to about (kL)^2 h^2; AMM's sines converge as Nx^-3.
    const Parameters p = with_hub_radius(0.5);
    const double omega = 20.0, k = omega * std::sqrt(p.rho / p.E), L = p.L, a = p.a;
    const double exact = -(a + L) + a * std::cos(k * L) + (1 + a * k * std::sin(k * L)) * std::tan(k * L) / k;
    const auto stretch = [&](const VariantKey& key) {
        const auto model = make_model(key, p, ModelSource::assembled);
        const SteadySpin s = steady_spin(*model, omega);
        return model->tip(s.q.data()).ux1;
    };
    CHECK(stretch(key_of(Method::bim, 6, 2)) == Approx(exact).epsilon(1e-9));
    CHECK(stretch(key_of(Method::fem, 8, 2)) == Approx(exact).epsilon(1e-5));
    CHECK(stretch(key_of(Method::bsim, 6, 2)) == Approx(exact).epsilon(1e-5));
    double previous = 1.0;
    for (int nx : {2, 4, 8}) {
        const double error = std::abs(stretch(key_of(Method::amm, nx, 2)) / exact - 1.0);
        INFO("AMM Nx " << nx << " relative error " << error);
        CHECK(error < previous / 4.0);
        previous = error;
    }
    CHECK(previous < 1e-3);
}

TEST_CASE("the natural frequencies are the oracle's eigenvalues and converge to the cantilever's", "[oracle]")
{
    // Without axial coordinates the bending equations about a steady spin are M2 B'' + (K2 + Omega^2 (G - M2)) B = 0:
    // the model's modes are the oracle's generalized eigenvalues at any Ny, and at rest those approach the exact
    // (b_i^2) sqrt(EI / (m L^4)) from above (Rayleigh-Ritz), the first three within 1 % at these sizes.
    for (double a : {0.0, 0.5}) {
        const Parameters p = with_hub_radius(a);
        const double unit = std::sqrt(p.E * p.I / (p.rho * p.S * std::pow(p.L, 4)));
        for (const Method method : {Method::amm, Method::fem, Method::bim, Method::bsim})
            for (const SplineBasis spline : {SplineBasis::open, SplineBasis::paper}) {
                if (spline == SplineBasis::paper && method != Method::bsim) continue;
                const VariantKey key = key_of(method, 0, method == Method::amm ? 5 : 8, Drive::prescribed, spline);
                const auto model = make_model(key, p, ModelSource::assembled);
                const Matrices o = oracle(key_of(method, 0, key.ny), p);  // the paper's splines span the same space
                for (double omega : {0.0, 3.0, 10.0}) {
                    INFO(key.name() << " a = " << a << " Omega " << omega);
                    const test::SymmetricEigen eig = test::generalized_eigen(o.K2 + omega * omega * (o.G - o.M2), o.M2);
                    std::vector<double> modes;
                    for (const NaturalMode& mode : natural_modes(*model, steady_spin(*model, omega))) modes.push_back(mode.rad_s);
                    REQUIRE(static_cast<Eigen::Index>(modes.size()) == eig.values.size());
                    for (std::size_t i = 0; i < modes.size(); ++i) {
                        const double expected = std::sqrt(eig.values[static_cast<Eigen::Index>(i)]);
                        CHECK(modes[i] == Approx(expected).epsilon(1e-8));
                        if (omega == 0.0 && i < 3) {
                            const double exact = std::pow(cantilever_root(static_cast<int>(i) + 1), 2) * unit;
                            CHECK(expected >= exact * (1 - 1e-10));
                            CHECK(expected == Approx(exact).epsilon(1e-2));
                        }
                    }
                }
            }
    }
}
