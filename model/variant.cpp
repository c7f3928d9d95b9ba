// VariantKey naming, parsing and DOF validity.
#include "variant.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "coordinates.hpp"
#include "interface.hpp"
#include "terms.hpp"

namespace hubbeam {

namespace {

const WordTable<Method, 4> methods = {
    {Method::amm, "amm"}, {Method::fem, "fem"}, {Method::bim, "bim"}, {Method::bsim, "bsim"}};
const WordTable<Order, 3> orders = {{Order::zero, "zero"}, {Order::first, "first"}, {Order::full, "full"}};
const WordTable<Drive, 2> drives = {{Drive::prescribed, "prescribed"}, {Drive::torque, "torque"}};
const WordTable<SplineBasis, 2> splines = {{SplineBasis::paper, "paper"}, {SplineBasis::open, "open"}};
const WordTable<Taper, 3> tapers = {{Taper::uniform, "uniform"}, {Taper::width, "width"}, {Taper::depth, "depth"}};

/// The name suffixes of the extras, in name order (the registry's, terms.hpp).
std::vector<std::string> extras_suffixes(const Extras& e)
{
    std::vector<std::string> s;
    for (const TermInfo* t : carried_terms(e)) s.push_back(t->suffix(e));
    return s;
}

}  // namespace

std::string stations_problem(const std::vector<double>& x)
{
    if (x.size() < 2) return "a profile needs at least 2 stations";
    if (x.front() != 0.0 || x.back() != 1.0) return "the stations must start at 0 and end at 1";
    for (std::size_t k = 1; k < x.size(); ++k)
        if (!(x[k] > x[k - 1])) return "the stations must increase strictly";
    return {};
}

int max_dof(Method m)
{
    switch (m) {
        case Method::amm:
            return 40;
        case Method::bim:
            return 27;
        case Method::fem:
        case Method::bsim:
            return 64;
    }
    return 0;
}

std::string max_dof_reason(Method m)
{
    switch (m) {
        case Method::bim:
            return "the Bernstein mass matrix loses definiteness in double precision from 28";
        case Method::amm:
            return "the supported range; the highest modes' frequencies make runs slow beyond it";
        default:
            return "the supported range: generation, compilation and every run grow quickly beyond it";
    }
}

std::string to_string(Method v)
{
    return word_of(v, methods);
}
std::string to_string(Order v)
{
    return word_of(v, orders);
}
std::string to_string(Drive v)
{
    return word_of(v, drives);
}
std::string to_string(SplineBasis v)
{
    return word_of(v, splines);
}
std::string to_string(Taper v)
{
    return word_of(v, tapers);
}
bool parse(std::string_view w, Taper& v)
{
    return parse_word(w, tapers, v);
}
template <>
std::vector<std::string> words<Taper>()
{
    return all_words(tapers);
}
bool parse(std::string_view w, Method& v)
{
    return parse_word(w, methods, v);
}
bool parse(std::string_view w, Order& v)
{
    return parse_word(w, orders, v);
}
bool parse(std::string_view w, Drive& v)
{
    return parse_word(w, drives, v);
}
bool parse(std::string_view w, SplineBasis& v)
{
    return parse_word(w, splines, v);
}
template <>
std::vector<std::string> words<Method>()
{
    return all_words(methods);
}
template <>
std::vector<std::string> words<Order>()
{
    return all_words(orders);
}
template <>
std::vector<std::string> words<SplineBasis>()
{
    return all_words(splines);
}

int VariantKey::nq() const
{
    return coordinate_layout(*this).size();
}

std::size_t VariantKey::params_read() const
{
    return extras.any() || out_of_plane() ? param_count : paper_param_count;
}

std::string VariantKey::name() const
{
    std::string s = to_string(method) + "_nx" + std::to_string(nx) + "_ny" + std::to_string(ny);
    if (nz > 0) s += "_nz" + std::to_string(nz);
    if (nt > 0) s += "_nt" + std::to_string(nt);
    s += "_" + to_string(drive) + "_" + to_string(order);
    if (method == Method::bsim && spline == SplineBasis::open) s += "_open";
    for (const std::string& suffix : extras_suffixes(extras)) s += "_" + suffix;
    return s;
}

namespace {

/// A variant name's parts between its '_'.
std::vector<std::string> name_parts(std::string_view name)
{
    std::vector<std::string> parts;
    std::string cur;
    for (char ch : name) {
        if (ch == '_') {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += ch;
        }
    }
    parts.push_back(cur);
    return parts;
}

/// The error for a name that is not a variant's: what is wrong, and the grammar.
std::invalid_argument not_a_name(std::string_view name, const std::string& what)
{
    return std::invalid_argument("not a variant name: '" + std::string(name) + "': " + what + " (expected " +
                                 variant_name_grammar + ", e.g. bim_nx4_ny4_torque_first)");
}

/// n from a part stem followed by a count ("nx4").
void read_count(std::string_view name, const std::string& part, const char* stem, int& n)
{
    if (part.size() < 3 || part.rfind(stem, 0) != 0 || part.find_first_not_of("0123456789", 2) != std::string::npos ||
        part.size() > 2 + 9)
        throw not_a_name(name, "'" + part + "' is not " + stem + " followed by a count");
    n = std::stoi(part.substr(2));
}

/// The counts nx, ny and, where the name has them, nz and nt, from parts[1] on; the index of the part after them.
std::size_t read_counts(std::string_view name, const std::vector<std::string>& parts, VariantKey& k)
{
    read_count(name, parts[1], "nx", k.nx);
    read_count(name, parts[2], "ny", k.ny);
    std::size_t next = 3;
    // nz and nt appear only where nonzero, so that each key has one name.
    for (const auto& [stem, n] : {std::pair<const char*, int*>{"nz", &k.nz}, {"nt", &k.nt}})
        if (parts.size() > next && parts[next].rfind(stem, 0) == 0) {
            read_count(name, parts[next++], stem, *n);
            if (*n == 0) throw not_a_name(name, std::string("'") + stem + "0': a zero count is left out of the name");
        }
    return next;
}

/// The extras from the name's suffixes rest, each at most once and in name order: the name of a key is unique.
void read_extras(std::string_view name, const std::vector<std::string>& rest, VariantKey& k)
{
    for (const std::string& part : rest) {
        bool known = false;
        for (const TermInfo& t : terms()) {
            try {
                known = t.read_suffix(part, k.extras);
            } catch (const std::invalid_argument& e) {
                throw not_a_name(name, "'" + part + "'" + e.what());
            }
            if (known) break;
        }
        if (!known) throw not_a_name(name, "'" + part + "' is not a suffix");
    }
    if (extras_suffixes(k.extras) != rest) throw not_a_name(name, "the suffixes are repeated or out of order");
    if (k.extras.profile() && k.extras.taper != Taper::uniform)
        throw not_a_name(name, "a profile and a taper together");
}

}  // namespace

VariantKey VariantKey::parse(std::string_view name)
{
    const std::vector<std::string> parts = name_parts(name);
    VariantKey k;
    const auto bad = [&](const std::string& what) { return not_a_name(name, what); };
    if (parts.size() < 5) throw bad(std::to_string(parts.size()) + " parts separated by '_'");
    if (!hubbeam::parse(parts[0], k.method))
        throw bad("method '" + parts[0] + "' is not one of " + joined(words<Method>()));
    std::size_t next = read_counts(name, parts, k);
    if (parts.size() < next + 2) throw bad(std::to_string(parts.size()) + " parts separated by '_'");
    if (!hubbeam::parse(parts[next], k.drive))
        throw bad("drive '" + parts[next] + "' is not one of prescribed, torque");
    if (!hubbeam::parse(parts[next + 1], k.order))
        throw bad("order '" + parts[next + 1] + "' is not one of " + joined(words<Order>()));
    next += 2;
    if (parts.size() > next && parts[next] == "open") {
        if (k.method != Method::bsim) throw bad("'open': only bsim takes the suffix _open");
        k.spline = SplineBasis::open;
        ++next;
    }
    read_extras(name, std::vector<std::string>(parts.begin() + static_cast<std::ptrdiff_t>(next), parts.end()), k);
    return k;
}

std::string VariantKey::dof_problem() const
{
    if (nx < 0) return "nx must be >= 0";
    if (ny < 1) return "ny must be >= 1";
    if (nz < 0) return "nz must be >= 0";
    if (nt < 0) return "nt must be >= 0";
    const int most = max_dof(method);
    for (const auto& [name, n] : {std::pair<const char*, int>{"ny", ny}, {"nx", nx}, {"nz", nz}, {"nt", nt}})
        if (n > most)
            return to_string(method) + " supports " + name + " up to " + std::to_string(most) + " (" +
                   max_dof_reason(method) + "), got " + std::to_string(n);
    // The flapwise field takes the in-plane field's basis, the twist field the axial one: the same rules (0 allowed).
    for (const auto& [name, n] : {std::pair<std::string, int>{"ny", ny}, {"nz", nz}}) {
        const std::string got = ", got " + std::to_string(n);
        if (n == 0) continue;
        if (method == Method::fem && n % 2 != 0)
            return "FEM needs an even " + name + " (a deflection and a slope per node)" + got;
        if (method == Method::bsim && spline == SplineBasis::paper && n < 4)
            return "BSIM with the paper's basis (eq. 41) needs " + name + " >= 4 (n >= 3 intervals)" + got +
                   "; spline_basis = \"open\" takes " + name + " >= 2";
        if (method == Method::bsim && spline == SplineBasis::open && n < 2) return "BSIM needs " + name + " >= 2" + got;
    }
    for (const auto& [name, n] : {std::pair<std::string, int>{"nx", nx}, {"nt", nt}})
        if (method == Method::bsim && n != 0 && n < 3)
            return "BSIM needs " + name + " = 0 or " + name + " >= 3 (n_x + 2 with n_x >= 1), got " + std::to_string(n);
    // A profile's chord angles are its pre-twist (docs/model.md 12.4).
    if (extras.profile() && extras.twist) return "a profile's pre-twist is its twist column, not beam.twist";
    // Section offsets are a blade table's columns, in its kinetic energy to second order (docs/model.md 12.5).
    if (extras.offsets && !(extras.profile() && out_of_plane()))
        return "section offsets need a blade's table (beam.blade_file) and a beam that leaves the plane";
    if (extras.offsets && order == Order::full)
        return "section offsets are modelled to second order in the deformation: order first or zero, not full";
    // The offset centre of mass's weight and the moving hub's velocity against the chord are not modelled.
    if (extras.offsets && (extras.gravity || extras.hub))
        return "section offsets do not combine with gravity or a moving hub ([support])";
    return tip_body_problem();
}

std::string VariantKey::tip_body_problem() const
{
    // The tip body in the blade's axes (docs/model.md section 11.1) turns with the flap slope and the twist.
    if (!extras.tip_body) return {};
    if (!out_of_plane())
        return "the tip body's flap and torsion inertias and offset need a beam that leaves the plane (nz or nt > 0, "
               "a pitch, pre-twist or precone)";
    if (order == Order::full)
        return "the tip body in the blade's axes is modelled to second order in the deformation: order first or zero, "
               "not full";
    if (extras.hub) return "the tip body in the blade's axes does not combine with a moving hub ([support])";
    return {};
}

}  // namespace hubbeam
