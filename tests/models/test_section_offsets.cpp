// A blade's section offsets (docs/model.md section 12.5) against oracles that share nothing with the generator: the
// offset centre of mass's kinetic energy by quadrature of the exact motion of a rigid section (turned by the
// pre-twist, pitch and twist, carried by the bent axis), and the coupled flap and torsion frequencies of a uniform
// cantilever whose centre of mass lies off its axis, from their closed-form frequency equation (the 6 x 6
// determinant of the exponential solutions; Banerjee 1989). Generated models, compiled on demand where not built in.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <tuple>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <vector>

#include "basis/basis.hpp"
#include "basis/quadrature.hpp"
#include "coordinates.hpp"
#include "shared_oracles.hpp"

using namespace hubbeam;

namespace {

using C = std::complex<double>;

/// A blade table: stations, and at each m, EI, ES, EI_flap, GJ, twist, j_c, j_n and the centre of mass's and the
/// tension centre's offsets.
struct Station {
    double x, m, EI, ES, EI_flap, GJ, twist, j_c, j_n, cg, tc = 0.0;
};

Parameters blade(const std::vector<Station>& table, double L)
{
    Parameters p;
    p.L = L;
    p.rho = table[0].m, p.S = 1.0, p.E = table[0].ES, p.I = table[0].EI / p.E, p.I_flap = table[0].EI_flap / p.E;
    for (const Station& s : table) {
        p.stations.push_back(s.x);
        p.profile.insert(p.profile.end(), {s.m, s.EI, s.ES, s.EI_flap, s.GJ, s.twist, s.j_c, s.j_n, s.twist});
        p.offsets.insert(p.offsets.end(), {s.cg, s.tc});  // in the order of SectionOffset
    }
    return p;
}

/// The offset centre of mass's share of T, 1/2 int m (|r_g_dot|^2 - |r_dot|^2 - |omega_a x d|^2) dx = int m V . D_dot
/// dx + 1/2 int m (|D_dot|^2 - |D_a_dot|^2) dx: V the reference point's inertial velocity, D the vector from it to the
/// centre of mass, D_a the same turned by the twist and the spin alone (the section's mass moments about the
/// reference axis hold the rotation omega_a and nothing of the slopes', so that r_g moves exactly). Each section is
/// rigid: its chord, at the angle pitch + beta(x) + phi from e2 towards e3 (beta and the mass's moment m d linear
/// between stations as the components m d cos beta, m d sin beta at the stations; m d^2 times the chord's
/// direction's square likewise), is carried by the rotation that takes e1 to the bent axis (1, u_y', u_z') by the
/// shortest way. Rates by a complex step along qd.
class OffsetOracle {
public:
    OffsetOracle(const VariantKey& key, const Parameters& p) : key_(key), p_(p) {}

    double kinetic(const std::vector<double>& q, const std::vector<double>& qd, double w) const
    {
        std::vector<C> qc(q.size());
        const double h = 1e-30;
        for (std::size_t k = 0; k < q.size(); ++k) qc[k] = C(q[k], h * qd[k]);
        // Cuts at the stations and at every eighth of the span (the elements' ends of the meshes used here).
        std::vector<double> cuts = p_.stations;
        for (int k = 0; k <= 8; ++k) cuts.push_back(k / 8.0);
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
        const QuadratureRule rule = composite_gauss_legendre(cuts, 12);
        double sum = 0.0;
        for (std::size_t n = 0; n < rule.nodes.size(); ++n) {
            const auto [V, D, rotation] = motion(qc, rule.nodes[n], cuts, h, w);
            sum += rule.weights[n] * (V[0] * D[0] + V[1] * D[1] + V[2] * D[2] + rotation);
        }
        return p_.L * sum;
    }

private:
    /// A field's value and derivatives d/dx at xi: sum_j c[first + j] phi_j(xi).
    std::array<C, 2> field(const FieldBasis& b, const std::vector<C>& q, int first, double xi) const
    {
        std::array<C, 2> f{0.0, 0.0};
        for (int j = 0; j < b.size(); ++j) {
            const Jet<double> phi = b.at(j, xi);
            f[0] += q[static_cast<std::size_t>(first + j)] * phi.v;
            f[1] += q[static_cast<std::size_t>(first + j)] * phi.d1 / p_.L;
        }
        return f;
    }

    int first(FieldKind k) const
    {
        const CoordinateLayout layout = coordinate_layout(key_);
        return layout.count(k) > 0 ? layout.first(k) : 0;
    }

    /// A station's share of the section at xi: the hat function's weight, the mass per length, the offset d towards
    /// the leading edge (the table's is towards the trailing edge) and the chord's angle (pitch + tabulated twist).
    struct Share {
        double weight, m, d, angle;
    };
    std::array<Share, 2> shares(double xi) const
    {
        const std::vector<double>& x = p_.stations;
        std::size_t k = 0;
        while (k + 2 < x.size() && xi > x[k + 1]) ++k;
        const double t = (xi - x[k]) / (x[k + 1] - x[k]);
        std::array<Share, 2> out;
        for (std::size_t s : {k, k + 1})
            out[s - k] = {s == k ? 1.0 - t : t, p_.profile[9 * s], -p_.offsets[2 * s],
                          p_.pitch + p_.profile[9 * s + 5]};
        return out;
    }

    /// m d cos and m d sin of the chord's angle, linear between stations.
    std::array<double, 2> moment(double xi) const
    {
        std::array<double, 2> out{0.0, 0.0};
        for (const Share& s : shares(xi)) {
            out[0] += s.weight * s.m * s.d * std::cos(s.angle);
            out[1] += s.weight * s.m * s.d * std::sin(s.angle);
        }
        return out;
    }

    /// The reference point's inertial velocity V and D_dot, in the hub frame, at xi, and the offset mass's rotation
    /// 1/2 m (|D_dot|^2 - |D_a_dot|^2).
    std::tuple<std::array<double, 3>, std::array<double, 3>, double> motion(const std::vector<C>& q, double xi,
                                                                            const std::vector<double>& cuts, double h,
                                                                            double w) const
    {
        const auto ux1 = field(key_.axial_basis(), q, first(FieldKind::axial), xi);
        const auto uy = field(key_.transverse_basis(), q, first(FieldKind::inplane), xi);
        const auto uz = field(key_.flap_basis(), q, first(FieldKind::flap), xi);
        const auto phi = field(key_.twist_basis(), q, first(FieldKind::twist), xi);
        // u_x2 = -1/2 int_0^x (u_y'^2 + u_z'^2), on the cuts below xi.
        C ux2 = 0.0;
        for (std::size_t k = 0; k + 1 < cuts.size() && cuts[k] < xi; ++k) {
            const double hi = std::min(cuts[k + 1], xi);
            const QuadratureRule r = composite_gauss_legendre({cuts[k], hi}, 8);
            for (std::size_t n = 0; n < r.nodes.size(); ++n) {
                const C y = field(key_.transverse_basis(), q, first(FieldKind::inplane), r.nodes[n])[1];
                const C z = field(key_.flap_basis(), q, first(FieldKind::flap), r.nodes[n])[1];
                ux2 -= p_.L * r.weights[n] * (y * y + z * z) / 2.0;
            }
        }
        const double cb = std::cos(p_.precone), sb = std::sin(p_.precone);
        const C along = p_.L * xi + ux1[0] + ux2;
        const std::array<C, 3> pos = {p_.a + along * cb - uz[0] * sb, uy[0], along * sb + uz[0] * cb};
        // A vector of the section's plane, (0, c, s) in the blade's axes, turned by phi about e1, then (bent) by the
        // shortest rotation from e1 to the bent axis t, in the hub frame.
        const C norm = std::sqrt(1.0 + uy[1] * uy[1] + uz[1] * uz[1]);
        const std::array<C, 3> t = {1.0 / norm, uy[1] / norm, uz[1] / norm};
        const std::array<C, 3> k = {0.0, -t[2], t[1]};  // e1 x t
        const auto cross = [](const std::array<C, 3>& a, const std::array<C, 3>& b) {
            return std::array<C, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        };
        const auto turned = [&](double c, double s, bool bent) {
            const std::array<C, 3> d0 = {0.0, c * std::cos(phi[0]) - s * std::sin(phi[0]),
                                         s * std::cos(phi[0]) + c * std::sin(phi[0])};
            std::array<C, 3> d = d0;
            if (bent) {
                const std::array<C, 3> kd = cross(k, d0), kkd = cross(k, kd);
                for (int n = 0; n < 3; ++n) d[n] = d0[n] + kd[n] + kkd[n] / (1.0 + t[0]);
            }
            return std::array<C, 3>{d[0] * cb - d[2] * sb, d[1], d[0] * sb + d[2] * cb};
        };
        // Inertial rates (the complex step along qd); the hub frame turns at w about k.
        const auto rate = [h](const C& c) { return c.imag() / h; };
        const auto inertial = [&](const std::array<C, 3>& r) {
            return std::array<double, 3>{rate(r[0]) - w * r[1].real(), rate(r[1]) + w * r[0].real(), rate(r[2])};
        };
        const auto [mc, ms] = moment(xi);
        const std::array<double, 3> V = inertial(pos), D = inertial(turned(mc, ms, true));
        double rotation = 0.0;
        for (const Share& s : shares(xi)) {
            const auto square = [](const std::array<double, 3>& r) { return r[0] * r[0] + r[1] * r[1] + r[2] * r[2]; };
            const double c = std::cos(s.angle), sn = std::sin(s.angle);
            rotation += s.weight * s.m * s.d * s.d / 2.0 *
                        (square(inertial(turned(c, sn, true))) - square(inertial(turned(c, sn, false))));
        }
        return {V, D, rotation};
    }

    VariantKey key_;
    Parameters p_;
};

/// T of a model at (q, qd), torque drive (w = qd[0]).
double kinetic(const Model& model, const std::vector<double>& q, const std::vector<double>& qd)
{
    return model.energy(HubInput{}, q.data(), qd.data()).kinetic();
}

/// The state q0 + e dq (rates likewise) with the hub's angle and rate kept: e scales the deformation alone.
std::vector<double> scaled(const std::vector<double>& base, const std::vector<double>& d, double e)
{
    std::vector<double> v = base;
    for (std::size_t k = 1; k < v.size(); ++k) v[k] = e * d[k];
    return v;
}

/// FEM with every field (two elements), a table with offsets, pitch and precone, under a torque: one compiled variant
/// for the energy's and the mass matrix's tests.
VariantKey every_field()
{
    VariantKey key{.method = Method::fem, .nx = 2, .ny = 4, .order = Order::first, .drive = Drive::torque};
    key.nz = 4, key.nt = 2;
    key.extras.tabulated = key.extras.offsets = key.extras.pitch = key.extras.cone = true;
    return key;
}

}  // namespace

TEST_CASE("section offsets: the offset centre of mass's kinetic energy is the rigid section's, to second order",
          "[section_offsets]")
{
    // Three stations with a turning chord and an offset that changes sign, a pitch and a precone, every field: the
    // generated T's share of the offsets (T at the offsets less T with them 0) against the oracle's exact one, term by
    // term in the deformation's scale e: the generated one is a polynomial of degree 2 in e, whose coefficients the
    // oracle's Taylor coefficients must be.
    const VariantKey key = every_field();
    Parameters p = blade({{0.0, 3.0, 900.0, 7e6, 300.0, 80.0, 0.3, 0.02, 0.10, 0.05},
                          {0.4, 2.0, 600.0, 5e6, 200.0, 50.0, 0.1, 0.01, 0.07, -0.02},
                          {1.0, 1.0, 200.0, 2e6, 90.0, 20.0, -0.2, 0.01, 0.03, 0.08}},
                         2.0);
    p.a = 0.5, p.pitch = 0.2, p.precone = 0.1;
    Parameters still = p;
    std::fill(still.offsets.begin(), still.offsets.end(), 0.0);
    const auto offset = make_model(key, p, ModelSource::generated);
    const auto none = make_model(key, still, ModelSource::generated);
    const OffsetOracle oracle(key, p);
    const int nq = key.nq();
    for (int trial = 0; trial < 3; ++trial) {
        std::vector<double> q(static_cast<std::size_t>(nq)), qd(q.size());
        for (int k = 0; k < nq; ++k) {
            q[static_cast<std::size_t>(k)] = 0.3 * std::sin(1.7 * k + trial + 0.4);
            qd[static_cast<std::size_t>(k)] = 0.5 * std::cos(2.3 * k - trial);
        }
        qd[0] = 3.0 + trial;  // the hub's rate
        const auto generated = [&](double e) {
            return kinetic(*offset, scaled(q, q, e), scaled(qd, qd, e)) -
                   kinetic(*none, scaled(q, q, e), scaled(qd, qd, e));
        };
        const auto exact = [&](double e) { return oracle.kinetic(scaled(q, q, e), scaled(qd, qd, e), qd[0]); };
        // The generated share is exactly quadratic in e: its coefficients from e = +-1. The oracle's by differences
        // at e = +-1e-4: their error, e^2 of the next orders, and round-off, 1e-16 / e^2, both near 1e-8.
        const auto coefficients = [](const auto& f, double e) {
            return std::array<double, 3>{f(0.0), (f(e) - f(-e)) / (2 * e), (f(e) + f(-e) - 2 * f(0.0)) / (2 * e * e)};
        };
        const std::array<double, 3> g = coefficients(generated, 1.0), o = coefficients(exact, 1e-4);
        for (int order = 0; order < 3; ++order) {
            INFO("trial " << trial << ", the term of order " << order << " in the deformation: generated " << g[order]
                          << ", off the oracle's by " << std::abs(g[order] - o[order]) / std::abs(o[order]));
            CHECK(std::abs(o[order]) > 1e-3);  // each order present, so that a dropped term shows
            CHECK(g[order] == Approx(o[order]).epsilon(1e-7));
        }
    }
}

TEST_CASE("section offsets: the mass matrix of a physical section stays positive definite with axial coordinates",
          "[section_offsets]")
{
    // An offset longer than an element (0.6 m, elements of 0.5 m), the section's polar moment about the reference
    // axis above m d^2 (a physical section's): the centre of mass's kinetic energy 1/2 m |V + d C_dot|^2 and the
    // rotation about it are each >= 0, so M is positive definite for every state. Without the offset mass's turn with
    // the slopes the axial rate's coupling to them, -m d u_x1_dot sigma_dot, stands alone and makes M indefinite.
    const VariantKey key = every_field();
    Parameters p = blade({{0.0, 1.0, 50.0, 1e4, 80.0, 30.0, 0.2, 0.05, 0.40, 0.6},
                          {1.0, 1.0, 50.0, 1e4, 80.0, 30.0, -0.1, 0.05, 0.40, -0.6}},
                         1.0);
    p.a = 0.2, p.pitch = 0.3, p.precone = 0.05;
    const auto model = make_model(key, p, ModelSource::generated);
    const int nq = key.nq();
    for (double scale : {0.0, 0.05}) {
        std::vector<double> q(static_cast<std::size_t>(nq));
        for (int k = 0; k < nq; ++k) q[static_cast<std::size_t>(k)] = scale * std::sin(1.3 * k + 0.2);
        Eigen::MatrixXd M(nq, nq);
        model->mass(HubInput{}, q.data(), M.data());
        const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
        INFO("state scale " << scale << ": M's eigenvalues from " << lambda.minCoeff() << " to " << lambda.maxCoeff());
        CHECK(lambda.minCoeff() > 0.0);
    }
}

namespace {

/// The frequencies (rad/s) below `most` of a uniform cantilever of flap stiffness EI and torsion stiffness GJ whose
/// centre of mass lies e off its axis along the chord (mass m, polar moment j about the axis, per length): the roots
/// of the determinant of the clamped-free conditions on the exponential solutions of
///     EI w'''' - omega^2 m (w + e phi) = 0,    GJ phi'' + omega^2 (m e w + j phi) = 0,
/// whose exponents lambda^2 = s solve EI GJ s^3 + EI j omega^2 s^2 - GJ m omega^2 s - omega^4 m (j - m e^2) = 0: one
/// root a^2 > 0 (cosh, sinh) and two -b^2, -c^2 < 0 (cos, sin), phi = k(s) w with k = (EI s^2 - omega^2 m) /
/// (omega^2 m e).
std::vector<double> coupled_frequencies(double EI, double GJ, double m, double j, double e, double L, double most)
{
    const auto determinant = [&](double w) {
        const double w2 = w * w;
        Eigen::Matrix3d companion = Eigen::Matrix3d::Zero();
        const double a3 = EI * GJ, a2 = EI * j * w2, a1 = -GJ * m * w2, a0 = -w2 * w2 * m * (j - m * e * e);
        companion(0, 0) = -a2 / a3, companion(0, 1) = -a1 / a3, companion(0, 2) = -a0 / a3;
        companion(1, 0) = companion(2, 1) = 1.0;
        const Eigen::Vector3cd roots = companion.eigenvalues();
        std::vector<double> s;
        for (int r = 0; r < 3; ++r) {
            REQUIRE(std::abs(roots[r].imag()) <= 1e-9 * std::abs(roots[r]));
            s.push_back(roots[r].real());
        }
        std::sort(s.begin(), s.end());
        REQUIRE((s[0] < 0.0 && s[1] < 0.0 && s[2] > 0.0));
        const double a = std::sqrt(s[2]), b = std::sqrt(-s[1]), c = std::sqrt(-s[0]);
        // The six solutions' n-th derivatives at x: cosh, sinh (a); cos, sin (b); cos, sin (c).
        const auto f = [&](int col, int n, double x) {
            const double r = col < 2 ? a : col < 4 ? b : c;
            const double scale = std::pow(r, n);
            if (col < 2) return scale * ((col + n) % 2 == 0 ? std::cosh(r * x) : std::sinh(r * x));
            // d^n/dx^n cos(r x) = r^n cos(r x + n pi/2), and sin(r x) = cos(r x - pi/2).
            return scale * std::cos(r * x + (n - col % 2) * M_PI / 2.0);
        };
        const double k[3] = {(EI * s[2] * s[2] - w2 * m) / (w2 * m * e), (EI * s[1] * s[1] - w2 * m) / (w2 * m * e),
                             (EI * s[0] * s[0] - w2 * m) / (w2 * m * e)};
        Eigen::Matrix<double, 6, 6> bc;
        for (int col = 0; col < 6; ++col) {
            const double kc = k[col / 2];
            bc(0, col) = f(col, 0, 0.0);
            bc(1, col) = f(col, 1, 0.0);
            bc(2, col) = kc * f(col, 0, 0.0);
            bc(3, col) = f(col, 2, L);
            bc(4, col) = f(col, 3, L);
            bc(5, col) = kc * f(col, 1, L);
        }
        return bc.determinant();
    };
    return test::bracketed_roots(determinant, 0.5, most, 4000, 1e-14);
}

}  // namespace

TEST_CASE("section offsets: the coupled flap and torsion frequencies of a cantilever with an offset centre of mass",
          "[section_offsets]")
{
    // Uniform (two equal stations), at rest, chord in the plane of rotation: the offset couples flap to twist through
    // the mass alone, m e w_dot phi_dot; the edgewise stiffness is 1e4 times the flapwise, its modes far above.
    const double EI = 1.0, GJ = 4.5, m = 1.0, jc = 0.01, jn = 0.04, cg = 0.15;
    const Station s{0.0, m, 1e4, 1e6, EI, GJ, 0.0, jc, jn, cg};
    Station tip = s;
    tip.x = 1.0;
    const Parameters p = blade({s, tip}, 1.0);
    const std::vector<double> exact = coupled_frequencies(EI, GJ, m, jc + jn, cg, 1.0, 50.0);
    REQUIRE(exact.size() >= 4);
    const auto modes = [&](int nz, int nt) {
        VariantKey key{.method = Method::bim, .nx = 0, .ny = 2, .order = Order::first, .drive = Drive::prescribed};
        key.nz = nz, key.nt = nt;
        key.extras.tabulated = key.extras.offsets = true;
        const auto model = make_model(key, p, ModelSource::generated);
        std::vector<double> f;
        for (const NaturalMode& mode : natural_modes(*model, steady_spin(*model, 0.0)))
            if (mode.kind != "edge") f.push_back(mode.rad_s);
        return f;
    };
    const std::vector<double> coarse = modes(6, 4), fine = modes(10, 8);
    // Without the offset the first twist frequency would be pi/2 sqrt(GJ/j_p) = 14.90, 3 % from the coupled one.
    for (std::size_t i = 0; i < 4; ++i) {
        const double e_coarse = std::abs(coarse[i] - exact[i]), e_fine = std::abs(fine[i] - exact[i]);
        INFO("mode " << i + 1 << ": exact " << exact[i] << ", BIM off by " << e_coarse / exact[i] << " then "
                     << e_fine / exact[i]);
        CHECK((e_fine < e_coarse || e_fine <= 1e-9 * exact[i]));
        // BIM Nt = 8's twist modes: the second (mode 4) 2.8e-6 off, from 2.8e-2 at Nt = 4.
        CHECK(e_fine <= 1e-5 * exact[i]);
    }
}

namespace {

/// The tension centre's share of U by the energy's own quadrature: -int EA d_A u_x1' (cos psi u_y'' + sin psi u_z'')
/// dx, d_A = -tc_offset towards the leading edge, psi = pitch + the station's twist, EA d_A cos psi and EA d_A sin psi
/// linear between stations (docs/model.md section 12.6).
double tension_energy(const VariantKey& key, const Parameters& p, const std::vector<double>& q)
{
    const CoordinateLayout layout = coordinate_layout(key);
    const auto derivative = [&](const FieldBasis& b, FieldKind kind, int n, double xi) {
        double sum = 0.0;
        for (int j = 0; j < b.size(); ++j) {
            const Jet<double> phi = b.at(j, xi);
            sum += q[static_cast<std::size_t>(layout.first(kind) + j)] * (n == 1 ? phi.d1 : phi.d2) / std::pow(p.L, n);
        }
        return sum;
    };
    // Cuts at the stations and at every 24th of the span: the ends of FEM's elements of either field (halves, thirds).
    std::vector<double> cuts = p.stations;
    for (int k = 0; k <= 24; ++k) cuts.push_back(k / 24.0);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    const QuadratureRule rule = composite_gauss_legendre(cuts, 10);
    double sum = 0.0;
    for (std::size_t n = 0; n < rule.nodes.size(); ++n) {
        const double xi = rule.nodes[n];
        std::size_t k = 0;
        while (k + 2 < p.stations.size() && xi > p.stations[k + 1]) ++k;
        const double t = (xi - p.stations[k]) / (p.stations[k + 1] - p.stations[k]);
        double c = 0.0, s = 0.0;
        for (std::size_t at : {k, k + 1}) {
            const double weight = at == k ? 1.0 - t : t, EA = p.profile[9 * at + 2];
            const double angle = p.pitch + p.profile[9 * at + 5], d = -p.offsets[2 * at + 1];
            c += weight * EA * d * std::cos(angle);
            s += weight * EA * d * std::sin(angle);
        }
        const double stretch = derivative(key.axial_basis(), FieldKind::axial, 1, xi);
        const double kappa = c * derivative(key.transverse_basis(), FieldKind::inplane, 2, xi) +
                             s * derivative(key.flap_basis(), FieldKind::flap, 2, xi);
        sum -= rule.weights[n] * stretch * kappa;
    }
    return p.L * sum;
}

}  // namespace

TEST_CASE("section offsets: the tension centre's strain energy is EA's cross term at the offset strain",
          "[section_offsets][tension_centre]")
{
    // A turning chord, a pitch and a tension centre that changes sign along the span, beside a centre of mass off the
    // axis: the generated U's share of the tension centre (U at the offsets less U with it 0) against the quadrature
    // of the energy, at states that bend both ways and stretch.
    for (const Method method : {Method::fem, Method::amm}) {
        VariantKey key{.method = method, .nx = 3, .ny = 4, .order = Order::first, .drive = Drive::torque};
        key.nz = 4, key.nt = 2;
        key.extras.tabulated = key.extras.offsets = key.extras.pitch = true;
        Parameters p = blade({{0.0, 3.0, 900.0, 7e6, 300.0, 80.0, 0.3, 0.02, 0.10, 0.05, 0.02},
                              {0.4, 2.0, 600.0, 5e6, 200.0, 50.0, 0.9, 0.01, 0.07, -0.02, -0.03},
                              {1.0, 1.0, 200.0, 2e6, 90.0, 20.0, -0.4, 0.01, 0.03, 0.08, 0.01}},
                             2.0);
        p.pitch = 0.2;
        Parameters still = p;
        for (std::size_t k = 1; k < still.offsets.size(); k += 2) still.offsets[k] = 0.0;
        const auto offset = make_model(key, p, ModelSource::generated);
        const auto none = make_model(key, still, ModelSource::generated);
        const int nq = key.nq();
        for (int trial = 0; trial < 3; ++trial) {
            std::vector<double> q(static_cast<std::size_t>(nq)), qd(q.size(), 0.0);
            for (int k = 0; k < nq; ++k) q[static_cast<std::size_t>(k)] = 0.01 * std::sin(1.3 * k + 2.1 * trial + 0.2);
            const double generated = offset->energy(HubInput{}, q.data(), qd.data()).U -
                                     none->energy(HubInput{}, q.data(), qd.data()).U;
            const double exact = tension_energy(key, p, q);
            INFO(key.name() << ", trial " << trial << ": generated " << generated << ", quadrature " << exact);
            CHECK(std::abs(exact) > 1e-3 * std::abs(offset->energy(HubInput{}, q.data(), qd.data()).U));
            CHECK(generated == Approx(exact).epsilon(1e-10));
        }
    }
}

namespace {

/// The frequencies (rad/s) below `most` of a uniform cantilever of axial stiffness EA and bending stiffness EI (about
/// the reference axis) whose tension centre lies e off the axis in the plane of bending, mass m per length: the roots
/// of the clamped-free determinant on the exponential solutions of
///     EA (u'' - e v''') + omega^2 m u = 0,    EI v'''' - EA e u''' - omega^2 m v = 0,
/// N = EA (u' - e v'') = 0, M = EI v'' - EA e u' = 0 and M' = 0 at the tip. Their exponents lambda^2 = s solve
/// (EA EI - EA^2 e^2) s^3 + omega^2 m EI s^2 - omega^2 m EA s - omega^4 m^2 = 0, one root a^2 > 0 and two -b^2, -c^2
/// < 0, and u = k(s) v''' with k = EA e / (EA s + omega^2 m).
std::vector<double> extension_bending_frequencies(double EA, double EI, double m, double e, double L, double most)
{
    const auto determinant = [&](double w) {
        const double w2 = w * w;
        Eigen::Matrix3d companion = Eigen::Matrix3d::Zero();
        const double a3 = EA * EI - EA * EA * e * e, a2 = w2 * m * EI, a1 = -w2 * m * EA, a0 = -w2 * w2 * m * m;
        companion(0, 0) = -a2 / a3, companion(0, 1) = -a1 / a3, companion(0, 2) = -a0 / a3;
        companion(1, 0) = companion(2, 1) = 1.0;
        const Eigen::Vector3cd roots = companion.eigenvalues();
        std::vector<double> s;
        for (int r = 0; r < 3; ++r) {
            REQUIRE(std::abs(roots[r].imag()) <= 1e-9 * std::abs(roots[r]));
            s.push_back(roots[r].real());
        }
        std::sort(s.begin(), s.end());
        REQUIRE((s[0] < 0.0 && s[1] < 0.0 && s[2] > 0.0));
        const double r3[3] = {std::sqrt(s[2]), std::sqrt(-s[1]), std::sqrt(-s[0])}, s3[3] = {s[2], s[1], s[0]};
        // The six solutions' n-th derivatives at x: cosh, sinh (a); cos, sin (b); cos, sin (c).
        const auto f = [&](int col, int n, double x) {
            const double r = r3[col / 2], scale = std::pow(r, n);
            if (col < 2) return scale * ((col + n) % 2 == 0 ? std::cosh(r * x) : std::sinh(r * x));
            return scale * std::cos(r * x + (n - col % 2) * M_PI / 2.0);
        };
        Eigen::Matrix<double, 6, 6> bc;
        for (int col = 0; col < 6; ++col) {
            const double k = EA * e / (EA * s3[col / 2] + w2 * m);
            bc(0, col) = f(col, 0, 0.0);
            bc(1, col) = f(col, 1, 0.0);
            bc(2, col) = k * f(col, 3, 0.0);
            bc(3, col) = k * f(col, 4, L) - e * f(col, 2, L);
            bc(4, col) = EI * f(col, 2, L) - EA * e * k * f(col, 4, L);
            bc(5, col) = EI * f(col, 3, L) - EA * e * k * f(col, 5, L);
        }
        return bc.determinant();
    };
    return test::bracketed_roots(determinant, 0.5, most, 4000, 1e-14);
}

}  // namespace

TEST_CASE("section offsets: the coupled extension and bending frequencies of a cantilever with an offset tension centre",
          "[section_offsets][tension_centre]")
{
    // Uniform, at rest, the chord in the plane of rotation: the offset couples the stretch to lead-lag through the
    // stiffness alone. EA e^2 is a quarter of EI (about the reference axis): the first bending frequency falls from
    // 3.516 towards that of EI - EA e^2; flapwise the blade is 1e4 times stiffer, its modes far above.
    const double EA = 100.0, EI = 1.0, m = 1.0, e = 0.05;
    const Station s{0.0, m, EI, EA, 1e4, 0.0, 0.0, 0.0, 0.0, 0.0, -e};  // tc_offset towards the trailing edge
    Station tip = s;
    tip.x = 1.0;
    const Parameters p = blade({s, tip}, 1.0);
    const std::vector<double> exact = extension_bending_frequencies(EA, EI, m, e, 1.0, 80.0);
    REQUIRE(exact.size() >= 4);
    const auto modes = [&](int n) {
        VariantKey key{.method = Method::bim, .nx = n, .ny = n, .order = Order::first, .drive = Drive::prescribed};
        key.nz = 2;
        key.extras.tabulated = key.extras.offsets = true;
        const auto model = make_model(key, p, ModelSource::generated);
        std::vector<double> f;
        for (const NaturalMode& mode : natural_modes(*model, steady_spin(*model, 0.0)))
            if (mode.kind != "flap") f.push_back(mode.rad_s);
        return f;
    };
    const std::vector<double> coarse = modes(4), fine = modes(8);
    // Coupled 3.027, 15.22, 19.29, 43.33 where uncoupled they would be 3.516 and 22.03 (bending), 15.71 and 47.12
    // (stretch).
    for (std::size_t i = 0; i < 4; ++i) {
        const double e_coarse = std::abs(coarse[i] - exact[i]), e_fine = std::abs(fine[i] - exact[i]);
        INFO("mode " << i + 1 << ": exact " << exact[i] << ", BIM off by " << e_coarse / exact[i] << " then "
                     << e_fine / exact[i]);
        CHECK((e_fine < e_coarse || e_fine <= 1e-9 * exact[i]));
        // BIM n = 8: mode 4 2.5e-7 off, from 8e-3 at n = 4; the lower ones 1e-8 and less.
        CHECK(e_fine <= 1e-6 * exact[i]);
    }
}
