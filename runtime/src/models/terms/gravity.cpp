// Gravity's assembled twin (docs/model.md section 11.3): the weight's integrals W are the beam's (with a tip body's,
// added by tip.cpp); gravity sets the g that scales them.
#include "models/assembled_terms.hpp"

namespace hubbeam {

void add_gravity(const AssemblyContext& a, ModelMatrices& m) { m.g = a.p.g; }

}  // namespace hubbeam
