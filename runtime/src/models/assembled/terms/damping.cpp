// Rayleigh damping's assembled twin (docs/model.md section 11.4): -dD/dqd = -(alpha M_ee + beta K_e) qd_e with
// M_ee = blockdiag(M1, M2r) of the beam with its tip body (added before: the registry puts the tip first).
#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

void add_damping(const AssemblyContext& a, ModelMatrices& m)
{
    const double alpha = a.p.alpha, beta = a.p.beta;
    m.D_A = alpha * m.M1 + beta * a.c.K1;
    m.D_B = alpha * m.M2r + beta * a.c.K2;
    m.damped = alpha != 0.0 || beta != 0.0;
    // Out of the plane (section 12.3) the same factors weigh the mass and stiffness of every elastic coordinate.
    m.alpha = alpha;
    m.beta = beta;
}

}  // namespace hubbeam
