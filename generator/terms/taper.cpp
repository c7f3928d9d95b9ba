// A tapered section (docs/model.md section 11): the root's values times the section's ratios along the span.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

BeamSection taper_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    const Extras& x = key.extras;
    // The section's area and second moment over the root's: a width taper scales both linearly, a depth taper the
    // area linearly and the second moment as the cube.
    const ex area = 1 + (s.tip_ratio - 1) * f.xi;
    const ex moment = x.taper == Taper::depth ? pow(area, 3) : area;
    return {s.m * area, s.ES * area, s.EI * moment};
}

}  // namespace hubbeam::gen
