// docs/model.md section 12.3's forms placed block by block. With the precone beta_c (cb = cos, sb = sin) a point's
// position in the hub frame is p = (R + e + cb u_x2, u_y, x sb + sb u_x1 + cb u_z + sb u_x2), R = a + x cb, where
// e = cb u_x1 - sb u_z is its radial displacement: in the plane of rotation e plays the part of the planar model's
// u_x1, so section 5.2's matrices carry over with the radial shape (cb Phi_x, -sb Phi_z) in place of Phi_x.
#include "models/assembled/quadratic_forms.hpp"

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Where each elastic field's coordinates begin in q_e, and how many (0 for an absent field).
struct Fields {
    int A = 0, B = 0, Z = 0, P = 0;
    int nx = 0, ny = 0, nz = 0, nt = 0, n = 0;
};

/// The elastic fields of key's layout, counted from the first coordinate after the hub angle.
Fields fields_of(const VariantKey& key)
{
    const CoordinateLayout l = coordinate_layout(key);
    const int e = l.first_beam();  // after the hub's coordinates (its angle, a moving hub's x_h, y_h)
    const auto start = [&](FieldKind k) {
        const CoordinateField* f = l.find(k);
        return f ? f->first - e : 0;
    };
    return {start(FieldKind::axial),  start(FieldKind::inplane), start(FieldKind::flap),
            start(FieldKind::twist),  l.count(FieldKind::axial), l.count(FieldKind::inplane),
            l.count(FieldKind::flap), l.count(FieldKind::twist), l.size() - e};
}

/// T's forms. |r_dot|^2 to second order in the deformation: u_x1_dot^2 + u_y_dot^2 + u_z_dot^2 (the precone turns the
/// axial and flapwise rates, not the sum of their squares), 2 w (R u_y_dot + e u_y_dot - u_y e_dot), and
/// w^2 (R^2 + 2 R e + e^2 + 2 R cb u_x2 + u_y^2); with a twist field, the section's T_sec.
void add_kinetic(const Fields& f, const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m,
                 QuadraticForms& q)
{
    const OutOfPlaneMatrices& o = m.o;
    const double cb = c.cb, sb = c.sb;
    const bool first = key.order != Order::zero;  // order zero has no u_x2, so no geometric stiffness
    q.M.block(f.A, f.A, f.nx, f.nx) = m.M1;
    q.M.block(f.B, f.B, f.ny, f.ny) = m.M2r;
    q.s.segment(f.B, f.ny) = m.S_y.transpose();
    q.N.block(f.A, f.B, f.nx, f.ny) = cb * m.M3;
    q.J = m.J_o;
    q.b.segment(f.A, f.nx) = cb * m.S_x.transpose();
    q.K_w.block(f.A, f.A, f.nx, f.nx) = cb * cb * m.M1;
    q.K_w.block(f.B, f.B, f.ny, f.ny) = first ? MatrixXd(m.M2 - cb * m.G) : m.M2;
    if (f.nz > 0) {
        q.M.block(f.Z, f.Z, f.nz, f.nz) = o.M_z;
        q.N.block(f.Z, f.B, f.nz, f.ny) = -sb * o.M_zy;
        q.b.segment(f.Z, f.nz) = -sb * o.S_z.transpose();
        q.K_w.block(f.A, f.Z, f.nx, f.nz) = -cb * sb * o.M_xz;
        q.K_w.block(f.Z, f.A, f.nz, f.nx) = -cb * sb * o.M_xz.transpose();
        q.K_w.block(f.Z, f.Z, f.nz, f.nz) = first ? MatrixXd(sb * sb * o.M_z - cb * o.G_z) : MatrixXd(sb * sb * o.M_z);
    }
    // int m (e u_y_dot - u_y e_dot) = q^T N qd with N skew: its lower blocks are minus the upper ones' transposes.
    q.N = (q.N - q.N.transpose()).eval();
    if (f.nt > 0) {
        // T_sec = 1/2 j_p (phi_dot + w sb)^2 + 1/2 w^2 cb^2 (the moment about k at phi = 0 + (j_c - j_n)(S2 phi +
        // C2 phi^2)): the rotary mass, a drive of the twist by the spin's component along the axis, the propeller
        // moment's load and stiffness.
        q.M.block(f.P, f.P, f.nt, f.nt) = o.M_t;
        q.s.segment(f.P, f.nt) = sb * o.S_t.transpose();
        q.J += sb * sb * o.J_p + cb * cb * o.J_n;
        q.b.segment(f.P, f.nt) = cb * cb * o.F_t.transpose();
        q.K_w.block(f.P, f.P, f.nt, f.nt) = cb * cb * o.K_p;
    }
}

/// U's forms: the strain energy (bending about the turned chord couples u_y and u_z) and the weight along each axis.
void add_potential(const Fields& f, const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m,
                   QuadraticForms& q)
{
    const OutOfPlaneMatrices& o = m.o;
    const double cb = c.cb, sb = c.sb;
    q.K.block(f.A, f.A, f.nx, f.nx) = c.K1;
    q.K.block(f.B, f.B, f.ny, f.ny) = c.K2;
    q.g = m.g;
    q.g_axis = m.g_axis;
    // p_i = R + cb u_x1 - sb u_z + cb u_x2, p_j = u_y, p_k = x sb + sb u_x1 + cb u_z + sb u_x2, with
    // int m u_x2 dx = -1/2 (B^T C B + Z^T C_z Z) (W_H = C with the tip's H(L); zero at order zero, as is u_x2).
    q.V_i.o = m.W_o;
    q.V_i.w.segment(f.A, f.nx) = cb * m.W_x.transpose();
    q.V_i.H.block(f.B, f.B, f.ny, f.ny) = cb * m.W_H;
    q.V_j.w.segment(f.B, f.ny) = m.W_y.transpose();
    q.V_k.o = sb * m.o.X_ob;
    q.V_k.w.segment(f.A, f.nx) = sb * m.W_x.transpose();
    q.V_k.H.block(f.B, f.B, f.ny, f.ny) = sb * m.W_H;
    if (f.nz > 0) {
        q.K.block(f.B, f.Z, f.ny, f.nz) = o.K_yz;
        q.K.block(f.Z, f.B, f.nz, f.ny) = o.K_yz.transpose();
        q.K.block(f.Z, f.Z, f.nz, f.nz) = o.K_zz;
        const MatrixXd C_z = key.order == Order::zero ? MatrixXd::Zero(f.nz, f.nz) : o.C_z;
        q.V_i.w.segment(f.Z, f.nz) = -sb * o.P_z.transpose();
        q.V_i.H.block(f.Z, f.Z, f.nz, f.nz) = cb * C_z;
        q.V_k.w.segment(f.Z, f.nz) = cb * o.P_z.transpose();
        q.V_k.H.block(f.Z, f.Z, f.nz, f.nz) = sb * C_z;
    }
    if (f.nt > 0) q.K.block(f.P, f.P, f.nt, f.nt) = o.K_t;
}

/// An axis's weight of n coordinates, all zero.
AxisWeight no_weight(int n)
{
    return {0.0, VectorXd::Zero(n), MatrixXd::Zero(n, n)};
}

}  // namespace

QuadraticForms quadratic_forms(const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m)
{
    const Fields f = fields_of(key);
    const int n = f.n;
    QuadraticForms q;
    q.M = q.N = q.K_w = q.K = MatrixXd::Zero(n, n);
    q.s = q.b = VectorXd::Zero(n);
    q.V_i = q.V_j = q.V_k = no_weight(n);
    add_kinetic(f, key, c, m, q);
    add_potential(f, key, c, m, q);
    // D = 1/2 int (alpha (m |u_dot|^2 + j_p phi_dot^2) + beta (the strain energy's density in the rates)) dx with the
    // tip body's alpha m_tip |u_dot(L)|^2 + alpha J_tip u_y_dot'(L)^2: alpha times T's M, beta times U's K.
    q.damped = m.alpha != 0.0 || m.beta != 0.0;
    if (q.damped) q.Dm = m.alpha * q.M + m.beta * q.K;
    return q;
}

}  // namespace hubbeam
