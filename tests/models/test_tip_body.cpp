// The tip body in the blade's axes (docs/model.md section 11.1) against oracles that share nothing with the generator:
// its kinetic energy by the exact motion of a rigid body carried by the tip section (its rotation matrix's rate, its
// centre of mass's velocity by a complex step), the twist frequencies of a shaft with a tip disk and the flap
// frequencies of a cantilever with a tip mass and rotary inertia from their frequency equations, and the twist a
// tip mass off the axis holds under its weight. Generated models, compiled on demand.
#include <Eigen/Dense>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <functional>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <vector>

#include "basis/basis.hpp"
#include "basis/quadrature.hpp"
#include "coordinates.hpp"
#include "csv_file.hpp"
#include "shared_oracles.hpp"
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

using C = std::complex<double>;
using V3 = std::array<C, 3>;

V3 cross(const V3& a, const V3& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// The tip body's kinetic energy from the exact motion: the tip point at p(L) (the foreshortening by quadrature of
/// both slopes), the body's axes the section's (e1, e2, e3) turned by pitch + phi(L) about e1 and carried by the
/// shortest rotation from e1 to the bent axis (1, u_y', u_z'), then tilted by the precone. T = 1/2 m |V_G|^2 + 1/2
/// sum_a J_a (omega . a)^2 with omega = w k + 1/2 sum_a a x a_dot (the axes' rates in the hub frame by a complex step
/// along qd) and G at -offset along the chord.
class TipBodyOracle {
public:
    TipBodyOracle(const VariantKey& key, const Parameters& p) : key_(key), p_(p) {}

    double kinetic(const std::vector<double>& q, const std::vector<double>& qd, double w) const
    {
        const double h = 1e-30;
        std::vector<C> qc(q.size());
        for (std::size_t k = 0; k < q.size(); ++k) qc[k] = C(q[k], h * qd[k]);
        const auto ux1 = field(key_.axial_basis(), qc, FieldKind::axial, 1.0);
        const auto uy = field(key_.transverse_basis(), qc, FieldKind::inplane, 1.0);
        const auto uz = field(key_.flap_basis(), qc, FieldKind::flap, 1.0);
        const auto phi = field(key_.twist_basis(), qc, FieldKind::twist, 1.0);
        C ux2 = 0.0;
        const QuadratureRule rule = composite_gauss_legendre({0.0, 0.25, 0.5, 0.75, 1.0}, 10);
        for (std::size_t n = 0; n < rule.nodes.size(); ++n) {
            const C y = field(key_.transverse_basis(), qc, FieldKind::inplane, rule.nodes[n])[1];
            const C z = field(key_.flap_basis(), qc, FieldKind::flap, rule.nodes[n])[1];
            ux2 -= p_.L * rule.weights[n] * (y * y + z * z) / 2.0;
        }
        const double cb = std::cos(p_.precone), sb = std::sin(p_.precone);
        const auto hub = [&](const V3& e) { return V3{e[0] * cb - e[2] * sb, e[1], e[0] * sb + e[2] * cb}; };
        const C along = p_.L + ux1[0] + ux2;
        const V3 tip = {p_.a + along * cb - uz[0] * sb, uy[0], along * sb + uz[0] * cb};
        // The axes: t the bent axis, c the chord (towards the leading edge), n = t x c.
        const C psi = p_.pitch + phi[0];
        const C norm = std::sqrt(1.0 + uy[1] * uy[1] + uz[1] * uz[1]);
        const V3 t = {1.0 / norm, uy[1] / norm, uz[1] / norm}, k = {0.0, -t[2], t[1]};
        const auto carried = [&](const V3& v) {
            const V3 kv = cross(k, v), kkv = cross(k, kv);
            V3 r;
            for (int i = 0; i < 3; ++i) r[i] = v[i] + kv[i] + kkv[i] / (1.0 + t[0]);
            return hub(r);
        };
        const V3 c = carried({0.0, std::cos(psi), std::sin(psi)}), n = carried({0.0, -std::sin(psi), std::cos(psi)});
        const V3 a = hub(t);
        const auto rate = [h](const V3& v) {
            return std::array<double, 3>{v[0].imag() / h, v[1].imag() / h, v[2].imag() / h};
        };
        const auto real = [](const V3& v) { return std::array<double, 3>{v[0].real(), v[1].real(), v[2].real()}; };
        const auto x = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
            return std::array<double, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        };
        const auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
            return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        };
        std::array<double, 3> omega = {0.0, 0.0, w};
        for (const V3* axis : {&a, &c, &n}) {
            const auto turn = x(real(*axis), rate(*axis));
            for (int i = 0; i < 3; ++i) omega[static_cast<std::size_t>(i)] += turn[static_cast<std::size_t>(i)] / 2.0;
        }
        const double d = -p_.tip_offset;
        V3 G;
        for (int i = 0; i < 3; ++i) G[i] = tip[i] + d * c[i];
        const std::array<double, 3> g = real(G), g_rate = rate(G);
        const std::array<double, 3> v = {g_rate[0] - w * g[1], g_rate[1] + w * g[0], g_rate[2]};
        const double spin = p_.J_tip_twist * std::pow(dot(omega, real(a)), 2) +
                            p_.J_tip_flap * std::pow(dot(omega, real(c)), 2) +
                            p_.J_tip * std::pow(dot(omega, real(n)), 2);
        return (p_.m_tip * dot(v, v) + spin) / 2.0;
    }

private:
    /// A field's value and derivative d/dx at xi.
    std::array<C, 2> field(const FieldBasis& b, const std::vector<C>& q, FieldKind kind, double xi) const
    {
        std::array<C, 2> f{0.0, 0.0};
        const CoordinateLayout layout = coordinate_layout(key_);
        if (layout.count(kind) == 0) return f;
        const int first = layout.first(kind);
        for (int j = 0; j < b.size(); ++j) {
            const Jet<double> phi = b.at(j, xi);
            f[0] += q[static_cast<std::size_t>(first + j)] * phi.v;
            f[1] += q[static_cast<std::size_t>(first + j)] * phi.d1 / p_.L;
        }
        return f;
    }

    VariantKey key_;
    Parameters p_;
};

/// The state base with the hub's angle and rate kept and the rest scaled by e.
std::vector<double> scaled(const std::vector<double>& base, double e)
{
    std::vector<double> v = base;
    for (std::size_t k = 1; k < v.size(); ++k) v[k] = e * base[k];
    return v;
}

/// A uniform blade of unit length, mass and flapwise stiffness, stiff edgewise (its edge modes far above), with a
/// torsion stiffness GJ = G J_t = 1 and polar mass moment j = rho (I + I_flap).
Parameters unit_blade()
{
    Parameters p;
    p.L = 1.0, p.rho = 1.0, p.S = 1.0, p.E = 1.0, p.I = 100.0, p.I_flap = 1.0, p.G = 1.0, p.J_t = 1.0, p.a = 0.0;
    return p;
}

/// The roots below `most` of f by a scan of `steps` intervals and bisection.
std::vector<double> roots(const std::function<double(double)>& f, double most, int steps = 4000)
{
    return test::bracketed_roots(f, 1e-3, most, steps, 1e-15);
}

/// The natural frequencies (rad/s) of one kind at rest, lowest first.
std::vector<double> frequencies(const VariantKey& key, const Parameters& p, const std::string& kind)
{
    const auto model = make_model(key, p, ModelSource::generated);
    std::vector<double> f;
    for (const NaturalMode& m : natural_modes(*model, steady_spin(*model, 0.0)))
        if (m.kind == kind) f.push_back(m.rad_s);
    return f;
}

VariantKey blade_key(Method method, int nz, int nt)
{
    VariantKey key{.method = method, .nx = 0, .ny = 2, .order = Order::first, .drive = Drive::prescribed};
    key.nz = nz, key.nt = nt;
    key.extras.tip = key.extras.tip_body = true;
    return key;
}

}  // namespace

TEST_CASE("the tip body's kinetic energy is the rigid body's carried by the tip section, to second order",
          "[tip_body]")
{
    // Every field, a pitch and a precone, on a hub of radius 0.5: the generated T's share of the tip body (T at its
    // values less T with them 0) against the oracle's exact one, term by term in the deformation's scale e. The
    // generated share is a polynomial of degree 2 in e; the oracle's Taylor coefficients must be its coefficients.
    // The inertias break the triangle inequality as BModes' CertTest 02 does (lag 10 > flap 1.75 + torsion 2.5).
    VariantKey key{.method = Method::fem, .nx = 2, .ny = 4, .order = Order::first, .drive = Drive::torque};
    key.nz = 4, key.nt = 2;
    key.extras.tip = key.extras.tip_body = key.extras.pitch = key.extras.cone = true;
    Parameters p = unit_blade();
    p.L = 2.0, p.I = 3.0, p.a = 0.5, p.pitch = 0.2, p.precone = 0.1;
    p.m_tip = 0.7, p.J_tip = 0.3, p.J_tip_flap = 0.0525, p.J_tip_twist = 0.075, p.tip_offset = 0.15;
    Parameters none = p;
    none.m_tip = none.J_tip = none.J_tip_flap = none.J_tip_twist = none.tip_offset = 0.0;
    const auto body = make_model(key, p, ModelSource::generated);
    const auto bare = make_model(key, none, ModelSource::generated);
    // The hand-assembled path has no form for it, and says so rather than dropping it.
    CHECK_THROWS_WITH(make_model(key, p, ModelSource::assembled), Catch::Contains("no hand-assembled form"));
    const TipBodyOracle oracle(key, p);
    const int nq = key.nq();
    for (int trial = 0; trial < 3; ++trial) {
        std::vector<double> q(static_cast<std::size_t>(nq)), qd(q.size());
        for (int k = 0; k < nq; ++k) {
            q[static_cast<std::size_t>(k)] = 0.3 * std::sin(1.7 * k + trial + 0.4);
            qd[static_cast<std::size_t>(k)] = 0.5 * std::cos(2.3 * k - trial);
        }
        qd[0] = 3.0 + trial;  // the hub's rate
        const auto kinetic = [](const Model& m, const std::vector<double>& x, const std::vector<double>& xd) {
            return m.energy(HubInput{}, x.data(), xd.data()).kinetic();
        };
        const auto generated = [&](double e) {
            return kinetic(*body, scaled(q, e), scaled(qd, e)) - kinetic(*bare, scaled(q, e), scaled(qd, e));
        };
        const auto exact = [&](double e) { return oracle.kinetic(scaled(q, e), scaled(qd, e), qd[0]); };
        // The oracle's coefficients by five-point differences at e = +-1e-2, +-2e-2: their error, e^4 of the orders
        // beyond, and round-off, 1e-16 / e^2, both near 1e-10. The generated ones, of a quadratic, are exact so.
        const auto coefficients = [](const auto& f, double e) {
            const double f0 = f(0.0), f1 = f(e), f_1 = f(-e), f2 = f(2 * e), f_2 = f(-2 * e);
            return std::array<double, 3>{f0, (8 * (f1 - f_1) - (f2 - f_2)) / (12 * e),
                                         (16 * (f1 + f_1) - (f2 + f_2) - 30 * f0) / (24 * e * e)};
        };
        const std::array<double, 3> g = coefficients(generated, 1.0), o = coefficients(exact, 1e-2);
        for (int order = 0; order < 3; ++order) {
            INFO("trial " << trial << ", the term of order " << order << " in the deformation: generated " << g[order]
                          << ", off the oracle's by " << std::abs(g[order] - o[order]) / std::abs(o[order]));
            CHECK(std::abs(o[order]) > 1e-3);
            CHECK(g[order] == Approx(o[order]).epsilon(1e-8));
        }
    }
}

TEST_CASE("the twist frequencies of a shaft with a tip disk are the roots of beta L tan(beta L) = j L / J_tip_twist",
          "[tip_body]")
{
    // GJ phi'' + omega^2 j phi = 0, phi(0) = 0, GJ phi'(L) = omega^2 J phi(L): phi = sin(beta x), beta^2 = omega^2 j /
    // GJ. A disk of half the shaft's polar moment lowers the first twist frequency from pi/2 sqrt(GJ/j) by a third.
    Parameters p = unit_blade();
    const double j = p.rho * (p.I + p.I_flap), GJ = p.G * p.J_t, disk = 0.5 * j * p.L;
    p.J_tip_twist = disk;
    const std::vector<double> exact = roots(
        [&](double w) {
            const double bL = w * std::sqrt(j / GJ) * p.L;
            return bL * std::sin(bL) - j * p.L / disk * std::cos(bL);
        },
        5.0 * std::sqrt(GJ / j) * M_PI);
    REQUIRE(exact.size() >= 3);
    CHECK(exact[0] < 0.7 * M_PI / 2 * std::sqrt(GJ / j));
    const std::vector<double> coarse = frequencies(blade_key(Method::bim, 2, 4), p, "twist"),
                              fine = frequencies(blade_key(Method::bim, 2, 8), p, "twist");
    for (std::size_t i = 0; i < 3; ++i) {
        const double e_coarse = std::abs(coarse[i] - exact[i]), e_fine = std::abs(fine[i] - exact[i]);
        INFO("mode " << i + 1 << ": exact " << exact[i] << ", BIM off by " << e_coarse / exact[i] << " then "
                     << e_fine / exact[i]);
        CHECK((e_fine < e_coarse || e_fine <= 1e-10 * exact[i]));
        // BIM Nt = 8: mode 3 1.3e-6 off, from 3.9e-2 at Nt = 4.
        CHECK(e_fine <= 3e-6 * exact[i]);
    }
}

TEST_CASE("the flap frequencies of a cantilever with a tip mass and a rotary inertia about the chord", "[tip_body]")
{
    // EI W'''' = omega^2 m W, W(0) = W'(0) = 0, EI W''(L) = omega^2 J W'(L), EI W'''(L) = -omega^2 M W(L): W = A (cosh -
    // cos) + B (sinh - sin), a 2 x 2 determinant in omega (Laura, Pombo & Susemihl 1974 with a rotary inertia).
    Parameters p = unit_blade();
    const double EI = p.E * p.I_flap, m = p.rho * p.S, L = p.L, M = 0.4, J = 0.05;
    p.m_tip = M, p.J_tip_flap = J;
    const std::vector<double> exact = roots(
        [&](double w) {
            const double b = std::sqrt(w * std::sqrt(m / EI)), x = b * L;
            const double ch = std::cosh(x), sh = std::sinh(x), c = std::cos(x), s = std::sin(x);
            // W, W', W'', W''' at L of each solution over b^n.
            const Eigen::Vector4d A{ch - c, sh + s, ch + c, sh - s}, B{sh - s, ch - c, sh + s, ch + c};
            const double k2 = w * w * J / (EI * b), k3 = w * w * M / (EI * b * b * b);
            Eigen::Matrix2d bc;
            bc << A[2] - k2 * A[1], B[2] - k2 * B[1], A[3] + k3 * A[0], B[3] + k3 * B[0];
            return bc.determinant() / (ch * ch);
        },
        200.0);
    REQUIRE(exact.size() >= 3);
    // Without the rotary inertia the second root would be 17.18 (Laura's tip mass alone), twice 8.21 with it.
    CHECK(exact[1] < 0.5 * 17.18);
    const std::vector<double> coarse = frequencies(blade_key(Method::fem, 8, 0), p, "flap"),
                              fine = frequencies(blade_key(Method::fem, 16, 0), p, "flap");
    for (std::size_t i = 0; i < 3; ++i) {
        const double e_coarse = std::abs(coarse[i] - exact[i]), e_fine = std::abs(fine[i] - exact[i]);
        INFO("mode " << i + 1 << ": exact " << exact[i] << ", FEM off by " << e_coarse / exact[i] << " then "
                     << e_fine / exact[i]);
        CHECK(e_fine < e_coarse);
        // Hermite cubics converge as h^4: mode 3 9.4e-5 off at 8 elements, 1.5e-3 at 4.
        CHECK(e_fine <= 2e-4 * exact[i]);
    }
}

TEST_CASE("a tip mass off the axis twists a held blade by m g offset L / GJ under gravity along the spin axis",
          "[tip_body]")
{
    // Its weight m g_axis at the offset along the chord is a torque m g_axis offset about the span axis; and it bends
    // the blade flapwise by -m g L^3 / (3 EI_flap). Small: the linear response of the second-order model.
    Parameters p = unit_blade();
    p.m_tip = 0.3, p.tip_offset = 0.2, p.g_axis = 1e-4;
    VariantKey key = blade_key(Method::fem, 4, 2);
    key.extras.gravity = true;
    const auto model = make_model(key, p, ModelSource::generated);
    const Tip tip = model->tip(held_equilibrium(*model, 0.0).q.data());
    const double twist = p.m_tip * p.g_axis * p.tip_offset * p.L / (p.G * p.J_t);
    const double sag = -p.m_tip * p.g_axis * std::pow(p.L, 3) / (3.0 * p.E * p.I_flap);
    CHECK(tip.phi == Approx(twist).epsilon(1e-6));
    CHECK(tip.uz == Approx(sag - p.rho * p.S * p.g_axis / (8.0 * p.E * p.I_flap)).epsilon(1e-6));
}

TEST_CASE("blade fields: u_z, phi, the torque and the shortening along a blade that an offset tip mass bends and twists",
          "[tip_body][fields]")
{
    // The statics of the test above, along the span and through the fields CSV: a tip load P = -m g_axis bends the
    // blade to u_z = P x^2 (3 L - x) / (6 EI_flap) (the beam's own weight made negligible), the torque T = m g_axis
    // offset twists it to phi = T x / GJ with GJ phi' = T, and the flapwise slope shortens it by u_x = -1/2 int_0^x
    // u_z'^2 = -1/2 (P / 2 EI_flap)^2 (4 L^2 x^3 / 3 - L x^4 + x^5 / 5). Ny, Nz and Nt differ, so that each field is
    // read by its own basis; Hermite cubics hold the cubic u_z, linear elements the linear phi.
    Parameters p = unit_blade();
    p.rho = 1e-9, p.m_tip = 0.3, p.tip_offset = 0.2, p.g_axis = 1e-4;
    VariantKey key = blade_key(Method::fem, 4, 2);
    key.extras.gravity = true;
    const auto model = make_model(key, p, ModelSource::generated);
    const std::vector<double> q = held_equilibrium(*model, 0.0).q;
    const TempFolder folder("tip-body-fields");
    const std::string path = (folder.path / "fields.csv").string();
    FieldRecorder recorder(key, p, {0.0}, 11, path);
    recorder.state(0.0, q.data());
    REQUIRE(recorder.finish());
    const test::Csv csv = test::read_csv(path);
    const double L = p.L, EI = p.E * p.I_flap, GJ = p.G * p.J_t, P = -p.m_tip * p.g_axis;
    const double T = p.m_tip * p.g_axis * p.tip_offset, w_tip = P * L * L * L / (3.0 * EI);
    int checked = 0;
    for (const std::vector<double>& row : csv.rows) {
        const double x = row[csv.column("x")];
        const double shortening = -0.5 * (P / (2.0 * EI)) * (P / (2.0 * EI)) *
                                  (4.0 * L * L * x * x * x / 3.0 - L * x * x * x * x + x * x * x * x * x / 5.0);
        INFO("x = " << x);
        CHECK(row[csv.column("uz")] == Approx(P * x * x * (3.0 * L - x) / (6.0 * EI)).margin(1e-6 * std::abs(w_tip)));
        CHECK(row[csv.column("phi")] == Approx(T * x / GJ).epsilon(1e-6).margin(1e-12));
        CHECK(row[csv.column("torque")] == Approx(T).epsilon(1e-6));
        CHECK(row[csv.column("ux")] == Approx(shortening).margin(1e-6 * 0.1 * w_tip * w_tip));
        ++checked;
    }
    CHECK(checked >= 11);
}
