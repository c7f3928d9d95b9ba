// The generator's terms lined up with the registry (model/terms.hpp): the one place a term's generator part is named.
#include "generator_terms.hpp"

#include <stdexcept>

namespace hubbeam::gen {

const GeneratorTerm& generator_part(const TermInfo& t)
{
    // In the order of terms(): tip, gravity, damping, taper, profile, pitch, twist, precone. These three have no
    // energy of their own: they turn the section's principal axes (bending_density, section_rotation) and the beam's
    // axis (velocity_squared, position) inside the beam's T and U and the other terms' (energy.cpp).
    static const std::vector<GeneratorTerm> table = {
        {nullptr, tip_energies},    {nullptr, gravity_energies}, {nullptr, damping_energies}, {taper_section, nullptr},
        {profile_section, nullptr}, {nullptr, nullptr},          {nullptr, nullptr},          {nullptr, nullptr}};
    if (table.size() != terms().size()) throw std::logic_error("generator_part: not one entry per registered term");
    return table.at(static_cast<std::size_t>(&t - terms().data()));
}

BeamSection uniform_section(const Symbols& s)
{
    return {s.m, s.ES, s.EI};
}

}  // namespace hubbeam::gen
