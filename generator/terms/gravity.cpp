// Gravity's potential (docs/model.md sections 11.3 and 12): the weight of the beam and of a tip body along -j of a
// vertical plane of motion (g), and along the spin axis -k (g_axis, a variant that leaves the plane).
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

void gravity_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    // The height of a point in the plane, p rotated by theta: sin(theta) p_i + cos(theta) p_j; order zero has no u_x2.
    const Position p = position(c.key.order, c.f, cone_of(c.key, s));
    ex weight = s.g * (s.sin_theta * p.i + s.cos_theta * p.j);
    if (c.key.out_of_plane()) weight += s.o->g_axis * p.k;
    e.U += c.integrate(c.beam.mass * weight);
    if (c.key.extras.tip) e.U += c.at_tip(s.m_tip * weight);
}

}  // namespace hubbeam::gen
