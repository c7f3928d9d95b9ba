// Gravity's assembled twin (docs/model.md sections 11.3 and 12.3): the weight's integrals W are the beam's (with a tip
// body's, added by tip.cpp); gravity sets the g that scales them, and out of the plane the g_axis along the spin axis.
#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

void add_gravity(const AssemblyContext& a, ModelMatrices& m)
{
    m.g = a.p.g;
    if (a.key.out_of_plane()) m.g_axis = a.p.g_axis;
}

}  // namespace hubbeam
