// The tip body's assembled twin (docs/model.md sections 11.1 and 12.3): m_tip and J_tip at x = L, as point values of
// the shape functions there added to section 5.2's matrices and to the flapwise field's, and its weight to section
// 11.3's.
#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

void add_tip(const AssemblyContext& a, ModelMatrices& m)
{
    const BeamMatrices& c = a.c;
    // R_L: the tip's arm about the spin axis, a + L cos(beta_c) with a precone.
    const double m_t = a.p.m_tip, J_t = a.p.J_tip, R = a.p.a + a.p.L * c.cb;
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

}  // namespace hubbeam
