// docs/model.md section 12.3's forms placed block by block. With the precone beta_c (cb = cos, sb = sin) a point's
// position in the hub frame is p = (R + e + cb u_x2, u_y, x sb + sb u_x1 + cb u_z + sb u_x2), R = a + x cb, where
// e = cb u_x1 - sb u_z is its radial displacement: in the plane of rotation e plays the part of the planar model's
// u_x1, so section 5.2's matrices carry over with the radial shape (cb Phi_x, -sb Phi_z) in place of Phi_x.
#include "models/assembled/quadratic_forms.hpp"

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

using namespace fields;

/// T's forms. |r_dot|^2 to second order in the deformation: u_x1_dot^2 + u_y_dot^2 + u_z_dot^2 (the precone turns the
/// axial and flapwise rates, not the sum of their squares), 2 w (R u_y_dot + e u_y_dot - u_y e_dot), and
/// w^2 (R^2 + 2 R e + e^2 + 2 R cb u_x2 + u_y^2); with a twist field, the section's T_sec.
void add_kinetic(const FieldBlocks& f, const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m,
                 QuadraticForms& q)
{
    const OutOfPlaneMatrices& o = m.o;
    const double cb = c.cb, sb = c.sb;
    const bool first = key.order != Order::zero;  // order zero has no u_x2, so no geometric stiffness
    f(q.M, A, A) = m.M1;
    f(q.M, B, B) = m.M2r;
    f(q.s, B) = m.S_y.transpose();
    f(q.N, A, B) = cb * m.M3;
    q.J = m.J_o;
    f(q.b, A) = cb * m.S_x.transpose();
    f(q.K_w, A, A) = cb * cb * m.M1;
    f(q.K_w, B, B) = first ? MatrixXd(m.M2 - cb * m.G) : m.M2;
    if (f.count(Z) > 0) {
        f(q.M, Z, Z) = o.M_z;
        f(q.N, Z, B) = -sb * o.M_zy;
        f(q.b, Z) = -sb * o.S_z.transpose();
        f(q.K_w, A, Z) = -cb * sb * o.M_xz;
        f(q.K_w, Z, A) = -cb * sb * o.M_xz.transpose();
        f(q.K_w, Z, Z) = first ? MatrixXd(sb * sb * o.M_z - cb * o.G_z) : MatrixXd(sb * sb * o.M_z);
    }
    // int m (e u_y_dot - u_y e_dot) = q^T N qd with N skew: its lower blocks are minus the upper ones' transposes.
    q.N = (q.N - q.N.transpose()).eval();
    if (f.count(P) > 0) {
        // T_sec = 1/2 j_p (phi_dot + w sb)^2 + 1/2 w^2 cb^2 (the moment about k at phi = 0 + (j_c - j_n)(S2 phi +
        // C2 phi^2)): the rotary mass, a drive of the twist by the spin's component along the axis, the propeller
        // moment's load and stiffness.
        f(q.M, P, P) = o.M_t;
        f(q.s, P) = sb * o.S_t.transpose();
        q.J += sb * sb * o.J_p + cb * cb * o.J_n;
        f(q.b, P) = cb * cb * o.F_t.transpose();
        f(q.K_w, P, P) = cb * cb * o.K_p;
    }
}

/// U's forms: the strain energy (bending about the turned chord couples u_y and u_z) and the weight along each axis.
void add_potential(const FieldBlocks& f, const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m,
                   QuadraticForms& q)
{
    const OutOfPlaneMatrices& o = m.o;
    const double cb = c.cb, sb = c.sb;
    f(q.K, A, A) = c.K1;
    f(q.K, B, B) = c.K2;
    q.g = m.g;
    q.g_axis = m.g_axis;
    // p_i = R + cb u_x1 - sb u_z + cb u_x2, p_j = u_y, p_k = x sb + sb u_x1 + cb u_z + sb u_x2, with
    // int m u_x2 dx = -1/2 (B^T C B + Z^T C_z Z) (W_H = C with the tip's H(L); zero at order zero, as is u_x2).
    q.V_i.o = m.W_o;
    f(q.V_i.w, A) = cb * m.W_x.transpose();
    f(q.V_i.H, B, B) = cb * m.W_H;
    f(q.V_j.w, B) = m.W_y.transpose();
    q.V_k.o = sb * m.o.X_ob;
    f(q.V_k.w, A) = sb * m.W_x.transpose();
    f(q.V_k.H, B, B) = sb * m.W_H;
    if (f.count(Z) > 0) {
        f(q.K, B, Z) = o.K_yz;
        f(q.K, Z, B) = o.K_yz.transpose();
        f(q.K, Z, Z) = o.K_zz;
        const MatrixXd C_z = key.order == Order::zero ? MatrixXd::Zero(f.count(Z), f.count(Z)) : o.C_z;
        f(q.V_i.w, Z) = -sb * o.P_z.transpose();
        f(q.V_i.H, Z, Z) = cb * C_z;
        f(q.V_k.w, Z) = cb * o.P_z.transpose();
        f(q.V_k.H, Z, Z) = sb * C_z;
    }
    if (f.count(P) > 0) f(q.K, P, P) = o.K_t;
}

}  // namespace

QuadraticForms quadratic_forms(const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m)
{
    const FieldBlocks f(key);
    const int n = f.size();
    QuadraticForms q = zero_forms(n);
    q.Dm.resize(0, 0);
    add_kinetic(f, key, c, m, q);
    add_potential(f, key, c, m, q);
    // D = 1/2 int (alpha (m |u_dot|^2 + j_p phi_dot^2) + beta (the strain energy's density in the rates)) dx with the
    // tip body's alpha m_tip |u_dot(L)|^2 + alpha J_tip u_y_dot'(L)^2: alpha times T's M, beta times U's K.
    q.damped = m.alpha != 0.0 || m.beta != 0.0;
    if (q.damped) q.Dm = m.alpha * q.M + m.beta * q.K;
    // After Dm: Rayleigh damping weighs the section's mass and stiffness without the offsets' couplings and the tip
    // body's rotation (11.4, 12.5, 11.1), which add their forms whole (their own share of Dm with them).
    for (const QuadraticForms& term : m.forms) q.add(term);
    return q;
}

QuadraticForms zero_forms(int n)
{
    QuadraticForms q;
    q.M = q.N = q.P = q.K_w = q.K = q.Dm = MatrixXd::Zero(n, n);
    q.s = q.b = VectorXd::Zero(n);
    q.V_i = q.V_j = q.V_k = {0.0, VectorXd::Zero(n), MatrixXd::Zero(n, n)};
    return q;
}

void QuadraticForms::add(const QuadraticForms& t)
{
    M += t.M, N += t.N, P += t.P, K_w += t.K_w, K += t.K;
    if (damped) Dm += t.Dm;
    s += t.s, b += t.b;
    J += t.J;
    for (auto [v, w] : {std::pair{&V_i, &t.V_i}, {&V_j, &t.V_j}, {&V_k, &t.V_k}}) {
        v->o += w->o;
        v->w += w->w;
        v->H += w->H;
    }
}

}  // namespace hubbeam
