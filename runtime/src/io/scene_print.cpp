// The effective scene of a loaded Scene (scene_print.hpp): each key's value read back from the Scene that parsing
// filled, so that what is printed is what runs, not what the file said.
#include <hubbeam/scene_print.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>
#include <optional>
#include <stdexcept>

#include "io/scene_io.hpp"

namespace hubbeam {

namespace {

SceneValue number(const SceneKey& k, double v)
{
    return {SceneValue::Kind::number, k.name, v, 0, {}};
}
SceneValue integer(const SceneKey& k, long long v)
{
    return {SceneValue::Kind::integer, k.name, 0.0, v, {}};
}
SceneValue text(const SceneKey& k, std::string v)
{
    return {SceneValue::Kind::text, k.name, 0.0, 0, std::move(v)};
}
SceneValue numbers(const SceneKey& k, std::vector<double> v)
{
    return {SceneValue::Kind::numbers, k.name, 0.0, 0, {}, std::move(v)};
}

/// [rotor], only for a rotor of several blades (a single blade's scene prints as it always has); an array left out
/// of the file is not printed.
std::optional<SceneValue> rotor_value(const Scene& s, const SceneKey& k)
{
    const Rotor& r = s.rotor;
    if (r.blades <= 1) return std::nullopt;
    const std::string leaf = k.leaf();
    if (leaf == "blades") return integer(k, r.blades);
    const std::vector<double>& v = leaf == "pitch_offsets" ? r.pitch_offsets : r.tip_masses;
    return v.empty() ? std::nullopt : std::optional(numbers(k, v));
}

/// A table's file as an absolute path: the scene names it relative to its own folder, which a printed scene read
/// from elsewhere does not share.
std::string absolute(const std::string& path)
{
    return path.empty() ? path : std::filesystem::absolute(path).lexically_normal().string();
}

std::string table_file(const Scene& s, const std::string& key)
{
    for (const auto& [k, file] : s.tables)
        if (k == key) return absolute(file);
    return {};
}

std::string joined_names(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
    return out;
}

/// The keys of [beam] that a profile's table replaces.
bool given_by_profile(const std::string& leaf)
{
    return std::find(scene_io::keys_a_table_replaces.begin(), scene_io::keys_a_table_replaces.end(), leaf) !=
           scene_io::keys_a_table_replaces.end();
}

std::optional<SceneValue> beam_value(const Scene& s, const SceneKey& k)
{
    const Parameters& p = s.parameters;
    const std::string leaf = k.leaf();
    const bool profile = s.variant.extras.profile();
    if (profile && given_by_profile(leaf)) return std::nullopt;
    if (leaf == "length") return number(k, p.L);
    if (leaf == "density") return number(k, p.rho);
    if (leaf == "area") return number(k, p.S);
    if (leaf == "second_moment") return number(k, p.I);
    if (leaf == "youngs_modulus") return number(k, p.E);
    if (leaf == "taper") return text(k, to_string(s.variant.extras.taper));
    if (leaf == "tip_ratio") return number(k, p.tip_ratio);
    if (leaf == "profile") return text(k, table_file(s, "beam.profile"));
    if (leaf == "blade_file") return text(k, table_file(s, "beam.blade_file"));
    if (leaf == "blade_stations") return integer(k, s.blade_stations);
    if (leaf == "second_moment_flap") return number(k, p.I_flap);
    if (leaf == "shear_modulus") return number(k, p.G);
    if (leaf == "torsion_constant") return number(k, p.J_t);
    if (leaf == "pitch") return number(k, p.pitch);
    if (leaf == "twist") return number(k, p.twist);
    if (leaf == "precone") return number(k, p.precone);
    throw std::logic_error("effective_scene: no value for " + std::string(k.name));
}

/// [blade_scale]: only with a blade file, whose columns it scales.
std::optional<SceneValue> blade_scale_value(const Scene& s, const SceneKey& k)
{
    if (table_file(s, "beam.blade_file").empty()) return std::nullopt;
    for (const scene_io::BladeScaleField& f : scene_io::blade_scale_fields)
        if (k.leaf() == f.key) return number(k, s.blade_scale.*f.factor);
    throw std::logic_error("effective_scene: no value for " + std::string(k.name));
}

std::optional<SceneValue> motion_value(const Scene& s, const SceneKey& k)
{
    const Motion& m = s.motion;
    const std::string leaf = k.leaf(), kind = scene_io::kind_word(m.kind);
    if (leaf == "kind") return text(k, kind);
    if (std::find(k.motion_kinds.begin(), k.motion_kinds.end(), kind) == k.motion_kinds.end()) return std::nullopt;
    if (leaf == "omega0") return number(k, m.omega0);
    if (leaf == "tau0") return number(k, m.tau0);
    if (leaf == "duration") return number(k, m.kind == Motion::Kind::torque ? m.torque_time : m.spin_time);
    if (leaf == "theta0") return number(k, m.theta0);
    if (leaf == "angle") return number(k, m.angle);
    if (leaf == "file") return text(k, absolute(m.table_file));
    throw std::logic_error("effective_scene: no value for " + std::string(k.name));
}

std::optional<SceneValue> control_value(const Scene& s, const SceneKey& k)
{
    if (!s.control || s.control->law) return std::nullopt;
    const Control& c = *s.control;
    const std::string leaf = k.leaf();
    if (leaf == "kp") return number(k, c.kp);
    if (leaf == "kd") return number(k, c.kd);
    if (leaf == "ki") return number(k, c.ki);
    if (leaf == "tau_max") return number(k, c.tau_max);
    if (leaf == "k_tip") return number(k, c.k_tip);
    throw std::logic_error("effective_scene: no value for " + std::string(k.name));
}

/// [tip], [damping], [gravity] and [hub]: parameters; gravity along the axis is held in g_axis (scene.cpp).
std::optional<SceneValue> parameter_value(const Scene& s, const SceneKey& k)
{
    const Parameters& p = s.parameters;
    const std::string name = k.name;
    if (name == "hub.radius") return number(k, p.a);
    if (name == "hub.inertia") return number(k, p.J_oh);
    if (name == "gravity.g") return number(k, p.g_axis != 0.0 ? p.g_axis : p.g);
    if (name == "gravity.direction") return text(k, p.g_axis != 0.0 ? "axis" : "plane");
    // A moving hub's keys only where there is one: every other scene prints as it always has.
    if ((k.table() == "support" || name == "hub.mass") && !s.variant.extras.hub) return std::nullopt;
    if (name == "hub.mass") return number(k, p.m_hub);
    // The modal ratios only where given: every other scene prints as it always has.
    if (name == "damping.flap_ratios" || name == "damping.edge_ratios") {
        const std::vector<double>& v = k.leaf() == "flap_ratios" ? s.modal_damping.flap : s.modal_damping.edge;
        return v.empty() ? std::nullopt : std::optional(numbers(k, v));
    }
    for (const TermInfo& t : terms())
        for (const TermSceneKey& tk : t.scene_keys)
            if (name == tk.name()) return number(k, value(p, tk.param));
    throw std::logic_error("effective_scene: no value for " + name);
}

std::optional<SceneValue> run_value(const Scene& s, const SceneKey& k)
{
    const std::string name = k.name;
    const VariantKey& v = s.variant;
    if (name == "discretization.method") return text(k, to_string(v.method));
    if (name == "discretization.ny") return integer(k, v.ny);
    if (name == "discretization.nx") return integer(k, v.nx);
    if (name == "discretization.nz") return integer(k, v.nz);
    if (name == "discretization.nt") return integer(k, v.nt);
    if (name == "discretization.spline_basis") return text(k, to_string(v.spline));
    if (name == "model.order") return text(k, to_string(v.order));
    if (name == "model.source") return text(k, to_string(s.source));
    if (name == "model.axial") return text(k, to_string(s.axial));
    const SolverOptions& so = s.solver;
    if (name == "solver.stepper") return text(k, so.stepper);
    if (name == "solver.rtol") return number(k, so.rtol);
    if (name == "solver.atol") return number(k, so.atol);
    if (name == "solver.h0") return number(k, so.h0);
    if (name == "solver.stepping") return text(k, to_string(so.stepping));
    if (name == "solver.max_steps") return integer(k, so.max_steps);
    if (name == "solver.error_check") return text(k, to_string(so.error_check));
    if (name == "solver.sensitivity_error_control") return text(k, to_string(so.sensitivity_error_control));
    const OutputOptions& o = s.output;
    if (name == "output.t_end") return number(k, o.t_end);
    if (name == "output.dt_out") return number(k, o.dt_out);
    if (name == "output.file") return o.file.empty() ? std::nullopt : std::optional(text(k, o.file));
    if (name == "output.sensitivities") return text(k, joined_names(o.sensitivities));
    if (name == "output.loads") return text(k, to_string(o.loads));
    if (name == "initial.state") return text(k, to_string(s.initial));
    throw std::logic_error("effective_scene: no value for " + name);
}

}  // namespace

std::vector<SceneValue> effective_scene(const Scene& scene)
{
    std::vector<SceneValue> out;
    for (const SceneKey& k : scene_keys()) {
        const std::string table = k.table();
        const std::optional<SceneValue> v =
            table == "beam"                                                                  ? beam_value(scene, k)
            : table == "blade_scale"                                                         ? blade_scale_value(scene, k)
            : table == "motion"                                                              ? motion_value(scene, k)
            : table == "control"                                                             ? control_value(scene, k)
            : table == "rotor"                                                               ? rotor_value(scene, k)
            : (table == "hub" || table == "tip" || table == "damping" || table == "gravity" || table == "support")
                ? parameter_value(scene, k)
                                                                                             : run_value(scene, k);
        if (v) out.push_back(*v);
    }
    return out;
}

std::string toml_number(double v)
{
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return shortest(v);
}

std::string quoted_string(std::string_view s, Quoting quoting)
{
    std::string out;
    out.reserve(s.size() + 2);
    out += '"';
    for (std::size_t i = 0; i < s.size();) {
        const TextChar c = text_char(s, i);
        if (c.code == '"' || c.code == '\\') {
            out += '\\';
            out += static_cast<char>(c.code);
        } else if (c.code == '\n')
            out += "\\n";
        else if (c.code == '\t')
            out += "\\t";
        else if (!c.escaped)
            out.append(s.substr(i, c.length));
        else {  // a control, a bidirectional override, a byte that is not UTF-8: never sent to the terminal as it is
            char code[16];
            const auto u = static_cast<unsigned long>(c.code);
            if (u < 0x10000)
                std::snprintf(code, sizeof code, "\\u%04lx", u);
            else if (quoting == Quoting::toml)
                std::snprintf(code, sizeof code, "\\U%08lx", u);
            else
                std::snprintf(code, sizeof code, "\\u%04lx\\u%04lx", 0xd800 + ((u - 0x10000) >> 10),
                              0xdc00 + (u & 0x3ff));
            out += code;
        }
        i += c.length;
    }
    out += '"';
    return out;
}

std::string effective_scene_toml(const Scene& scene)
{
    std::string out, table;
    for (const SceneValue& v : effective_scene(scene)) {
        const std::string name = v.key, t = name.substr(0, name.find('.'));
        if (t != table) {
            out += (out.empty() ? "[" : "\n[") + t + "]\n";
            table = t;
        }
        out += name.substr(name.find('.') + 1) + " = ";
        switch (v.kind) {
            case SceneValue::Kind::number:
                out += toml_number(v.number);
                break;
            case SceneValue::Kind::integer:
                out += std::to_string(v.integer);
                break;
            case SceneValue::Kind::text:
                out += quoted_string(v.text);
                break;
            case SceneValue::Kind::numbers:
                out += '[';
                for (std::size_t i = 0; i < v.numbers.size(); ++i) out += (i ? ", " : "") + toml_number(v.numbers[i]);
                out += ']';
                break;
        }
        out += '\n';
    }
    return out;
}

}  // namespace hubbeam
