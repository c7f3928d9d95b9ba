// The tip body's assembled twin (docs/model.md section 11.1): m_tip and J_tip at x = L, as point values of the shape
// functions there added to section 5.2's matrices, and its weight to section 11.3's.
#include "models/assembled_terms.hpp"

namespace hubbeam {

void add_tip(const AssemblyContext& a, ModelMatrices& m)
{
    const BeamMatrices& c = a.c;
    const double m_t = a.p.m_tip, J_t = a.p.J_tip, R = a.p.a + a.p.L;
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
}

}  // namespace hubbeam
