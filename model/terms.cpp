// The registry of physics terms (terms.hpp): one entry per term of docs/model.md section 11.
#include "terms.hpp"

#include <cmath>
#include <stdexcept>

namespace hubbeam {

namespace {

/// A term named by one fixed suffix word.
bool is(std::string_view part, const char* word)
{
    return part == word;
}

bool read_taper_suffix(std::string_view part, Extras& e)
{
    Taper t;
    if (!parse(part, t) || t == Taper::uniform) return false;
    e.taper = t;
    return true;
}

// The suffix and banner words of the terms a flag of Extras switches on and off.
constexpr char tip_word[] = "tip", tip_summary[] = "tip_body";
constexpr char gravity_word[] = "gravity";
constexpr char damped_word[] = "damped", damped_summary[] = "rayleigh_damping";
constexpr char pitched_word[] = "pitched", pitched_summary[] = "pitch";
constexpr char twisted_word[] = "twisted", twisted_summary[] = "pre_twist";
constexpr char coned_word[] = "coned", coned_summary[] = "precone";
constexpr char tip_body_word[] = "tipbody", tip_body_summary[] = "tip_body_axes";

/// A term selected by its values and carried where the flag `member` of Extras is set, named by the suffix `word`
/// and by `summary` on the banner.
template <bool Extras::*member, const char* word, const char* summary>
TermInfo switched(const char* name, unsigned energies, std::vector<Param> params, std::vector<TermSceneKey> keys = {})
{
    return {name,
            energies,
            std::move(params),
            std::move(keys),
            true,
            [](const Extras& e) { return e.*member; },
            [](const Extras&) { return std::string(word); },
            [](std::string_view s, Extras& e) { return is(s, word) && (e.*member = true); },
            [](const Extras&) { return std::string(summary); },
            [](Extras& e, bool on) { e.*member = on; }};
}

std::vector<TermInfo> make_terms()
{
    using P = Param;
    using R = KeyRange;
    const auto never = [](Extras&, bool) {};
    return {
        // The tip body's weight and damping are gravity's and damping's terms (generator/terms/tip.cpp): a tip body
        // alone adds to T only.
        switched<&Extras::tip, tip_word, tip_summary>("tip body (section 11.1)", adds_T, {P::m_tip, P::J_tip},
                                                      {{"tip", "mass", P::m_tip, R::nonnegative, "m_tip, kg"},
                                                       {"tip", "inertia", P::J_tip, R::nonnegative, "J_tip, kg m^2"}}),
        switched<&Extras::gravity, gravity_word, gravity_word>("gravity (section 11.3)", adds_U | reads_hub_angle,
                                                               {P::g, P::g_axis},
                                                               {{"gravity", "g", P::g, R::finite, "g, m/s^2"}}),
        switched<&Extras::damping, damped_word, damped_summary>(
            "Rayleigh damping (section 11.4)", adds_D, {P::alpha, P::beta},
            {{"damping", "mass_proportional", P::alpha, R::nonnegative, "alpha, 1/s"},
             {"damping", "stiffness_proportional", P::beta, R::nonnegative, "beta, s"}}),
        {"taper (section 11)",
         shapes_section,
         {P::tip_ratio},
         {},
         false,
         [](const Extras& e) { return e.taper != Taper::uniform; },
         [](const Extras& e) { return to_string(e.taper); },
         read_taper_suffix,
         [](const Extras& e) { return "taper=" + to_string(e.taper); },
         never,
         "beam.taper \"width\" or \"depth\""},
        {"tabulated profile (section 11.2)",
         shapes_section,
         {},
         {},
         false,
         [](const Extras& e) { return e.profile(); },
         [](const Extras&) { return std::string("profile"); },
         [](std::string_view part, Extras& e) { return part == "profile" && (e.tabulated = true); },
         [](const Extras&) { return std::string("tabulated_profile"); },
         never,
         "beam.profile or beam.blade_file"},
        // Chosen by the table's words (a blade's offsets columns), as the profile is: the centre of mass's T, the
        // tension centre's U (which vanishes with nx = 0).
        {"section offsets (sections 12.5 and 12.6)",
         adds_T | adds_U,
         {},
         {},
         false,
         [](const Extras& e) { return e.offsets; },
         [](const Extras&) { return std::string("offsets"); },
         [](std::string_view part, Extras& e) { return part == "offsets" && (e.offsets = true); },
         [](const Extras&) { return std::string("section_offsets"); },
         never,
         "a table's cg_offset or tc_offset column"},
        switched<&Extras::pitch, pitched_word, pitched_summary>("pitch (section 12)", adds_U | adds_T, {P::pitch}),
        switched<&Extras::twist, twisted_word, twisted_summary>("pre-twist (section 12)", adds_U | adds_T, {P::twist}),
        // The precone tilts the axis: its own module moves the beam's points (T); the tilted weight is gravity's U.
        switched<&Extras::cone, coned_word, coned_summary>("precone (section 12)", adds_T, {P::precone}),
        // A moving hub is chosen by the scene's [support] table, not by values: a free-floating hub (stiffness 0)
        // still translates. Its kinetic energy reads theta's sine and cosine (the hub's velocity in the blade's frame).
        // Its mass is [hub]'s (hub.mass, read with the hub's other keys).
        {"moving hub (section 13)",
         adds_T | adds_U | adds_D | kinetic_reads_angle,
         {P::m_hub, P::k_x, P::k_y, P::c_x, P::c_y},
         {{"support", "stiffness_x", P::k_x, R::nonnegative, "k_x, N/m"},
          {"support", "stiffness_y", P::k_y, R::nonnegative, "k_y, N/m"},
          {"support", "damping_x", P::c_x, R::nonnegative, "c_x, N s/m"},
          {"support", "damping_y", P::c_y, R::nonnegative, "c_y, N s/m"}},
         false,
         [](const Extras& e) { return e.hub; },
         [](const Extras&) { return std::string("hub"); },
         [](std::string_view part, Extras& e) { return part == "hub" && (e.hub = true); },
         [](const Extras&) { return std::string("moving_hub"); },
         never,
         "a [support] table (the hub translates only on a support)"},
        // The tip body's own axes (its flap and torsion inertias, its offset): the tip term's m_tip and J_tip, read by
        // this term's energies in the section's axes, stay the tip term's parameters and keys.
        switched<&Extras::tip_body, tip_body_word, tip_body_summary>(
            "tip body in the blade's axes (section 11.1)", adds_T, {P::J_tip_flap, P::J_tip_twist, P::tip_offset},
            {{"tip", "inertia_flap", P::J_tip_flap, R::nonnegative,
              "J_tip_flap, kg m^2: about the chord through the body's centre of mass; out of the plane"},
             {"tip", "inertia_twist", P::J_tip_twist, R::nonnegative,
              "J_tip_twist, kg m^2: about the span axis through the body's centre of mass; out of the plane"},
             {"tip", "offset", P::tip_offset, R::finite,
              "tip_offset, m: the body's centre of mass along the chord from the beam's end, positive towards the "
              "trailing edge; out of the plane"}}),
    };
}

}  // namespace

bool in_range(KeyRange r, double v)
{
    switch (r) {
        case KeyRange::finite:
            return std::isfinite(v);
        case KeyRange::nonnegative:
            return v >= 0.0 && std::isfinite(v);
        case KeyRange::positive:
            return v > 0.0 && std::isfinite(v);
    }
    return false;
}

std::string TermSceneKey::name() const
{
    return std::string(table) + "." + key;
}

std::string TermSceneKey::expected() const
{
    static constexpr const char* words[] = {"a finite number", "a number >= 0", "a number > 0"};
    return std::string(words[static_cast<int>(range)]) + " (" + detail + ")";
}

const std::vector<TermInfo>& terms()
{
    // Never destroyed: a thread still computing while the process exits (a Python daemon thread) may read it.
    static const std::vector<TermInfo>& table = *new std::vector<TermInfo>(make_terms());
    return table;
}

std::vector<const TermInfo*> carried_terms(const Extras& e)
{
    std::vector<const TermInfo*> carried;
    for (const TermInfo& t : terms())
        if (t.carried(e)) carried.push_back(&t);
    return carried;
}

namespace {

/// Whether a term the variant carries has one of the TermEnergy bits.
bool carries_a_term_that(const VariantKey& key, unsigned bits)
{
    for (const TermInfo& t : terms())
        if ((t.energies & bits) != 0 && t.carried(key.extras)) return true;
    return false;
}

}  // namespace

bool dissipates(const VariantKey& key)
{
    return carries_a_term_that(key, adds_D);
}

bool potential_reads_angle(const VariantKey& key)
{
    return carries_a_term_that(key, reads_hub_angle);
}

bool kernels_read_angle(const VariantKey& key)
{
    return carries_a_term_that(key, reads_hub_angle | kinetic_reads_angle);
}

bool reads_driven_angle(const VariantKey& key)
{
    return key.drive == Drive::prescribed && kernels_read_angle(key);
}

bool mass_reads_angle(const VariantKey& key)
{
    return carries_a_term_that(key, kinetic_reads_angle);
}

bool shaped_section(const VariantKey& key)
{
    return carries_a_term_that(key, shapes_section);
}

}  // namespace hubbeam
