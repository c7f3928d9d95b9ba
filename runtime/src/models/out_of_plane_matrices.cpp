// docs/model.md section 12.3's integrals of the flapwise and twist fields by Gauss-Legendre quadrature: the chord's
// angle enters through cos 2 beta(x) and sin 2 beta(x) evaluated at the nodes, on a rule fine enough that the
// pre-twist's cosines integrate to round-off as the shape functions' products do exactly.
#include "models/out_of_plane_matrices.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

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

/// Gauss-Legendre on the common refinement of the bases' pieces. A polynomial integrand here is a product of two
/// pieces times at most a quadratic in xi (degree 2 max + 2), and the pre-twist multiplies products of two pieces
/// (degree 2 max) by cos 2 beta(xi) or sin 2 beta(xi): with max + 10 points the rule is exact to degree 2 max + 19, so
/// what it misses of their Taylor series in (2 twist xi), |2 twist| <= 1 (max_twist), is below 1/20! ~ 4e-19 of the
/// integral. AMM: the composite rule converged to round-off for the highest mode, on which the slow cosine changes
/// nothing.
QuadratureRule section_rule(const std::vector<FieldBasis>& bases)
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
    if (!polynomial) return transcendental_rule(largest);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double u, double v) { return v - u < 1e-14; }), cuts.end());
    return composite_gauss_legendre(cuts, degree + 10);
}

/// Phi(1) of every function of a basis (1 x n).
Eigen::RowVectorXd at_tip(const FieldBasis& basis)
{
    Eigen::RowVectorXd r(basis.size());
    for (int i = 0; i < basis.size(); ++i) r(i) = basis.at(i, 1.0).v;
    return r;
}

}  // namespace

std::string out_of_plane_problem(const VariantKey& key)
{
    if (!key.out_of_plane() || (key.extras.taper == Taper::uniform && !key.extras.profile())) return {};
    return "a taper or a tabulated profile does not combine with a beam that leaves the plane (nz, nt, pitch, "
           "pre-twist, precone: docs/model.md section 12), and variant " +
           key.name() + " has both";
}

OutOfPlaneMatrices assemble_out_of_plane(const VariantKey& key, const Parameters& p)
{
    if (const std::string why = out_of_plane_problem(key); !why.empty()) throw std::invalid_argument(why);
    const FieldBasis axial = key.axial_basis(), inplane = key.transverse_basis(), flap = key.flap_basis(),
                     twist = key.twist_basis();
    const QuadratureRule rule = section_rule({axial, inplane, flap, twist});
    const int nn = static_cast<int>(rule.nodes.size());
    const ArrayXd xi = Eigen::Map<const ArrayXd>(rule.nodes.data(), nn);
    const VectorXd w = Eigen::Map<const VectorXd>(rule.weights.data(), nn);
    const AtNodes X = at_nodes(axial, rule), Y = at_nodes(inplane, rule), Z = at_nodes(flap, rule),
                  T = at_nodes(twist, rule);

    // Section 12's section: EI_e = E I (the planar EI), EI_f = E I_flap, GJ = G J_t; j_n = rho I, j_c = rho I_flap.
    const double L = p.L, a = p.a, m = p.rho * p.S, EI_e = p.E * p.I, EI_f = p.E * p.I_flap, GJ = p.G * p.J_t;
    const double j_n = p.rho * p.I, j_c = p.rho * p.I_flap, j_p = j_n + j_c;
    const double cb = key.extras.cone ? std::cos(p.precone) : 1.0;
    const ArrayXd beta = (key.extras.pitch ? p.pitch : 0.0) + (key.extras.twist ? p.twist : 0.0) * xi;
    const ArrayXd C2 = (2.0 * beta).cos(), S2 = (2.0 * beta).sin();

    // In xi: dx = L dxi, ' = (1/L) d/dxi; the weights below carry the section's factors and the powers of L.
    const auto weighed = [&](const ArrayXd& f) { return VectorXd((w.array() * f).matrix()); };
    const ArrayXd one = ArrayXd::Ones(nn);
    OutOfPlaneMatrices o;
    o.M_z = m * L * gram(Z.v, w);
    o.M_xz = m * L * product(X.v, w, Z.v);
    o.M_zy = m * L * product(Z.v, w, Y.v);
    o.S_z = (Z.v.transpose() * weighed(m * L * (a + cb * L * xi))).transpose();
    o.P_z = (Z.v.transpose() * weighed(m * L * one)).transpose();
    // H_z(x) weighed by int_x^L m dt = m L (1 - xi) and by int_x^L m t dt = m L^2 (1 - xi^2)/2, over dx / L^2.
    o.C_z = gram(Z.d1, weighed(m * (1.0 - xi)));
    o.G_z = a * o.C_z + cb * gram(Z.d1, weighed(0.5 * m * L * (1.0 - xi * xi)));
    o.X_ob = 0.5 * m * L * L;
    // EI_e kappa_c^2 + EI_f kappa_n^2 = u_y''^2 (EI_e c^2 + EI_f s^2) + u_z''^2 (EI_e s^2 + EI_f c^2)
    //                                  + 2 u_y'' u_z'' s c (EI_e - EI_f), with c^2 = (1 + C2)/2, s^2 = (1 - C2)/2, 2 s
    //                                  c = S2.
    const double L3 = L * L * L, mean = 0.5 * (EI_e + EI_f), half_difference = 0.5 * (EI_e - EI_f);
    o.K_yy = gram(Y.d2, weighed(mean + half_difference * C2)) / L3;
    o.K_zz = gram(Z.d2, weighed(mean - half_difference * C2)) / L3;
    o.K_yz = product(Y.d2, weighed(half_difference * S2), Z.d2) / L3;
    o.K_t = GJ / L * gram(T.d1, w);
    o.M_t = j_p * L * gram(T.v, w);
    o.S_t = (T.v.transpose() * weighed(j_p * L * one)).transpose();
    o.F_t = (T.v.transpose() * weighed(0.5 * (j_c - j_n) * L * S2)).transpose();
    o.K_p = (j_c - j_n) * L * gram(T.v, weighed(C2));
    o.J_p = j_p * L;
    o.J_n = L * weighed(0.5 * (j_c + j_n) + 0.5 * (j_n - j_c) * C2).sum();
    o.Phi_z_L = at_tip(flap);
    o.H_z_L = gram(Z.d1, w) / L;
    o.Phi_t_L = at_tip(twist);
    return o;
}

}  // namespace hubbeam
