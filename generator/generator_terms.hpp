// The generator's part of each physics term (model/terms.hpp): its energies or dissipation given the beam's
// fields, or its section (the distributions m(x), ES(x), EI(x) inside the beam's own T and U). One file per term,
// generator/terms/NAME.cpp; the table in generator/terms/generator_terms.cpp lines them up with the registry, and
// derive_energies loops over the terms a variant carries.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <functional>
#include <vector>

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

/// A term of the generator: section replaces the beam's distributions (a section term), energies adds to T, U, D
/// (either may be null); inputs are the symbols its energies read from p (Symbols::input), each made once by the
/// coefficients kernel.
struct GeneratorTerm {
    BeamSection (*section)(const VariantKey&, const Symbols&, const FieldSymbols&) = nullptr;
    void (*energies)(const TermContext&, Energies&) = nullptr;
    std::vector<TermInput> inputs = {};
};

/// The generator's part of a registered term (model/terms.hpp); an empty one for a term with none of its own.
const GeneratorTerm& generator_part(const TermInfo& t);

// Each defined in its own file, generator/terms/NAME.cpp.
extern const GeneratorTerm tip_term, gravity_term, damping_term, taper_term, profile_term, offsets_term, hub_term,
    tip_body_term;

/// The uniform beam's section: m, ES, EI and, out of the plane, E I_flap, G J_t, rho I and rho I_flap turned by the
/// pitch and pre-twist.
BeamSection uniform_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f);
/// b (its m, ES and edgewise EI) with the distributions EI_flap, GJ, j_c and j_n turned by the pitch and pre-twist
/// (docs/model.md section 12), where the variant leaves the plane.
BeamSection turned_section(const VariantKey& key, const Symbols& s, const FieldSymbols& f, BeamSection b,
                           const GiNaC::ex& EI_flap, const GiNaC::ex& GJ, const GiNaC::ex& j_c, const GiNaC::ex& j_n);

/// A unit vector of the section's plane, (0, C, S) in (e1, e2, e3) before the deformation (C, S: the cosine and sine
/// of its angle from e2 towards e3, or these times a factor, in which the vector is linear), in the hub frame (i, j, k)
/// and in field symbols: turned by phi about e1, then carried by the smallest rotation that takes e1 to the bent axis
/// (1, u_y', u_z'), to second order in phi and the slopes (docs/model.md section 12.5; generator/terms/offsets.cpp).
std::array<GiNaC::ex, 3> chord(const FieldSymbols& f, const Cone& cone, const GiNaC::ex& C, const GiNaC::ex& S);
/// The terms of e of degree at most 2 in the deformation: u_x1, u_y, u_z, phi, the slopes and their rates first
/// order, u_x2 and its rate second (docs/model.md section 3). f.offsets holds the flapwise slope's rate.
GiNaC::ex second_order(const GiNaC::ex& e, const FieldSymbols& f);

/// A tip body's centre of mass from the beam's end in hub components, carried by the tip section (turned by the pitch,
/// phi and the slopes; tip.cpp): what its weight reads (gravity.cpp), so that where the body sits is tip.cpp's alone.
std::array<GiNaC::ex, 3> tip_body_centre(const TermContext& c);

}  // namespace hubbeam::gen
