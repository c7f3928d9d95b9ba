// Scene files: TOML read with toml++, every key checked for presence, type and range, every unknown key
// rejected. The format is documented in README.md ("Scene files"); the symbols are those of MODEL.md.
#include "scene.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "integrate.hpp"

namespace hubbeam {

namespace {

// What each checked key must hold: the "expected ..." part of every message about it, shared by the
// type checks of load_scene() and the range checks of validate().
constexpr const char* expect_length = "a number > 0 (L, m)";
constexpr const char* expect_density = "a number > 0 (rho, kg/m^3)";
constexpr const char* expect_area = "a number > 0 (S, m^2)";
constexpr const char* expect_second_moment = "a number > 0 (I, m^4)";
constexpr const char* expect_youngs = "a number > 0 (E, Pa)";
constexpr const char* expect_radius = "a number >= 0 (a, m)";
constexpr const char* expect_inertia = "a number > 0 (J_oh, kg m^2)";
constexpr const char* expect_omega0 = "a finite number (Omega0, rad/s)";
constexpr const char* expect_tau0 = "a finite number (tau0, N m)";
constexpr const char* expect_spin_time = "a number > 0 (T_s, s)";
constexpr const char* expect_torque_time = "a number > 0 (T_t, s)";
constexpr const char* expect_nx = "an integer >= 0 (Nx)";
constexpr const char* expect_ny = "an integer >= 1 (Ny)";
constexpr const char* expect_rtol = "a number > 0 (relative tolerance)";
constexpr const char* expect_atol = "a number > 0 (absolute tolerance)";
constexpr const char* expect_h0 = "a number > 0 (first trial step, s)";
constexpr const char* expect_t_end = "a number > 0 (end time, s)";
constexpr const char* expect_dt_out = "a number > 0 and <= output.t_end (output interval, s)";
constexpr const char* missing = "nothing (the key is missing)";

/// Shortest text that reads back as the same double.
std::string format_number(double v)
{
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

/// A TOML value as the "got ..." part of a message, on one line.
std::string describe(const toml::node& n)
{
    switch (n.type()) {
        case toml::node_type::string: {
            std::string s(n.as_string()->get());
            if (s.size() > 40) s = s.substr(0, 40) + "...";
            for (char& ch : s)
                if (static_cast<unsigned char>(ch) < 0x20) ch = '?';
            return "a string \"" + s + "\"";
        }
        case toml::node_type::integer:
            return "an integer " + std::to_string(n.as_integer()->get());
        case toml::node_type::floating_point:
            return "a float " + format_number(n.as_floating_point()->get());
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

std::string file_label(const std::string& path)
{
    return path.empty() ? std::string("<scene>") : path;
}

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& expected,
                       const std::string& got)
{
    throw SceneError(file_label(file) + ": " + key + ": expected " + expected + ", got " + got);
}

/// One table of the scene file ([beam], [hub], ...), absent tables read as empty.
class Section {
public:
    Section(const std::string& file, const toml::table& root, std::string name) : file_(file), name_(std::move(name))
    {
        if (const toml::node* n = root.get(name_)) table_ = n->as_table();
    }

    bool present() const { return table_ != nullptr; }
    std::string path(std::string_view key) const { return name_ + "." + std::string(key); }
    const toml::node* get(std::string_view key) const { return table_ ? table_->get(key) : nullptr; }

    /// Rejects any key not in allowed (a mistyped key must not be silently ignored).
    void only(const std::vector<std::string>& allowed, const std::string& note = "") const
    {
        if (!table_) return;
        for (auto&& [k, v] : *table_) {
            if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end())
                fail(file_, path(k.str()), "one of " + joined(allowed) + note,
                     std::string("an unknown ") + (v.is_table() ? "table" : "key"));
        }
    }

    /// A number (TOML integer or float), or nullopt if the key is absent.
    std::optional<double> number(std::string_view key, const char* expected) const
    {
        const toml::node* n = get(key);
        if (!n) return std::nullopt;
        if (const auto* i = n->as_integer()) return static_cast<double>(i->get());
        if (const auto* f = n->as_floating_point()) return f->get();
        fail(file_, path(key), expected, describe(*n));
    }
    double number(std::string_view key, const char* expected, double fallback) const
    {
        return number(key, expected).value_or(fallback);
    }
    double required_number(std::string_view key, const char* expected, const std::string& why = "") const
    {
        if (const auto v = number(key, expected)) return *v;
        fail(file_, path(key), expected + why, missing);
    }

    /// A TOML integer that fits an int (floats such as 4.0 are rejected: a DOF count is a count).
    int required_integer(std::string_view key, const char* expected) const
    {
        const toml::node* n = get(key);
        if (!n) fail(file_, path(key), expected, missing);
        const auto* i = n->as_integer();
        if (!i) fail(file_, path(key), expected, describe(*n));
        if (i->get() < INT_MIN || i->get() > INT_MAX) fail(file_, path(key), expected, describe(*n));
        return static_cast<int>(i->get());
    }

    std::optional<std::string> string(std::string_view key, const std::string& expected) const
    {
        const toml::node* n = get(key);
        if (!n) return std::nullopt;
        if (const auto* s = n->as_string()) return s->get();
        fail(file_, path(key), expected, describe(*n));
    }

    /// One of a fixed set of words; parse_word turns it into the value.
    template <class T, class F>
    std::optional<T> word(std::string_view key, const std::vector<std::string>& words, F parse_word) const
    {
        const std::string expected = "one of " + joined(words, "\"");
        const auto s = string(key, expected);
        if (!s) return std::nullopt;
        T value{};
        if (!parse_word(*s, value)) fail(file_, path(key), expected, describe(*get(key)));
        return value;
    }
    template <class T, class F>
    T required_word(std::string_view key, const std::vector<std::string>& words, F parse_word) const
    {
        if (const auto v = word<T>(key, words, parse_word)) return *v;
        fail(file_, path(key), "one of " + joined(words, "\""), missing);
    }

private:
    const std::string& file_;
    std::string name_;
    const toml::table* table_ = nullptr;
};

bool parse_kind(std::string_view w, Motion::Kind& k)
{
    if (w == "spin-up")
        k = Motion::Kind::spin_up;
    else if (w == "torque")
        k = Motion::Kind::torque;
    else
        return false;
    return true;
}

template <class E>
bool parse_enum(std::string_view w, E& e)
{
    return hubbeam::parse(w, e);
}

std::string read_file(const std::string& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw SceneError(file_label(path) + ": cannot open");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(file_label(path) + ": cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw SceneError(file_label(path) + ": cannot open");
    return text.str();
}

toml::table parse_toml(const std::string& path)
{
    const std::string text = read_file(path);
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        throw SceneError(file_label(path) + ":" + std::to_string(e.source().begin.line) + ":" +
                         std::to_string(e.source().begin.column) + ": " + description);
    }
}

// Range checks of validate(), naming the key.
void check_positive(const Scene& s, double v, const char* key, const char* expected)
{
    if (!(v > 0.0) || !std::isfinite(v)) fail(s.path, key, expected, format_number(v));
}
void check_finite(const Scene& s, double v, const char* key, const char* expected)
{
    if (!std::isfinite(v)) fail(s.path, key, expected, format_number(v));
}

}  // namespace

Scene load_scene(const std::string& path)
{
    const toml::table root = parse_toml(path);
    const std::vector<std::string> tables = {"beam", "hub", "motion", "discretization", "model", "solver", "output"};
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

    Scene scene;
    scene.path = path;

    // [beam]: MODEL.md section 1.
    const Section beam(path, root, "beam");
    beam.only({"length", "density", "area", "second_moment", "youngs_modulus"});
    Parameters& p = scene.parameters;
    p.L = beam.required_number("length", expect_length);
    p.rho = beam.required_number("density", expect_density);
    p.S = beam.required_number("area", expect_area);
    p.I = beam.required_number("second_moment", expect_second_moment);
    p.E = beam.required_number("youngs_modulus", expect_youngs);

    // [motion]: paper eq. 58 (spin-up) or eq. 59 (torque).
    const Section motion(path, root, "motion");
    Motion& m = scene.motion;
    m.kind = motion.required_word<Motion::Kind>("kind", {"spin-up", "torque"}, parse_kind);
    if (m.kind == Motion::Kind::spin_up) {
        motion.only({"kind", "omega0", "duration"}, " (the keys of kind = \"spin-up\")");
        m.omega0 = motion.required_number("omega0", expect_omega0);
        m.spin_time = motion.required_number("duration", expect_spin_time);
    } else {
        motion.only({"kind", "tau0", "duration"}, " (the keys of kind = \"torque\")");
        m.tau0 = motion.required_number("tau0", expect_tau0);
        m.torque_time = motion.required_number("duration", expect_torque_time);
    }

    // [hub]: the hub inertia only enters the torque case, where theta is a coordinate.
    const Section hub(path, root, "hub");
    hub.only({"radius", "inertia"});
    p.a = hub.number("radius", expect_radius, 0.0);
    if (m.kind == Motion::Kind::torque)
        p.J_oh = hub.required_number("inertia", expect_inertia, ", required for kind = \"torque\"");
    else
        p.J_oh = hub.number("inertia", expect_inertia, 30.0);

    // [discretization]: MODEL.md section 4.
    const Section disc(path, root, "discretization");
    disc.only({"method", "ny", "nx", "spline_basis"});
    VariantKey& key = scene.variant;
    key.method = disc.required_word<Method>("method", words<Method>(), parse_enum<Method>);
    key.ny = disc.required_integer("ny", expect_ny);
    key.nx = disc.required_integer("nx", expect_nx);
    key.spline =
        disc.word<SplineBasis>("spline_basis", words<SplineBasis>(), parse_enum<SplineBasis>).value_or(SplineBasis::paper);
    key.drive = m.drive();

    // [model]: MODEL.md section 3; whether the build can run an order is make_model's call.
    const Section model(path, root, "model");
    model.only({"order", "source"});
    key.order = model.word<Order>("order", words<Order>(), parse_enum<Order>).value_or(Order::first);
    scene.source = model.word<ModelSource>("source", words<ModelSource>(), parse_enum<ModelSource>)
                       .value_or(ModelSource::automatic);

    // [solver]
    const Section solver(path, root, "solver");
    solver.only({"stepper", "rtol", "atol", "h0"});
    SolverOptions& so = scene.solver;
    so.stepper = solver.string("stepper", "one of " + joined(stepper_names(), "\"")).value_or(so.stepper);
    so.rtol = solver.number("rtol", expect_rtol, so.rtol);
    so.atol = solver.number("atol", expect_atol, so.atol);
    so.h0 = solver.number("h0", expect_h0, so.h0);

    // [output]
    const Section output(path, root, "output");
    output.only({"t_end", "dt_out", "file"});
    OutputOptions& out = scene.output;
    out.t_end = output.required_number("t_end", expect_t_end);
    out.dt_out = output.number("dt_out", expect_dt_out, 0.01);
    out.file = output.string("file", "a file name").value_or("");

    validate(scene);
    return scene;
}

void validate(const Scene& s)
{
    const Parameters& p = s.parameters;
    check_positive(s, p.L, "beam.length", expect_length);
    check_positive(s, p.rho, "beam.density", expect_density);
    check_positive(s, p.S, "beam.area", expect_area);
    check_positive(s, p.I, "beam.second_moment", expect_second_moment);
    check_positive(s, p.E, "beam.youngs_modulus", expect_youngs);
    if (!(p.a >= 0.0) || !std::isfinite(p.a)) fail(s.path, "hub.radius", expect_radius, format_number(p.a));
    check_positive(s, p.J_oh, "hub.inertia", expect_inertia);

    if (s.motion.kind == Motion::Kind::spin_up) {
        check_finite(s, s.motion.omega0, "motion.omega0", expect_omega0);
        check_positive(s, s.motion.spin_time, "motion.duration", expect_spin_time);
    } else {
        check_finite(s, s.motion.tau0, "motion.tau0", expect_tau0);
        check_positive(s, s.motion.torque_time, "motion.duration", expect_torque_time);
    }

    // DOF counts: a problem that persists with nx = 0 is about ny.
    const VariantKey& key = s.variant;
    if (key.ny < 1) fail(s.path, "discretization.ny", expect_ny, std::to_string(key.ny));
    if (key.nx < 0) fail(s.path, "discretization.nx", expect_nx, std::to_string(key.nx));
    if (const std::string problem = key.dof_problem(); !problem.empty()) {
        VariantKey without_axial = key;
        without_axial.nx = 0;
        const char* name = without_axial.dof_problem().empty() ? "discretization.nx" : "discretization.ny";
        throw SceneError(file_label(s.path) + ": " + name + ": " + problem);
    }

    const std::vector<std::string> steppers = stepper_names();
    if (std::find(steppers.begin(), steppers.end(), s.solver.stepper) == steppers.end())
        fail(s.path, "solver.stepper", "one of " + joined(steppers, "\""), "\"" + s.solver.stepper + "\"");
    check_positive(s, s.solver.rtol, "solver.rtol", expect_rtol);
    check_positive(s, s.solver.atol, "solver.atol", expect_atol);
    check_positive(s, s.solver.h0, "solver.h0", expect_h0);

    check_positive(s, s.output.t_end, "output.t_end", expect_t_end);
    if (!(s.output.dt_out > 0.0) || !(s.output.dt_out <= s.output.t_end))
        fail(s.path, "output.dt_out", expect_dt_out,
             format_number(s.output.dt_out) + " with t_end = " + format_number(s.output.t_end));
}

}  // namespace hubbeam
