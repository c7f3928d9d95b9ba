// Scene files: TOML read with toml++, overrides set on the parsed table, every key checked for presence,
// type and range against one table of keys (scene_keys.cpp), every unknown key rejected. The format is documented
// in docs/scene.md; the symbols are those of docs/model.md.
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>
#include <optional>
#include <string_view>

#include "io/scene_io.hpp"

namespace hubbeam {

using namespace scene_io;

namespace {

/// A TOML value as the "got ..." part of a message, on one line.
std::string describe(const toml::node& n)
{
    switch (n.type()) {
        case toml::node_type::string: {
            return "a string \"" + printable(n.as_string()->get(), 40) + "\"";
        }
        case toml::node_type::integer:
            return "an integer " + std::to_string(n.as_integer()->get());
        case toml::node_type::floating_point:
            return "a float " + shortest(n.as_floating_point()->get());
        case toml::node_type::boolean:
            return std::string("a boolean ") + (n.as_boolean()->get() ? "true" : "false");
        case toml::node_type::array:
            return "an array";
        case toml::node_type::table:
            return "a table";
        case toml::node_type::date:
            return "a date";
        case toml::node_type::time:
            return "a time";
        case toml::node_type::date_time:
            return "a date-time";
        default:
            return "a value";
    }
}

/// One table of the scene file ([beam], [hub], ...); an absent table reads as empty.
class Section {
public:
    Section(const std::string& file, const toml::table& root, std::string name) : file_(file), name_(std::move(name))
    {
        if (const toml::node* n = root.get(name_)) table_ = n->as_table();
    }

    std::string path(std::string_view key) const { return name_ + "." + std::string(key); }
    const std::string& file() const { return file_; }
    const toml::node* get(std::string_view key) const { return table_ ? table_->get(key) : nullptr; }
    bool absent() const { return table_ == nullptr; }

    /// Rejects any key the key table does not give this table (for [motion], its kind): a mistyped key must not
    /// be silently ignored.
    void only(const std::string& motion_kind = "") const
    {
        if (!table_) return;
        const std::vector<std::string> allowed = table_keys(name_, motion_kind);
        const std::string note = motion_kind.empty() ? "" : " (the keys of kind = \"" + motion_kind + "\")";
        for (auto&& [k, v] : *table_) {
            if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end())
                fail(file_, path(k.str()), "one of " + joined(allowed) + note,
                     std::string("an unknown ") + (v.is_table() ? "table" : "key"));
        }
    }

    /// The key's value is out of range: expected what the key table says, got `got`.
    [[noreturn]] void refuse(std::string_view key, const std::string& got) const
    {
        hubbeam::fail(file_, path(key), expected(path(key)), got);
    }

    /// A number (TOML integer or float), or nullopt if the key is absent.
    std::optional<double> number(std::string_view key) const
    {
        const toml::node* n = get(key);
        if (!n) return std::nullopt;
        if (const auto* i = n->as_integer()) return static_cast<double>(i->get());
        if (const auto* f = n->as_floating_point()) return f->get();
        fail(file_, path(key), expected(path(key)), describe(*n));
    }
    double number(std::string_view key, double fallback) const { return number(key).value_or(fallback); }
    double required_number(std::string_view key, const std::string& why = "") const
    {
        if (const auto v = number(key)) return *v;
        fail(file_, path(key), expected(path(key)) + why, missing);
    }

    /// An array of numbers (TOML integers or floats), or nullopt if the key is absent.
    std::optional<std::vector<double>> numbers(std::string_view key) const
    {
        const toml::node* n = get(key);
        if (!n) return std::nullopt;
        const toml::array* a = n->as_array();
        if (!a) fail(file_, path(key), expected(path(key)), describe(*n));
        std::vector<double> out;
        for (const toml::node& e : *a) {
            if (const auto* i = e.as_integer())
                out.push_back(static_cast<double>(i->get()));
            else if (const auto* f = e.as_floating_point())
                out.push_back(f->get());
            else
                fail(file_, path(key), expected(path(key)), "an array holding " + describe(e));
        }
        return out;
    }

    /// A TOML integer that fits an int (floats such as 4.0 are rejected: a DOF count is a count).
    int required_integer(std::string_view key) const
    {
        const toml::node* n = get(key);
        if (!n) fail(file_, path(key), expected(path(key)), missing);
        const auto* i = n->as_integer();
        if (!i || i->get() < INT_MIN || i->get() > INT_MAX) fail(file_, path(key), expected(path(key)), describe(*n));
        return static_cast<int>(i->get());
    }

    /// An integer key that may be absent (fallback).
    int integer(std::string_view key, int fallback) const { return get(key) ? required_integer(key) : fallback; }

    std::string required_string(std::string_view key) const
    {
        if (const auto v = string(key)) return *v;
        fail(file_, path(key), expected(path(key)), missing);
    }

    std::optional<std::string> string(std::string_view key) const
    {
        const toml::node* n = get(key);
        if (!n) return std::nullopt;
        const auto* s = n->as_string();
        if (!s) fail(file_, path(key), expected(path(key)), describe(*n));
        // TOML allows "\u0000"; a C path or step-type name would end there ("a\u0000b.csv" would write "a").
        if (s->get().find('\0') != std::string::npos)
            fail(file_, path(key), expected(path(key)) + " with no NUL character", describe(*n));
        return s->get();
    }

    /// One of a fixed set of words, turned into its value by parse_word.
    template <class T, class F>
    std::optional<T> word(std::string_view key, F parse_word) const
    {
        const auto s = string(key);
        if (!s) return std::nullopt;
        T value{};
        if (!parse_word(*s, value)) fail(file_, path(key), expected(path(key)), describe(*get(key)));
        return value;
    }
    template <class T, class F>
    T required_word(std::string_view key, F parse_word) const
    {
        if (const auto v = word<T>(key, parse_word)) return *v;
        fail(file_, path(key), expected(path(key)), missing);
    }

private:
    const std::string& file_;
    std::string name_;
    const toml::table* table_ = nullptr;
};

template <class E>
bool parse_enum(std::string_view w, E& e)
{
    return hubbeam::parse(w, e);
}

toml::table parse_toml(std::string_view text, const std::string& path)
{
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        throw SceneError::with_detail(
            path + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column), "",
            description);
    }
}

/// The override's text as the TOML value its key holds; a text that is not of the key's kind is an error
/// naming the key.
void set_override(toml::table& root, const std::string& file, const std::string& name, const std::string& text)
{
    const SceneKey& key = scene_key(name);
    const std::size_t dot = name.find('.');
    const std::string table = name.substr(0, dot), leaf = name.substr(dot + 1);
    if (!root.contains(table)) root.insert_or_assign(table, toml::table{});
    if (!root[table].is_table()) return;  // the file's own error ("expected a table") is reported as it is
    toml::table& t = *root[table].as_table();
    const auto bad = [&] { fail(file, name, key.expected, "\"" + text + "\""); };
    switch (key.kind) {
        case SceneKey::Kind::integer: {
            long long v = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || end != text.data() + text.size()) bad();
            t.insert_or_assign(leaf, v);
            break;
        }
        case SceneKey::Kind::number: {
            double v = 0.0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || end != text.data() + text.size()) bad();
            t.insert_or_assign(leaf, v);
            break;
        }
        case SceneKey::Kind::word:
        case SceneKey::Kind::text:
        case SceneKey::Kind::file:
            t.insert_or_assign(leaf, text);
            break;
        case SceneKey::Kind::numbers: {
            // "0, 0.1, 0" or as TOML writes it, "[0, 0.1, 0]"; "[]" is none.
            std::string list(trimmed(text));
            if (list.size() >= 2 && list.front() == '[' && list.back() == ']') list = list.substr(1, list.size() - 2);
            toml::array a;
            for (const std::string& item : trimmed(list).empty() ? std::vector<std::string>{} : split_list(list)) {
                const std::string v(trimmed(item));
                double x = 0.0;
                const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
                if (v.empty() || ec != std::errc() || end != v.data() + v.size()) bad();
                a.push_back(x);
            }
            t.insert_or_assign(leaf, std::move(a));
            break;
        }
    }
}

/// The files root names: scene_files of a parsed scene, the one list of what a scene reads besides itself (the
/// readers of [beam] and [motion] open these same names).
std::vector<std::pair<std::string, std::string>> named_files(const toml::table& root, const std::string& path)
{
    std::vector<std::pair<std::string, std::string>> files;
    for (const SceneKey* k : file_keys()) {
        const std::string_view name = k->name;
        const std::size_t dot = name.find('.');
        const toml::node* table = root.get(name.substr(0, dot));
        const toml::node* value = table != nullptr && table->is_table() ? table->as_table()->get(name.substr(dot + 1))
                                                                        : nullptr;
        if (value == nullptr || !value->is_string()) continue;  // absent, or of the wrong type: the reader says so
        const std::string& file = value->as_string()->get();
        if (!file.empty()) files.emplace_back(k->name, table_path(path, file));
    }
    return files;
}

// The parts of parse_scene, in the order it calls them: the file as a whole, then one table each. A table's
// reader takes its keys' values; ranges and the checks that join keys are validate()'s.

void check_size(std::string_view text, const std::string& path)
{
    if (text.size() > max_scene_bytes)
        throw SceneError::with_detail(
            path, "", "is larger than a scene file can be (" + std::to_string(max_scene_bytes / 1024) + " KB)");
}

/// Every top-level name is one of the key table's tables and is a table; the tables without a default are there.
void check_tables(const toml::table& root, const std::string& path)
{
    const std::vector<std::string> tables = scene_tables();
    for (auto&& [k, v] : root) {
        const bool known = std::find(tables.begin(), tables.end(), k.str()) != tables.end();
        if (!known)
            fail(path, std::string(k.str()), "one of the tables " + joined(tables),
                 std::string("an unknown ") + (v.is_table() ? "table" : "key"));
        if (!v.is_table()) fail(path, std::string(k.str()), "a table [" + std::string(k.str()) + "]", describe(v));
    }
    for (const char* required : {"beam", "motion", "discretization", "output"})
        if (!root.get(required))
            fail(path, required, std::string("a table [") + required + "]", "nothing (the table is missing)");
}

/// [beam]'s out-of-plane keys (docs/model.md section 12); a zero pitch, pre-twist or precone leaves its term out.
void read_out_of_plane_section(const Section& beam, Parameters& p)
{
    p.G = beam.number("shear_modulus", p.G);
    p.J_t = beam.number("torsion_constant", p.J_t);
    p.pitch = beam.number("pitch", p.pitch);
    p.twist = beam.number("twist", p.twist);
    p.precone = beam.number("precone", p.precone);
}

/// [gravity] direction: "plane" (g along -j of the inertial plane) or "axis" (along -k): the weight goes to g or to
/// g_axis (docs/model.md section 12).
void read_gravity_direction(const Section& gravity, Parameters& p)
{
    if (gravity.absent()) return;
    const auto direction = gravity.string("direction");
    if (!direction || *direction == "plane") return;
    if (*direction != "axis") gravity.refuse("direction", describe(*gravity.get("direction")));
    p.g_axis = p.g;
    p.g = 0.0;
}

/// [blade_scale]: factors on beam.blade_file's columns (docs/scene.md), each in its key's range (a mass or a stiffness
/// > 0, a mass moment >= 0, an offset's any finite number); one other than 1 is refused without a blade file, where it
/// would scale nothing.
BladeScale read_blade_scale(const Section& s, const Section& beam)
{
    BladeScale scale;
    if (s.absent()) return scale;
    s.only();
    const auto blade = beam.string("blade_file");
    for (const BladeScaleField& f : blade_scale_fields) {
        const std::optional<double> v = s.number(f.key);
        if (!v) continue;
        const std::string_view key = f.key;
        const bool offset = key.ends_with("offset"), moment = key.starts_with("inertia");
        if (!std::isfinite(*v) || (!offset && *v < 0.0) || (!offset && !moment && *v == 0.0))
            s.refuse(f.key, shortest(*v));
        if (*v != 1.0 && (!blade || blade->empty()))
            throw SceneError::with_detail(s.file(), s.path(f.key),
                                          "not used without beam.blade_file (it scales the file's column): remove it");
        scale.*f.factor = *v;
    }
    return scale;
}

/// [beam]: docs/model.md section 1, the taper of section 11 (a taper kind without a ratio is refused: the default
/// ratio 1 would make it uniform without a word) and the tabulated profile of section 11.2 (the section's keys and
/// a taper with it are refused: the table gives the beam's distributions). Returns the profile table, if any.
std::optional<ProfileTable> read_beam(const Section& beam, const std::string& scene_path, const BladeScale& scale,
                                      Parameters& p, Extras& extras)
{
    beam.only();
    p.L = beam.required_number("length");
    read_out_of_plane_section(beam, p);
    const auto profile = beam.string("profile"), blade = beam.string("blade_file");
    const bool tabulated = profile && !profile->empty(), from_file = blade && !blade->empty();
    if (tabulated && from_file)
        throw SceneError::with_detail(scene_path, beam.path("blade_file"),
                                      "not used with beam.profile (one table gives the section): remove one");
    const int resample = beam.integer("blade_stations", 0);
    if (resample != 0 && !from_file)
        throw SceneError::with_detail(scene_path, beam.path("blade_stations"),
                                      "not used without beam.blade_file: remove it");
    if (resample != 0 && (resample < 2 || resample > static_cast<int>(scene_io::max_profile_stations))) beam.refuse("blade_stations", std::to_string(resample));
    if (tabulated || from_file) {
        const char* by = tabulated ? "beam.profile" : "beam.blade_file";
        for (const char* key : keys_a_table_replaces)
            if (beam.get(key))
                throw SceneError::with_detail(
                    scene_path, beam.path(key),
                    std::string("not used with ") + by + " (its table gives the section along the span): remove it");
        if (tabulated) return read_profile(scene_path, *profile, p, extras);
        return read_blade(scene_path, *blade, resample, scale, p, extras);
    }
    p.rho = beam.required_number("density");
    p.S = beam.required_number("area");
    p.I = beam.required_number("second_moment");
    p.I_flap = beam.number("second_moment_flap", p.I);
    p.E = beam.required_number("youngs_modulus");
    Taper& taper = extras.taper;
    taper = beam.word<Taper>("taper", parse_enum<Taper>).value_or(Taper::uniform);
    if (taper != Taper::uniform)
        p.tip_ratio = beam.required_number("tip_ratio", ", required for a taper");
    else if (const auto r = beam.number("tip_ratio"); r && *r != 1.0)
        beam.refuse("tip_ratio", shortest(*r) + " without beam.taper = \"width\" or \"depth\"");
    return std::nullopt;
}

/// [tip], [damping], [gravity]: the extra terms of docs/model.md section 11; absent tables leave them out.
void read_extras(const toml::table& root, const std::string& path, Parameters& p)
{
    // Each term's own table and keys are the registry's (terms.hpp): every table is checked before any is read.
    for (const TermInfo& t : terms())
        if (!t.scene_keys.empty()) Section(path, root, t.scene_keys.front().table).only();
    for (const TermInfo& t : terms())
        for (const TermSceneKey& k : t.scene_keys)
            value(p, k.param) = Section(path, root, k.table).number(k.key, value(p, k.param));
}

/// [motion]: paper eq. 58 (spin-up) or eq. 59 (torque), a held hub, or a table of theta or tau against time; the
/// kind decides which keys the table may hold.
void read_motion(const Section& motion, const std::string& path, Motion& m)
{
    m.kind = motion.required_word<Motion::Kind>("kind", parse_kind);
    motion.only(kind_word(m.kind));
    switch (m.kind) {
        case Motion::Kind::spin_up:
            m.omega0 = motion.required_number("omega0");
            m.spin_time = motion.required_number("duration");
            break;
        case Motion::Kind::torque:
            m.tau0 = motion.required_number("tau0");
            m.torque_time = motion.required_number("duration");
            break;
        case Motion::Kind::held:
            m.angle = motion.required_number("angle");
            break;
        case Motion::Kind::step:
            m.angle = motion.required_number("angle");
            m.omega0 = 0.0;  // no spin: what reads the final rate of a motion (modes' default rates) reads none
            break;
        case Motion::Kind::table:
        case Motion::Kind::torque_table: {
            const std::string file = motion.required_string("file");
            if (file.empty()) motion.refuse("file", "an empty one");
            const bool angle = m.kind == Motion::Kind::table;
            m.table_file = table_path(path, file);
            // The angle's rate and acceleration enter the equations: a C2 spline. A torque enters as it is, and a
            // test rig's record is piecewise constant or linear: straight lines, each row a breakpoint, so a step
            // stays a step (a spline would overshoot it).
            m.table = read_drive_table(
                path, m.table_file, angle ? "theta" : "tau", angle ? "the hub angle, rad" : "the hub torque, N m",
                angle ? DriveTable::Interpolation::cubic_spline : DriveTable::Interpolation::linear);
            break;
        }
    }
    m.theta0 = motion.number("theta0", m.theta0);
}

/// [control]: docs/model.md section 11; absent, the hub follows its motion.
void read_control(const Section& control, std::optional<Control>& c)
{
    if (control.absent()) return;
    control.only();
    c.emplace();
    c->kp = control.required_number("kp");
    c->kd = control.required_number("kd");
    c->ki = control.number("ki", c->ki);
    c->tau_max = control.number("tau_max", c->tau_max);
    c->k_tip = control.number("k_tip", c->k_tip);
}

/// [hub]: the hub inertia only enters the torque drives (or a controlled hub), where theta is a coordinate.
void read_hub(const Section& hub, const Scene& scene, Parameters& p)
{
    hub.only();
    p.a = hub.number("radius", p.a);
    if (hub.get("mass") && !scene.variant.extras.hub)
        throw SceneError::with_detail(scene.path, hub.path("mass"),
                                      "only with a [support] table (the hub translates on its support): add one");
    p.m_hub = hub.number("mass", p.m_hub);
    const Motion::Kind kind = scene.motion.kind;
    if (scene.control)
        p.J_oh = hub.required_number("inertia", ", required for a controlled hub ([control])");
    else if (kind == Motion::Kind::torque || kind == Motion::Kind::torque_table)
        p.J_oh = hub.required_number("inertia", ", required for kind = \"" + kind_word(kind) + "\"");
    else
        p.J_oh = hub.number("inertia", p.J_oh);
}

/// [damping]'s arrays: the modal damping of docs/model.md section 11.5 (its keys checked by read_extras); their
/// ranges are validate()'s, the count of the blade's modes make_scene_model's.
void read_modal_damping(const Section& damping, ModalDamping& d)
{
    d.flap = damping.numbers("flap_ratios").value_or(d.flap);
    d.edge = damping.numbers("edge_ratios").value_or(d.edge);
}

/// [rotor]: docs/model.md section 13; its arrays' lengths and ranges are validate()'s.
void read_rotor(const Section& rotor, Rotor& r)
{
    rotor.only();
    r.blades = rotor.integer("blades", r.blades);
    r.pitch_offsets = rotor.numbers("pitch_offsets").value_or(r.pitch_offsets);
    r.tip_masses = rotor.numbers("tip_masses").value_or(r.tip_masses);
}

/// [discretization]: docs/model.md section 4; the variant's drive follows the motion.
void read_discretization(const Section& disc, const Scene& scene, VariantKey& key)
{
    disc.only();
    key.method = disc.required_word<Method>("method", parse_enum<Method>);
    key.ny = disc.required_integer("ny");
    key.nx = disc.required_integer("nx");
    key.nz = disc.integer("nz", key.nz);
    key.nt = disc.integer("nt", key.nt);
    key.spline = disc.word<SplineBasis>("spline_basis", parse_enum<SplineBasis>).value_or(key.spline);
    key.drive = scene.drive();
}

/// [model]: docs/model.md section 3; whether the build can run an order is make_model's call.
void read_model(const Section& model, Scene& scene)
{
    model.only();
    scene.variant.order = model.word<Order>("order", parse_enum<Order>).value_or(scene.variant.order);
    scene.source = model.word<ModelSource>("source", parse_enum<ModelSource>).value_or(scene.source);
    scene.axial = model.word<Axial>("axial", parse_enum<Axial>).value_or(scene.axial);
}

/// [solver]: the stepper word is checked against GSL's step types by validate().
void read_solver(const Section& solver, SolverOptions& so)
{
    solver.only();
    so.stepper = solver.string("stepper").value_or(so.stepper);
    so.rtol = solver.number("rtol", so.rtol);
    so.atol = solver.number("atol", so.atol);
    so.h0 = solver.number("h0", so.h0);
    so.stepping = solver.word<Stepping>("stepping", parse_enum<Stepping>).value_or(so.stepping);
    so.error_check = solver.word<ErrorCheck>("error_check", parse_enum<ErrorCheck>).value_or(so.error_check);
    so.sensitivity_error_control =
        solver.word<SensitivityErrorControl>("sensitivity_error_control", parse_enum<SensitivityErrorControl>)
            .value_or(so.sensitivity_error_control);
    if (const auto budget = solver.number("max_steps")) {  // 1e7 reads better than 10000000: a float is accepted
        if (!(*budget >= 1.0 && *budget <= 1e15 && *budget == std::floor(*budget)))
            solver.refuse("max_steps", shortest(*budget));
        so.max_steps = static_cast<long>(*budget);
    }
}

/// [output]
void read_output(const Section& output, OutputOptions& out)
{
    output.only();
    out.t_end = output.required_number("t_end");
    out.dt_out = output.number("dt_out", out.dt_out);
    if (const auto file = output.string("file")) {
        // An empty name is refused, not read as "the default": -o "" is more likely a lost shell variable.
        if (file->empty()) output.refuse("file", "an empty one");
        out.file = *file;
    }
    if (const auto names = output.string("sensitivities")) {
        out.sensitivities.clear();
        if (!trimmed(*names).empty())  // "" asks for none
            for (const std::string& item : split_list(*names)) out.sensitivities.emplace_back(trimmed(item));
    }
    out.loads = output.word<OutputLoads>("loads", parse_enum<OutputLoads>).value_or(out.loads);
}

/// [initial]: where the run starts; whether the scene has that state is validate()'s.
void read_initial(const Section& initial, Scene& scene)
{
    initial.only();
    scene.initial = initial.word<InitialState>("state", parse_enum<InitialState>).value_or(scene.initial);
}

}  // namespace

Scene load_scene(const std::string& path, const Overrides& overrides)
{
    return parse_scene(read_file(path), path, overrides);
}

Scene parse_scene(std::string_view text, const std::string& path, const Overrides& overrides)
{
    check_size(text, path);
    toml::table root = parse_toml(text, path);
    for (const auto& [name, value] : overrides) set_override(root, path, name, value);
    check_tables(root, path);

    Scene scene;
    scene.path = path;
    scene.blade_scale = read_blade_scale(Section(path, root, "blade_scale"), Section(path, root, "beam"));
    const std::optional<ProfileTable> profile =
        read_beam(Section(path, root, "beam"), path, scene.blade_scale, scene.parameters, scene.variant.extras);
    scene.tables = named_files(root, path);
    if (profile) scene.blade_stations = profile->resample;
    read_extras(root, path, scene.parameters);
    read_modal_damping(Section(path, root, "damping"), scene.modal_damping);
    // [support] makes the hub translate (docs/model.md section 13), at any stiffness: 0 is a free-floating hub.
    scene.variant.extras.hub = !Section(path, root, "support").absent();
    read_gravity_direction(Section(path, root, "gravity"), scene.parameters);
    read_motion(Section(path, root, "motion"), path, scene.motion);
    read_control(Section(path, root, "control"), scene.control);
    read_hub(Section(path, root, "hub"), scene, scene.parameters);
    read_rotor(Section(path, root, "rotor"), scene.rotor);
    read_discretization(Section(path, root, "discretization"), scene, scene.variant);
    read_model(Section(path, root, "model"), scene);
    read_solver(Section(path, root, "solver"), scene.solver);
    read_output(Section(path, root, "output"), scene.output);
    read_initial(Section(path, root, "initial"), scene);
    if (profile) fit_profile(path, *profile, scene.key(), scene.parameters);
    validate(scene);
    return scene;
}

std::vector<std::pair<std::string, std::string>> scene_files(std::string_view text, const std::string& path,
                                                             const Overrides& overrides)
{
    check_size(text, path);
    toml::table root = parse_toml(text, path);
    for (const auto& [name, value] : overrides) set_override(root, path, name, value);
    return named_files(root, path);
}

}  // namespace hubbeam
