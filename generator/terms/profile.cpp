// A tabulated profile (docs/model.md sections 11.2 and 12.4): the distributions are the stations' values times their
// hat functions, the field symbols m_x, ES_x, EI_x (and a blade's) that the density integrator expands.
#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

BeamSection profile_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    BeamSection b{f.m_x, f.ES_x, f.EI_x};
    if (!key.out_of_plane()) return b;
    // The table's deviators are turned by its own chord angles; the pitch turns them all: cos 2 (pitch + beta) =
    // cos 2 pitch cos 2 beta - sin 2 pitch sin 2 beta, sin 2 (pitch + beta) = sin 2 pitch cos 2 beta + cos 2 pitch sin
    // 2 beta.
    const ex c = key.extras.pitch ? ex(s.o->cos_2pitch) : ex(1), sn = key.extras.pitch ? ex(s.o->sin_2pitch) : ex(0);
    b.bend_mean = (f.EI_x + f.EI_flap_x) / 2;
    b.bend_cos = c * f.EI_cos_x - sn * f.EI_sin_x;
    b.bend_sin = sn * f.EI_cos_x + c * f.EI_sin_x;
    b.torsion = f.GJ_x;
    b.polar = f.j_p_x;
    b.inertia_cos = c * f.j_cos_x - sn * f.j_sin_x;
    b.inertia_sin = sn * f.j_cos_x + c * f.j_sin_x;
    return b;
}

}  // namespace hubbeam::gen
