// The tip body's kinetic energy (docs/model.md section 11.1): m_tip at x = L moving with the beam's end, J_tip turning
// with the hub and the slope there. Its weight and damping are added by gravity.cpp and damping.cpp.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

void tip_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    e.T += c.at_tip(s.m_tip * c.v2 / 2 + s.J_tip * pow(s.theta_dot + c.f.uy_x_dot, 2) / 2);
}

}  // namespace hubbeam::gen
