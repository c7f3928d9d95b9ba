// Rayleigh damping's dissipation function (docs/model.md section 11.4) of the elastic rates, with the tip body's.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

void damping_energies(const TermContext& c, Energies& e)
{
    const Symbols& s = c.s;
    const FieldSymbols& f = c.f;
    const BeamSection& b = c.beam;
    // Rayleigh: D = 1/2 qd_e^T (alpha M_ee + beta K_e) qd_e, M_ee and K_e of the undeformed beam (with its tip body):
    // the section's rotary inertia and torsional stiffness where the variant has a twist field (docs/model.md 12).
    const ex rates2 = pow(f.ux1_dot, 2) + pow(f.uy_dot, 2) + pow(f.uz_dot, 2);
    ex mass = b.mass * rates2,
       stiffness = b.axial * pow(f.ux1_x_dot, 2) + bending_density(c.key, b, f.uy_xx_dot, f.uz_xx_dot);
    if (c.key.nt > 0) {
        mass += b.polar * pow(f.phi_dot, 2);
        stiffness += b.torsion * pow(f.phi_x_dot, 2);
    }
    e.D += c.integrate((s.alpha * mass + s.beta * stiffness) / 2);
    if (c.key.extras.tip) e.D += c.at_tip(s.alpha * (s.m_tip * rates2 + s.J_tip * pow(f.uy_x_dot, 2)) / 2);
}

}  // namespace

const GeneratorTerm damping_term = {.energies = damping_energies};

}  // namespace hubbeam::gen
