// The tip body's assembled twin (docs/model.md sections 11.1 and 12.3): m_tip and J_tip at x = L, as point values of
// the shape functions there added to section 5.2's matrices and to the flapwise field's, and its weight to section
// 11.3's; in the blade's axes (add_tip_body), its rotation and its centre of mass's offset as forms of section 12.3.
#include <cmath>
#include <utility>

#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

void add_tip(const AssemblyContext& a, ModelMatrices& m)
{
    const BeamMatrices& c = a.c;
    // R_L: the tip's arm about the spin axis, a + L cos(beta_c) with a precone.
    // In the blade's axes (add_tip_body) J_tip turns with the body's axes instead of with theta_dot + u_y_dot'(L).
    const double m_t = a.p.m_tip, J_t = a.key.extras.tip_body ? 0.0 : a.p.J_tip, R = a.p.a + a.p.L * c.cb;
    m.J_o += m_t * R * R;
    m.J_o += J_t;
    m.S_x += m_t * R * c.Phi_x_L;
    m.S_y += m_t * R * c.Phi_y_L;
    m.S_y += J_t * c.Phi_y1_L;
    m.M1 += m_t * c.Phi_x_L.transpose() * c.Phi_x_L;
    m.M2 += m_t * c.Phi_y_L.transpose() * c.Phi_y_L;
    m.M3 += m_t * c.Phi_x_L.transpose() * c.Phi_y_L;
    m.M2r = m.M2 + J_t * c.Phi_y1_L.transpose() * c.Phi_y1_L;
    m.G += m_t * R * c.H_L;
    m.W_o += m_t * R;
    m.W_x += m_t * c.Phi_x_L;
    m.W_y += m_t * c.Phi_y_L;
    if (a.key.order != Order::zero) m.W_H += m_t * c.H_L;
    add_tip_out_of_plane(a, m);
}

void add_tip_out_of_plane(const AssemblyContext& a, ModelMatrices& m)
{
    // The point mass moves with u_z(L) too; J_tip turns with the in-plane slope alone (section 12).
    if (!a.key.out_of_plane()) return;  // a planar variant's section 12.3 matrices are empty
    const BeamMatrices& c = a.c;
    const Eigen::RowVectorXd& z = c.o.Phi_z_L;
    const double m_t = a.p.m_tip, R = a.p.a + a.p.L * c.cb;
    OutOfPlaneMatrices& o = m.o;
    o.M_z += m_t * z.transpose() * z;
    o.M_xz += m_t * c.Phi_x_L.transpose() * z;
    o.M_zy += m_t * z.transpose() * c.Phi_y_L;
    o.S_z += m_t * R * z;
    o.P_z += m_t * z;
    o.C_z += m_t * c.o.H_z_L;
    o.G_z += m_t * R * c.o.H_z_L;
    o.X_ob += m_t * a.p.L;
}

namespace {

using Eigen::MatrixXd;
using namespace fields;

/// Section 11.1's tip body in the blade's axes, without a precone: its centre of mass's offset d = -tip_offset along
/// the tip's chord (at the pitch, psi = pitch + phi(L)) is 12.5's T_g at the tip point (in `point`, each integral
/// replaced by its integrand's value at x = L, m_tip d in place of m d, H(L) and H_z(L) the tail of u_x2), and its
/// rotation 1/2 (P_c |c_dot|^2 + P_n |n_dot|^2 + P_t |t_dot|^2) is T_r's bracket for the chord and its normal (in
/// `point`'s D terms, P_c and P_n at the chord's angle and a quarter turn on) with the axes' turn about the axis and by
/// the spin, and the tangent's. Shape functions' values at the tip: Phi_y'(L), Phi_z'(L), Phi_t(L).
struct TipBodyForms {
    OffsetMatrices point;
    double P_c = 0.0, P_n = 0.0, P_t = 0.0, md = 0.0, cos_pitch = 1.0, sin_pitch = 0.0, J_tip = 0.0;
    Eigen::RowVectorXd y1, z1, t0;
};

/// Section 11.1's tip body in the blade's axes: T_g at the tip point and T_r's bracket for its chord
/// and normal (add_offset_forms), their turn about the axis and by the spin, 1/2 P_c (w^2 cos^2 psi + phi_dot^2) + 1/2
/// P_n (w^2 sin^2 psi + phi_dot^2) with psi = pitch + phi(L), the tangent's 1/2 P_t (w^2 + 2 w u_y_dot' + u_y_dot'^2 +
/// u_z_dot'^2 - w^2 u_z'^2), and the weight of its centre of mass's offset m_tip d c, c the chord to second order:
/// (-sigma, cos psi - u_y' sigma / 2, sin psi - u_z' sigma / 2), sigma = u_y' cos psi + u_z' sin psi (all at x = L).
void add_tip_body_forms(const FieldBlocks& f, const VariantKey& key, const TipBodyForms& b, double alpha,
                        QuadraticForms& q)
{
    add_offset_forms(f, key, b.point, q);
    const double c = b.cos_pitch, s = b.sin_pitch;
    const auto outer = [](const Eigen::RowVectorXd& u, const Eigen::RowVectorXd& v) {
        return MatrixXd(u.transpose() * v);
    };
    f(q.M, P, P) += (b.P_c + b.P_n) * outer(b.t0, b.t0);
    q.J += b.P_c * c * c + b.P_n * s * s + b.P_t;
    f(q.b, P) += (b.P_n - b.P_c) * c * s * b.t0.transpose();
    f(q.K_w, P, P) += (b.P_n - b.P_c) * (c * c - s * s) * outer(b.t0, b.t0);
    f(q.s, B) += b.P_t * b.y1.transpose();
    f(q.M, B, B) += b.P_t * outer(b.y1, b.y1);
    f(q.M, Z, Z) += b.P_t * outer(b.z1, b.z1);
    f(q.K_w, Z, Z) -= b.P_t * outer(b.z1, b.z1);
    // The weight: V_n = o + w^T q - 1/2 q^T H q per unit g, the offset's m_tip d c_n to second order in phi and the
    // slopes.
    const auto both = [&](MatrixXd& m, FieldKind r, FieldKind k, const MatrixXd& v) { f.add_both(m, r, k, v); };
    const double md = b.md;
    f(q.V_i.w, B) -= md * c * b.y1.transpose();
    f(q.V_i.w, Z) -= md * s * b.z1.transpose();
    both(q.V_i.H, P, B, -md * s * outer(b.t0, b.y1));
    both(q.V_i.H, P, Z, md * c * outer(b.t0, b.z1));
    q.V_j.o += md * c;
    f(q.V_j.w, P) -= md * s * b.t0.transpose();
    f(q.V_j.H, P, P) += md * c * outer(b.t0, b.t0);
    f(q.V_j.H, B, B) += md * c * outer(b.y1, b.y1);
    both(q.V_j.H, B, Z, 0.5 * md * s * outer(b.y1, b.z1));
    q.V_k.o += md * s;
    f(q.V_k.w, P) += md * c * b.t0.transpose();
    f(q.V_k.H, P, P) += md * s * outer(b.t0, b.t0);
    f(q.V_k.H, Z, Z) += md * s * outer(b.z1, b.z1);
    both(q.V_k.H, B, Z, 0.5 * md * c * outer(b.y1, b.z1));
    // Rayleigh damping's mass keeps J_tip turning with the in-plane slope (11.4), which the body's form replaces.
    f(q.Dm, B, B) += alpha * b.J_tip * outer(b.y1, b.y1);
}

}  // namespace

void add_tip_body(const AssemblyContext& a, ModelMatrices& m)
{
    const Parameters& p = a.p;
    const double L = p.L, d = -p.tip_offset, md = p.m_tip * d;
    const double c = std::cos(p.pitch), s = std::sin(p.pitch);
    TipBodyForms b;
    // The body's second moments of mass along its axes about the tip point: its inertias about its centre, J_tip
    // (lag, about the chord's normal), J_tip_flap (about the chord) and J_tip_twist (about the tangent), with m d^2
    // about the two axes across the chord.
    b.P_c = 0.5 * (p.J_tip_twist + p.J_tip - p.J_tip_flap) + md * d;
    b.P_n = 0.5 * (p.J_tip_twist + p.J_tip_flap - p.J_tip);
    b.P_t = 0.5 * (p.J_tip_flap + p.J_tip - p.J_tip_twist);
    b.md = md, b.cos_pitch = c, b.sin_pitch = s, b.J_tip = p.J_tip;
    b.y1 = a.c.Phi_y1_L, b.z1 = a.c.o.Phi_z1_L, b.t0 = a.c.o.Phi_t_L;
    // T_g at the tip point with C = m_tip d cos(pitch), S = m_tip d sin(pitch); T_r's bracket with the chord's P_c and
    // its normal's P_n, whose angle is the chord's a quarter turn on (cos -> -sin, sin -> cos); no tension centre. The
    // integrands at x = L, by a rule of one node there; the tail of u_x2's term is the whole beam's, H(L) and H_z(L).
    const double C = md * c, S = md * s, D = b.P_c - b.P_n;
    const OffsetValues v{{C}, {S}, {b.P_c + b.P_n}, {D * (c * c - s * s)}, {2.0 * D * c * s}, {0.0}, {0.0}, {0.0}};
    b.point = offset_matrices(a.key, QuadratureRule{{1.0}, {1.0 / L}}, L, p.a, v);
    b.point.Ct_yy = C * a.c.H_L;
    b.point.Ct_zz = C * a.c.o.H_z_L;
    const FieldBlocks f(a.key);
    QuadraticForms forms = zero_forms(f.size());
    add_tip_body_forms(f, a.key, b, m.alpha, forms);
    m.forms.push_back(std::move(forms));
}

}  // namespace hubbeam
