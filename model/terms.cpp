// The registry of physics terms (terms.hpp): one entry per term of docs/model.md section 11.
#include "terms.hpp"

#include <stdexcept>

namespace hubbeam {

namespace {

/// A term named by one fixed suffix word.
bool is(std::string_view part, const char* word)
{
    return part == word;
}

/// profileDENxN0xN1...: digits separated by 'x', each a number of at most 7 digits (docs/model.md section 11.2).
bool read_profile_suffix(std::string_view part, Extras& e)
{
    if (part.rfind("profile", 0) != 0 || part.size() <= 7 || part.size() > max_profile_suffix) return false;
    std::vector<long long> numbers;
    std::string digits;
    for (std::size_t c = 7; c <= part.size(); ++c) {
        if (c == part.size() || part[c] == 'x') {
            if (digits.empty() || digits.size() > 7) throw std::invalid_argument(" is not profileDENxN0xN1...");
            numbers.push_back(std::stoll(digits));
            digits.clear();
        } else if (part[c] >= '0' && part[c] <= '9') {
            digits += part[c];
        } else {
            throw std::invalid_argument(" is not profileDENxN0xN1...");
        }
    }
    e.station_denominator = numbers.front();
    e.stations.assign(numbers.begin() + 1, numbers.end());
    if (const std::string why = stations_problem(e); !why.empty()) throw std::invalid_argument(": " + why);
    return true;
}

std::string profile_suffix(const Extras& e)
{
    std::string p = "profile" + std::to_string(e.station_denominator);
    for (long long n : e.stations) p += 'x' + std::to_string(n);
    return p;
}

std::string profile_summary(const Extras& e)
{
    std::string stations;
    for (long long n : e.stations) stations += (stations.empty() ? "" : ",") + std::to_string(n);
    return "profile_stations=(" + stations + ")/" + std::to_string(e.station_denominator);
}

bool read_taper_suffix(std::string_view part, Extras& e)
{
    Taper t;
    if (!parse(part, t) || t == Taper::uniform) return false;
    e.taper = t;
    return true;
}

std::vector<TermInfo> make_terms()
{
    using P = Param;
    const auto never = [](Extras&, bool) {};
    return {
        {"tip body (section 11.1)",
         adds_T | adds_U | adds_D,
         {P::m_tip, P::J_tip},
         {{"tip", "mass", P::m_tip}, {"tip", "inertia", P::J_tip}},
         true,
         [](const Extras& e) { return e.tip; },
         [](const Extras&) { return std::string("tip"); },
         [](std::string_view s, Extras& e) { return is(s, "tip") && (e.tip = true); },
         [](const Extras&) { return std::string("tip_body"); },
         [](Extras& e, bool on) { e.tip = on; }},
        {"gravity (section 11.3)",
         adds_U,
         {P::g, P::g_axis},
         {{"gravity", "g", P::g}},
         true,
         [](const Extras& e) { return e.gravity; },
         [](const Extras&) { return std::string("gravity"); },
         [](std::string_view s, Extras& e) { return is(s, "gravity") && (e.gravity = true); },
         [](const Extras&) { return std::string("gravity"); },
         [](Extras& e, bool on) { e.gravity = on; }},
        {"Rayleigh damping (section 11.4)",
         adds_D,
         {P::alpha, P::beta},
         {{"damping", "mass_proportional", P::alpha}, {"damping", "stiffness_proportional", P::beta}},
         true,
         [](const Extras& e) { return e.damping; },
         [](const Extras&) { return std::string("damped"); },
         [](std::string_view s, Extras& e) { return is(s, "damped") && (e.damping = true); },
         [](const Extras&) { return std::string("rayleigh_damping"); },
         [](Extras& e, bool on) { e.damping = on; }},
        {"taper (section 11)",
         shapes_section,
         {P::tip_ratio},
         {},
         false,
         [](const Extras& e) { return e.taper != Taper::uniform; },
         [](const Extras& e) { return to_string(e.taper); },
         read_taper_suffix,
         [](const Extras& e) { return "taper=" + to_string(e.taper); },
         never},
        {"tabulated profile (section 11.2)",
         shapes_section,
         {},
         {},
         false,
         [](const Extras& e) { return e.profile(); },
         profile_suffix,
         read_profile_suffix,
         profile_summary,
         never},
        {"pitch (section 12)",
         adds_U | adds_T,
         {P::pitch},
         {},
         true,
         [](const Extras& e) { return e.pitch; },
         [](const Extras&) { return std::string("pitched"); },
         [](std::string_view s, Extras& e) { return is(s, "pitched") && (e.pitch = true); },
         [](const Extras&) { return std::string("pitch"); },
         [](Extras& e, bool on) { e.pitch = on; }},
        {"pre-twist (section 12)",
         adds_U | adds_T,
         {P::twist},
         {},
         true,
         [](const Extras& e) { return e.twist; },
         [](const Extras&) { return std::string("twisted"); },
         [](std::string_view s, Extras& e) { return is(s, "twisted") && (e.twist = true); },
         [](const Extras&) { return std::string("pre_twist"); },
         [](Extras& e, bool on) { e.twist = on; }},
        {"precone (section 12)",
         adds_T | adds_U,
         {P::precone},
         {},
         true,
         [](const Extras& e) { return e.cone; },
         [](const Extras&) { return std::string("coned"); },
         [](std::string_view s, Extras& e) { return is(s, "coned") && (e.cone = true); },
         [](const Extras&) { return std::string("precone"); },
         [](Extras& e, bool on) { e.cone = on; }},
    };
}

}  // namespace

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

}  // namespace hubbeam
