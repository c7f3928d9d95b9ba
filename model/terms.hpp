// The physics terms beyond the paper's beam (docs/model.md section 11), registered in one table: each term's name
// suffix, summary words, the parameters it owns, its scene keys and which of T, U, D it adds to. The variant's name,
// the generated banner, the scene reader and the choice of a scene's variant read this table; the generator's
// energies (generator/terms/) and the assembled twins (runtime/src/models/assembled/terms/) are one file per term.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

/// Which energies a term's own module adds to (docs/model.md section 2): kinetic T, potential U, dissipation D (what
/// it adds only with another term, as the tip body's weight, is that term's); a section term changes the beam's
/// distributions m(x), EI(x), ES(x) inside the beam's own T and U. A term whose U reads the hub
/// angle does so linearly in sin theta and cos theta, which the kernels take as inputs (generated_model.cpp's
/// forces_theta relies on the linearity).
/// A term whose T reads the hub angle (a moving hub: the hub's velocity in the blade's frame) has kinetic_reads_angle;
/// the kernels then take sin theta and cos theta too, and M holds them.
enum TermEnergy : unsigned {
    adds_T = 1u,
    adds_U = 2u,
    adds_D = 4u,
    shapes_section = 8u,
    reads_hub_angle = 16u,
    kinetic_reads_angle = 32u
};

/// The numbers a scene key accepts: any finite number, a finite one >= 0, or a finite one > 0.
enum class KeyRange { finite, nonnegative, positive };
/// Whether v is in range r.
bool in_range(KeyRange r, double v);

/// A scene key that sets one of a term's parameters: [table] key = value, with what it accepts: the range, which the
/// scene's validation checks, and the symbol and unit its message gives ("m_tip, kg"). The key table's row and every
/// refusal of the key read it from here.
struct TermSceneKey {
    const char* table;
    const char* key;
    Param param;
    KeyRange range;
    const char* detail;

    /// "tip.mass".
    std::string name() const;
    /// What the key takes, as the key table and its refusals say it: "a number >= 0 (m_tip, kg)".
    std::string expected() const;
};

/// One physics term of a variant.
struct TermInfo {
    const char* name;                      // the term, as docs/model.md section 11 calls it
    unsigned energies;                     // TermEnergy bits
    std::vector<Param> params;             // the entries of p it owns (read only by variants that carry it)
    std::vector<TermSceneKey> scene_keys;  // the scene keys of its own table (empty: it is read with [beam])
    /// Whether a scene's parameters select it: any of its params nonzero (else the paper's variant runs); false
    /// for a term chosen by the scene's words (taper, profile).
    bool selected_by_values;
    bool (*carried)(const Extras&);
    /// Its suffix of the variant's name ("tip"); called only when carried.
    std::string (*suffix)(const Extras&);
    /// Sets the term in e from a name suffix; false if the suffix is not this term's. Throws std::invalid_argument
    /// for a suffix of this term that is malformed, its what() the message's rest after the quoted suffix.
    bool (*read_suffix)(std::string_view, Extras&);
    /// Its words on the generated banner's variant line ("tip_body"); called only when carried.
    std::string (*summary)(const Extras&);
    /// Sets whether e carries the term (a term selected by values; a no-op for the others).
    void (*set)(Extras&, bool);
    /// A term chosen by the scene's words: what chooses it ("a [support] table"). A sensitivity to one of its
    /// parameters is refused where the scene does not carry it: its derivative there would be a column of zeros.
    const char* chosen_by = nullptr;
};

/// Every term, in the order of the variant's name suffixes: tip, gravity, damped, width|depth, profile, offsets,
/// pitched, twisted, coned, hub, tipbody.
const std::vector<TermInfo>& terms();

/// The terms a variant carries, in registry order.
std::vector<const TermInfo*> carried_terms(const Extras& e);

// The questions the runtime and the generator ask about a variant's structure, answered from the registry's bits
// of the terms it carries, so that a new term with those bits needs no branch of its own where they are used.

/// Whether the variant has a dissipation function D (a carried term adds to it): its runs carry the dissipated
/// energy (and, under an applied torque, the hub's work) as states, its linearization a damping matrix.
bool dissipates(const VariantKey& key);
/// Whether U reads the hub angle (a carried term's does): the kernels take sin theta and cos theta, U holds more
/// than the beam's strain (it can stay below 0), and a spin at a constant rate is not steady.
bool potential_reads_angle(const VariantKey& key);
/// Whether the kernels take sin theta and cos theta: U reads the angle (potential_reads_angle) or T does (a moving hub).
bool kernels_read_angle(const VariantKey& key);
/// Whether the prescribed angle is an input of the kernels (kernels_read_angle under a prescribed drive: U's weight
/// in the plane, a moving hub's T): dQ/dtheta theta_dot (and dM/dtheta theta_dot) enter df/dt, and no energy is
/// constant while the hub turns.
bool reads_driven_angle(const VariantKey& key);
/// Whether T reads the hub angle (a carried term's does: a moving hub's velocity in the blade's frame): M holds sin
/// theta and cos theta, so M turns with the angle, and no spin at a constant rate is steady in the blade's frame.
bool mass_reads_angle(const VariantKey& key);
/// Whether a carried term shapes the section (m(x), EI(x), ES(x) vary along the span): the generator's point terms
/// for order full know a uniform section only.
bool shaped_section(const VariantKey& key);

}  // namespace hubbeam
