// The generator's terms lined up with the registry (model/terms.hpp): the one place a term's generator part is named.
#include "generator_terms.hpp"

#include <array>
#include <stdexcept>

namespace hubbeam::gen {

using namespace GiNaC;

const GeneratorTerm& generator_part(const TermInfo& t)
{
    // In the order of terms(): tip, gravity, damping, taper, profile, offsets, pitch, twist, precone, hub, tip body. Pitch,
    // twist and precone have no energy of their own: they turn the section's principal axes (bending_density,
    // section_rotation) and the beam's axis (velocity_squared, position) inside the beam's T and U and the other
    // terms' (energy.cpp).
    static const std::array<const GeneratorTerm*, 11> table = {
        &tip_term,    &gravity_term, &damping_term, &taper_term, &profile_term, &offsets_term,
        nullptr,      nullptr,       nullptr,       &hub_term,   &tip_body_term};
    static const GeneratorTerm none;
    if (table.size() != terms().size()) throw std::logic_error("generator_part: not one entry per registered term");
    const GeneratorTerm* part = table.at(static_cast<std::size_t>(&t - terms().data()));
    return part ? *part : none;
}

BeamSection turned_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f, BeamSection b,
                           const ex& EI_flap, const ex& GJ, const ex& j_c, const ex& j_n)
{
    if (!key.out_of_plane()) return b;
    const auto [c2, s2] = chord_angle(key, s, f);
    const ex bend = (b.bending - EI_flap) / 2, inertia = (j_n - j_c) / 2;
    b.bend_mean = (b.bending + EI_flap) / 2;
    b.bend_cos = bend * c2;
    b.bend_sin = bend * s2;
    b.torsion = GJ;
    b.polar = j_c + j_n;
    b.inertia_cos = inertia * c2;
    b.inertia_sin = inertia * s2;
    return b;
}

BeamSection uniform_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    if (!key.out_of_plane()) return {s.m, s.ES, s.EI};
    const Symbols::OutOfPlane& o = *s.o;
    return turned_section(key, s, f, {s.m, s.ES, s.EI}, o.EI_flap, o.GJ, o.j_c, o.j_n);
}

}  // namespace hubbeam::gen
