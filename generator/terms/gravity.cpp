// Gravity's potential (docs/model.md section 11.3): the weight of the beam and of a tip body along -j of a vertical
// plane of motion.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

void gravity_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    const FieldSymbols& f = c.f;
    // The height of a point, p rotated by theta: sin(theta) (X + u_x) + cos(theta) u_y; order zero has no u_x2.
    const ex ux = f.ux1 + (c.key.order == Order::zero ? ex(0) : ex(f.ux2));
    const ex height = s.sin_theta * (f.X + ux) + s.cos_theta * f.uy;
    e.U += c.integrate(s.g * c.beam.mass * height);
    if (c.key.extras.tip) e.U += c.at_tip(s.g * s.m_tip * height);
}

}  // namespace hubbeam::gen
