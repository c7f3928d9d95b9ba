// Rayleigh damping's dissipation function (docs/model.md section 11.4) of the elastic rates, with the tip body's.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

void damping_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    const FieldSymbols& f = c.f;
    const BeamSection& b = c.beam;
    // Rayleigh: D = 1/2 qd_e^T (alpha M_ee + beta K_e) qd_e, M_ee and K_e of the undeformed beam (with its tip body).
    const ex rates2 = pow(f.ux1_dot, 2) + pow(f.uy_dot, 2);
    e.D += c.integrate((s.alpha * b.mass * rates2 + s.beta * (b.axial * pow(f.ux1_x_dot, 2) + b.bending * pow(f.uy_xx_dot, 2))) / 2);
    if (c.key.extras.tip) e.D += c.at_tip(s.alpha * (s.m_tip * rates2 + s.J_tip * pow(f.uy_x_dot, 2)) / 2);
}

}  // namespace hubbeam::gen
