// The generator's part of each physics term (model/terms.hpp): its energies or dissipation given the beam's
// fields, or its section (the distributions m(x), ES(x), EI(x) inside the beam's own T and U). One file per term,
// generator/terms/NAME.cpp; the table in generator/terms/generator_terms.cpp lines them up with the registry, and
// derive_energies loops over the terms a variant carries.
#pragma once

#include <ginac/ginac.h>

#include <functional>

#include "energy.hpp"
#include "terms.hpp"

namespace hubbeam::gen {

/// What a term's energies are built from: the variant, its symbols, the field symbols, the beam's section and
/// |r_dot|^2, and the two ways to turn a density into a polynomial (over the span, at the tip x = L).
struct TermContext {
    const VariantKey& key;
    const Symbols& s;
    const FieldSymbols& f;
    const BeamSection& beam;
    const GiNaC::ex& v2;
    std::function<Poly(const GiNaC::ex&)> integrate, at_tip;
};

/// A term of the generator: section replaces the beam's distributions (a section term), energies adds to T, U, D.
/// Either may be null.
struct GeneratorTerm {
    BeamSection (*section)(const VariantKey&, const Symbols&, const FieldSymbols&);
    void (*energies)(const TermContext&, Energies&);
};

/// The generator's part of a registered term (model/terms.hpp).
const GeneratorTerm& generator_part(const TermInfo& t);

/// The uniform beam's section: m, ES, EI and, out of the plane, E I_flap, G J_t, rho I and rho I_flap turned by the
/// pitch and pre-twist.
BeamSection uniform_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f);
/// b (its m, ES and edgewise EI) with the distributions EI_flap, GJ, j_c and j_n turned by the pitch and pre-twist
/// (docs/model.md section 12), where the variant leaves the plane.
BeamSection turned_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f, BeamSection b,
                           const GiNaC::ex& EI_flap, const GiNaC::ex& GJ, const GiNaC::ex& j_c, const GiNaC::ex& j_n);

// One per term (generator/terms/NAME.cpp).
void tip_energies(const TermContext& c, Energies& e);
void gravity_energies(const TermContext& c, Energies& e);
void damping_energies(const TermContext& c, Energies& e);
void hub_energies(const TermContext& c, Energies& e);
void offsets_energies(const TermContext& c, Energies& e);
BeamSection taper_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f);
BeamSection profile_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f);

}  // namespace hubbeam::gen
