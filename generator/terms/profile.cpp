// A tabulated profile (docs/model.md sections 11.2 and 12.4): the distributions are the stations' values times their
// hat functions, the field symbols m_x, ES_x, EI_x (and a blade's) that the density integrator expands.
#include <tuple>

#include "generator_terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

BeamSection profile_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    BeamSection b{f.m_x, f.ES_x, f.EI_x};
    if (!key.out_of_plane()) return b;
    // The table's deviators are turned by its own chord angles; the pitch turns them all.
    b.bend_mean = (f.EI_x + f.EI_flap_x) / 2;
    std::tie(b.bend_cos, b.bend_sin) = turned_by_pitch(key, s, f.EI_cos_x, f.EI_sin_x);
    b.torsion = f.GJ_x;
    b.polar = f.j_p_x;
    std::tie(b.inertia_cos, b.inertia_sin) = turned_by_pitch(key, s, f.j_cos_x, f.j_sin_x);
    return b;
}

}  // namespace

const GeneratorTerm profile_term = {.section = profile_section};

}  // namespace hubbeam::gen
