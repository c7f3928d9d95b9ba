// docs/model.md section 12.3's integrals of the flapwise and twist fields by Gauss-Legendre quadrature: the chord's
// angle enters through cos 2 beta(x) and sin 2 beta(x) evaluated at the nodes, on a rule fine enough that the
// pre-twist's cosines integrate to round-off as the shape functions' products do exactly.
#include "models/assembled/out_of_plane_matrices.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "profile.hpp"

namespace hubbeam {

namespace {

using Eigen::ArrayXd;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// A basis's functions and their first two xi-derivatives at the nodes (one row per node, one column per function).
struct AtNodes {
    MatrixXd v, d1, d2;
};

/// The basis's values at the rule's nodes.
AtNodes at_nodes(const FieldBasis& basis, const QuadratureRule& rule)
{
    const int nn = static_cast<int>(rule.nodes.size()), n = basis.size();
    AtNodes a{MatrixXd(nn, n), MatrixXd(nn, n), MatrixXd(nn, n)};
    for (int r = 0; r < nn; ++r)
        for (int i = 0; i < n; ++i) {
            const Jet<double> f = basis.at(i, rule.nodes[r]);
            a.v(r, i) = f.v;
            a.d1(r, i) = f.d1;
            a.d2(r, i) = f.d2;
        }
    return a;
}

/// int_0^1 P^T diag(w) Q dxi by the rule, from values at the nodes.
MatrixXd product(const MatrixXd& P, const VectorXd& w, const MatrixXd& Q)
{
    return P.transpose() * w.asDiagonal() * Q;
}

/// P^T diag(w) P, exactly symmetric.
MatrixXd gram(const MatrixXd& P, const VectorXd& w)
{
    const MatrixXd R = product(P, w, P);
    return 0.5 * (R + R.transpose());
}

/// Gauss-Legendre on the common refinement of the bases' pieces and a profile's stations. A polynomial integrand here
/// is a product of two pieces times at most a quadratic in xi (degree 2 max + 2), or a profile's linear distribution
/// (degree 2 max + 1), and the pre-twist multiplies products of two pieces (degree 2 max) by cos 2 beta(xi) or sin 2
/// beta(xi): cut into pieces on each of which 2 twist xi turns by at most 1 rad, with max + 10 points the rule is exact
/// to degree 2 max + 19 there, so what it misses of their Taylor series about the piece's start is below 1/20! ~ 4e-19
/// of the integral. AMM: the composite rule converged to round-off for the highest mode, on which the slow cosine (its
/// panels no wider than the pieces) and a profile's kinks (cuts) change nothing.
QuadratureRule section_rule(const std::vector<FieldBasis>& bases, const std::vector<double>& stations, double twist)
{
    int largest = 0, degree = 0;
    bool polynomial = true;
    std::vector<double> cuts{0.0, 1.0};
    for (const FieldBasis& b : bases) {
        if (b.size() == 0) continue;
        largest = std::max(largest, b.size());
        polynomial = polynomial && b.polynomial();
        if (!b.polynomial()) continue;
        degree = std::max(degree, b.degree());
        for (int k = 1; k < b.intervals(); ++k) cuts.push_back(static_cast<double>(k) / b.intervals());
    }
    if (!polynomial) {
        if (stations.empty()) return transcendental_rule(largest);
        const int panels = transcendental_panels(largest);
        cuts.clear();
        for (int k = 0; k <= panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    }
    cuts.insert(cuts.end(), stations.begin(), stations.end());
    const int turns = static_cast<int>(std::ceil(2.0 * std::abs(twist)));
    for (int k = 1; k < turns; ++k) cuts.push_back(static_cast<double>(k) / turns);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-14; }), cuts.end());
    cuts.back() = 1.0;
    return composite_gauss_legendre(cuts, polynomial ? degree + 10 : transcendental_points);
}

/// The section at the nodes (docs/model.md sections 12 and 12.4): mass per length, the bending stiffness in the hub's
/// axes (K_yy, K_zz, K_yz of EI_e kappa_c^2 + EI_f kappa_n^2 = K_yy u_y''^2 + K_zz u_z''^2 + 2 K_yz u_y'' u_z''), GJ,
/// j_p = j_c + j_n, the inertia about k at phi = 0 (j_c s^2 + j_n c^2), the propeller moment's drive (j_c - j_n) s c
/// and stiffness (j_c - j_n) C2; the tails int_xi^1 m dt and int_xi^1 m t dt; int_0^1 m t dt.
struct BladeAtNodes {
    ArrayXd m, K_yy, K_zz, K_yz, GJ, j_p, j_k, drive, stiffness, above, above_x;
    double first_moment = 0.0;
};

/// The section's values at one place, its chord at the angle beta and its principal inertia axes at beta_inertia, in
/// the order of BladeAtNodes' first nine arrays.
std::array<double, 9> turned(double m, double EI_e, double EI_f, double GJ, double j_c, double j_n, double beta,
                             double beta_inertia)
{
    const double c = std::cos(beta), s = std::sin(beta), ci = std::cos(beta_inertia), si = std::sin(beta_inertia);
    return {m,         EI_e * c * c + EI_f * s * s,   EI_e * s * s + EI_f * c * c, (EI_e - EI_f) * s * c, GJ,
            j_c + j_n, j_c * si * si + j_n * ci * ci, (j_c - j_n) * si * ci,       (j_c - j_n) * (ci * ci - si * si)};
}

/// A uniform section turned by pitch + twist xi at each node, or a profile's: its stations' sections turned by pitch +
/// their tabulated angle, each value linear between stations (section 12.4).
BladeAtNodes blade_at_nodes(const VariantKey& key, const Parameters& p, const std::vector<double>& stations,
                            const ArrayXd& xi)
{
    const Eigen::Index nn = xi.size();
    const double pitch = key.extras.pitch ? p.pitch : 0.0;
    BladeAtNodes b;
    for (ArrayXd* a :
         {&b.m, &b.K_yy, &b.K_zz, &b.K_yz, &b.GJ, &b.j_p, &b.j_k, &b.drive, &b.stiffness, &b.above, &b.above_x})
        a->resize(nn);
    const auto store = [&](Eigen::Index r, const std::array<double, 9>& v) {
        ArrayXd* arrays[] = {&b.m, &b.K_yy, &b.K_zz, &b.K_yz, &b.GJ, &b.j_p, &b.j_k, &b.drive, &b.stiffness};
        for (std::size_t j = 0; j < v.size(); ++j) (*arrays[j])(r) = v[j];
    };
    if (stations.empty()) {
        // Section 12's uniform section: EI_e = E I, EI_f = E I_flap, GJ = G J_t; j_n = rho I, j_c = rho I_flap; a taper
        // scales the area by s = 1 + r1 xi, the edgewise values by i_e and the flapwise ones and GJ by i_f (width: the
        // flapwise thickness, i_e = s, i_f = s^3; depth: the chord, i_e = s^3, i_f = s).
        const double m = p.rho * p.S, twist = key.extras.twist ? p.twist : 0.0;
        const Taper taper = key.extras.taper;
        const double r1 = taper == Taper::uniform ? 0.0 : p.tip_ratio - 1.0;
        for (Eigen::Index r = 0; r < nn; ++r) {
            const double s = 1.0 + r1 * xi(r), cube = s * s * s;
            const double i_e = taper == Taper::depth ? cube : s, i_f = taper == Taper::width ? cube : s;
            store(r, turned(m * s, p.E * p.I * i_e, p.E * p.I_flap * i_f, p.G * p.J_t * i_f, p.rho * p.I_flap * i_f,
                            p.rho * p.I * i_e, pitch + twist * xi(r), pitch + twist * xi(r)));
        }
        b.above = m * ((1.0 - xi) + 0.5 * r1 * (1.0 - xi * xi));
        b.above_x = m * (0.5 * (1.0 - xi * xi) + r1 * (1.0 - xi * xi * xi) / 3.0);
        b.first_moment = m * (0.5 + r1 / 3.0);
        return b;
    }
    // The stations' sections turned, one row of nine each, linear between stations.
    const std::size_t n = stations.size(), w = p.profile.size() / n;
    std::vector<double> at_station;
    for (std::size_t k = 0; k < n; ++k) {
        const auto v = [&](ProfileValue j) { return p.profile[w * k + static_cast<std::size_t>(j)]; };
        const std::array<double, 9> row =
            turned(v(ProfileValue::m), v(ProfileValue::EI), v(ProfileValue::EI_flap), v(ProfileValue::GJ),
                   v(ProfileValue::j_c), v(ProfileValue::j_n), pitch + v(ProfileValue::twist),
                   pitch + v(ProfileValue::inertia_twist));
        at_station.insert(at_station.end(), row.begin(), row.end());
    }
    const MassTail tail0(stations, p.profile, 0), tail1(stations, p.profile, 1);
    for (Eigen::Index r = 0; r < nn; ++r) {
        std::array<double, 9> row;
        for (std::size_t j = 0; j < row.size(); ++j) row[j] = linear_between(stations, at_station, j, xi(r));
        store(r, row);
        b.above(r) = tail0(xi(r));
        b.above_x(r) = tail1(xi(r));
    }
    b.first_moment = tail1(0.0);
    return b;
}

/// Phi(1) of every function of a basis (1 x n), or with slope, its xi-derivative there.
Eigen::RowVectorXd at_tip(const FieldBasis& basis, bool slope = false)
{
    Eigen::RowVectorXd r(basis.size());
    for (int i = 0; i < basis.size(); ++i) {
        const Jet<double> f = basis.at(i, 1.0);
        r(i) = slope ? f.d1 : f.v;
    }
    return r;
}

}  // namespace

OutOfPlaneMatrices assemble_out_of_plane(const VariantKey& key, const Parameters& p)
{
    const FieldBasis axial = key.axial_basis(), inplane = key.transverse_basis(), flap = key.flap_basis(),
                     twist = key.twist_basis();
    const std::vector<double> stations = p.stations;
    const QuadratureRule rule = section_rule({axial, inplane, flap, twist}, stations, key.extras.twist ? p.twist : 0.0);
    const int nn = static_cast<int>(rule.nodes.size());
    const ArrayXd xi = Eigen::Map<const ArrayXd>(rule.nodes.data(), nn);
    const VectorXd w = Eigen::Map<const VectorXd>(rule.weights.data(), nn);
    const AtNodes X = at_nodes(axial, rule), Y = at_nodes(inplane, rule), Z = at_nodes(flap, rule),
                  T = at_nodes(twist, rule);
    const BladeAtNodes b = blade_at_nodes(key, p, stations, xi);
    const double L = p.L, a = p.a, cb = key.extras.cone ? std::cos(p.precone) : 1.0;

    // In xi: dx = L dxi, ' = (1/L) d/dxi; the weights below carry the section's factors and the powers of L.
    const auto weighed = [&](const ArrayXd& f) { return VectorXd((w.array() * f).matrix()); };
    const VectorXd w_m = weighed(L * b.m);
    OutOfPlaneMatrices o;
    o.M_z = gram(Z.v, w_m);
    o.M_xz = product(X.v, w_m, Z.v);
    o.M_zy = product(Z.v, w_m, Y.v);
    o.S_z = (Z.v.transpose() * weighed(L * b.m * (a + cb * L * xi))).transpose();
    o.P_z = (Z.v.transpose() * w_m).transpose();
    // H_z(x) weighed by int_x^L m dt = L above and by int_x^L m t dt = L^2 above_x, over dx / L^2.
    o.C_z = gram(Z.d1, weighed(b.above));
    o.G_z = a * o.C_z + cb * gram(Z.d1, weighed(L * b.above_x));
    o.X_ob = L * L * b.first_moment;
    const double L3 = L * L * L;
    o.K_yy = gram(Y.d2, weighed(b.K_yy)) / L3;
    o.K_zz = gram(Z.d2, weighed(b.K_zz)) / L3;
    o.K_yz = product(Y.d2, weighed(b.K_yz), Z.d2) / L3;
    o.K_t = gram(T.d1, weighed(b.GJ)) / L;
    o.M_t = gram(T.v, weighed(L * b.j_p));
    o.S_t = (T.v.transpose() * weighed(L * b.j_p)).transpose();
    o.F_t = (T.v.transpose() * weighed(L * b.drive)).transpose();
    o.K_p = gram(T.v, weighed(L * b.stiffness));
    o.J_p = L * weighed(b.j_p).sum();
    o.J_n = L * weighed(b.j_k).sum();
    o.Phi_z_L = at_tip(flap);
    o.Phi_z1_L = at_tip(flap, true) / L;
    o.H_z_L = gram(Z.d1, w) / L;
    o.Phi_t_L = at_tip(twist);
    return o;
}

OffsetMatrices offset_matrices(const VariantKey& key, const QuadratureRule& rule, double L, double a,
                               const OffsetValues& v)
{
    const int nn = static_cast<int>(rule.nodes.size());
    const ArrayXd xi = Eigen::Map<const ArrayXd>(rule.nodes.data(), nn);
    const VectorXd w = Eigen::Map<const VectorXd>(rule.weights.data(), nn);
    const AtNodes X = at_nodes(key.axial_basis(), rule), Y = at_nodes(key.transverse_basis(), rule),
                  Z = at_nodes(key.flap_basis(), rule), T = at_nodes(key.twist_basis(), rule);
    const auto at = [&](const std::vector<double>& f) { return ArrayXd(Eigen::Map<const ArrayXd>(f.data(), nn)); };
    const ArrayXd C = at(v.C), S = at(v.S), D = at(v.D), D2c = at(v.D2c), Ec = at(v.Ec), Es = at(v.Es), Ct = at(v.Ct);
    const ArrayXd R = a + L * xi;
    // In xi: dx = L dxi and ' = (1/L) d/dxi, so that each integral's weight carries L to the power 1 - (its primes).
    const auto weighed = [&](const ArrayXd& f, int primes) {
        return VectorXd((w.array() * f).matrix() * std::pow(L, 1 - primes));
    };
    const ArrayXd Dcc = 0.5 * (D + D2c), Dss = 0.5 * (D - D2c), Dcs = 0.5 * at(v.D2s);
    const auto row = [](const MatrixXd& P, const VectorXd& u) {
        return Eigen::RowVectorXd((P.transpose() * u).transpose());
    };
    OffsetMatrices o;
    o.C_zt = product(Z.v, weighed(C, 0), T.v);
    o.S_yt = product(Y.v, weighed(S, 0), T.v);
    o.C_xy1 = product(X.v, weighed(C, 1), Y.d1);
    o.S_xz1 = product(X.v, weighed(S, 1), Z.d1);
    o.S_xt = product(X.v, weighed(S, 0), T.v);
    o.C_yy1 = product(Y.v, weighed(C, 1), Y.d1);
    o.S_yz1 = product(Y.v, weighed(S, 1), Z.d1);
    o.RC_tt = product(T.v, weighed(R * C, 0), T.v);
    o.RC_yy = product(Y.d1, weighed(R * C, 2), Y.d1);
    o.RS_yz = product(Y.d1, weighed(R * S, 2), Z.d1);
    o.RS_ty = product(T.v, weighed(R * S, 1), Y.d1);
    o.RC_tz = product(T.v, weighed(R * C, 1), Z.d1);
    o.Ct_yy = product(Y.d1, weighed(Ct, 2), Y.d1);
    o.Ct_zz = product(Z.d1, weighed(Ct, 2), Z.d1);
    o.Dcc_yy = product(Y.d1, weighed(Dcc, 2), Y.d1);
    o.Dss_zz = product(Z.d1, weighed(Dss, 2), Z.d1);
    o.Dcs_yz = product(Y.d1, weighed(Dcs, 2), Z.d1);
    o.D_zt = product(Z.d1, weighed(D, 1), T.v);
    o.Dcs_ty = product(T.v, weighed(Dcs, 1), Y.d1);
    o.D2c_tz = product(T.v, weighed(D2c, 1), Z.d1);
    o.E_xy = product(X.d1, weighed(Ec, 3), Y.d2);
    o.E_xz = product(X.d1, weighed(Es, 3), Z.d2);
    o.C_x = row(X.v, weighed(C, 0));
    o.RS_t = row(T.v, weighed(R * S, 0));
    o.Dcc_y = row(Y.d1, weighed(Dcc, 1));
    o.Dcs_z = row(Z.d1, weighed(Dcs, 1));
    o.C_y = row(Y.v, weighed(C, 0));
    o.RC_y1 = row(Y.d1, weighed(R * C, 1));
    o.RS_z1 = row(Z.d1, weighed(R * S, 1));
    return o;
}

OffsetMatrices assemble_offsets(const VariantKey& key, const Parameters& p)
{
    const std::vector<double>& stations = p.stations;
    const std::size_t n = stations.size(), width = p.profile.size() / n;
    if (n < 2 || p.offsets.size() != 2 * n)
        throw std::invalid_argument("section offsets: the table has " + std::to_string(p.offsets.size()) +
                                    " offsets for " + std::to_string(n) + " stations, 2 a station expected");
    // The distributions at the stations (m d and EA d_A along the chord turned by the pitch and the station's angle),
    // from the table's own columns: cg_offset and tc_offset in that order, towards the trailing edge.
    const double pitch = key.extras.pitch ? p.pitch : 0.0;
    std::vector<double> at_station;
    for (std::size_t k = 0; k < n; ++k) {
        const double* row = p.profile.data() + width * k;
        const double m = row[static_cast<std::size_t>(ProfileValue::m)],
                     EA = row[static_cast<std::size_t>(ProfileValue::ES)];
        const double psi = pitch + row[static_cast<std::size_t>(ProfileValue::twist)];
        const double d = -p.offsets[2 * k], d_A = -p.offsets[2 * k + 1], c = std::cos(psi), s = std::sin(psi);
        at_station.insert(at_station.end(), {m * d * c, m * d * s, m * d * d, m * d * d * std::cos(2.0 * psi),
                                             m * d * d * std::sin(2.0 * psi), EA * d_A * c, EA * d_A * s});
    }
    const QuadratureRule rule =
        section_rule({key.axial_basis(), key.transverse_basis(), key.flap_basis(), key.twist_basis()}, stations, 0.0);
    OffsetValues v;
    std::vector<double>* values[] = {&v.C, &v.S, &v.D, &v.D2c, &v.D2s, &v.Ec, &v.Es};
    const MassTail tail(stations, at_station, 0);  // int_xi^1 C dt: C, the first column, is read as a table's m
    for (const double xi : rule.nodes) {
        for (std::size_t j = 0; j < 7; ++j) values[j]->push_back(linear_between(stations, at_station, j, xi));
        v.Ct.push_back(p.L * tail(xi));  // C^(x) = L int_xi^1 C dt
    }
    return offset_matrices(key, rule, p.L, p.a, v);
}

}  // namespace hubbeam
