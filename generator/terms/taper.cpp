// A tapered section (docs/model.md section 11): the root's values times the section's ratios along the span.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

BeamSection taper_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    const Extras& x = key.extras;
    // The section's area and second moment over the root's: a width taper scales both linearly, a depth taper the
    // area linearly and the second moment as the cube.
    const ex area = 1 + (s.tip_ratio - 1) * f.xi;
    const ex moment = x.taper == Taper::depth ? pow(area, 3) : area;
    const BeamSection planar{s.m * area, s.ES * area, s.EI * moment};
    if (!key.out_of_plane()) return planar;
    // Out of the plane the width is the flapwise thickness, the depth the chord (docs/model.md section 12): the
    // flapwise moment scales the other way, and a thin section's torsion constant (chord thickness^3 / 3) as the
    // flapwise one.
    const Symbols::OutOfPlane& o = *s.o;
    const ex flap = x.taper == Taper::depth ? area : pow(area, 3);
    return turned_section(key, s, f, planar, o.EI_flap * flap, o.GJ * flap, o.j_c * flap, o.j_n * moment);
}

}  // namespace

const GeneratorTerm taper_term = {.section = taper_section};

}  // namespace hubbeam::gen
