// Scene files: TOML read with toml++, overrides set on the parsed table, every key checked for presence,
// type and range against one table of keys, every unknown key rejected. The format is documented in
// docs/scene.md; the symbols are those of docs/model.md.
#include "scene.hpp"

#include "output_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

#include "csv_columns.hpp"
#include "integrate.hpp"
#include "shortest.hpp"

namespace hubbeam {

namespace {
const WordTable<ErrorCheck, 2> error_check_words = {{ErrorCheck::on, "on"}, {ErrorCheck::off, "off"}};
}  // namespace

std::string to_string(ErrorCheck v) { return word_of(v, error_check_words); }
bool parse(std::string_view w, ErrorCheck& v) { return parse_word(w, error_check_words, v); }
template <> std::vector<std::string> words<ErrorCheck>() { return all_words(error_check_words); }

namespace {

constexpr const char* missing = "nothing (the key is missing)";

// The words of motion.kind; the key table's motion_kinds entries are among them (tests/test_scene.cpp).
const WordTable<Motion::Kind, 6> kind_words = {{Motion::Kind::spin_up, "spin-up"},
                                               {Motion::Kind::torque, "torque"},
                                               {Motion::Kind::held, "held"},
                                               {Motion::Kind::table, "table"},
                                               {Motion::Kind::torque_table, "torque-table"},
                                               {Motion::Kind::step, "step"}};

std::vector<std::string> motion_kinds() { return all_words(kind_words); }

bool parse_kind(std::string_view w, Motion::Kind& k) { return parse_word(w, kind_words, k); }

std::string one_of(const std::vector<std::string>& words) { return "one of " + joined(words, "\""); }

/// "auto" (the stepper for the scene's stiffness), then every GSL step type.
std::vector<std::string> stepper_words()
{
    std::vector<std::string> w = {automatic_stepper_word};
    for (const std::string& s : stepper_names()) w.push_back(s);
    return w;
}

std::vector<SceneKey> make_scene_keys()
{
    using K = SceneKey::Kind;
    return {
        {"beam.length", nullptr, K::number, "a number > 0 (L, m)"},
        {"beam.density", nullptr, K::number, "a number > 0 (rho, kg/m^3)"},
        {"beam.area", nullptr, K::number, "a number > 0 (S, m^2)"},
        {"beam.second_moment", nullptr, K::number, "a number > 0 (I, m^4)"},
        {"beam.youngs_modulus", nullptr, K::number, "a number > 0 (E, Pa)"},
        {"beam.taper", nullptr, K::word, one_of(words<Taper>())},
        {"beam.tip_ratio", nullptr, K::number, "a number > 0 (the tapered dimension at the tip over the root)"},
        {"beam.profile", nullptr, K::text,
         "a CSV file name relative to the scene's folder, with the columns x/L, m, EI, ES (m kg/m, EI N m^2, ES N); "
         "empty: none"},
        {"hub.radius", nullptr, K::number, "a number >= 0 (a, m)"},
        {"hub.inertia", nullptr, K::number, "a number > 0 (J_oh, kg m^2)"},
        {"tip.mass", nullptr, K::number, "a number >= 0 (m_tip, kg)"},
        {"tip.inertia", nullptr, K::number, "a number >= 0 (J_tip, kg m^2)"},
        {"damping.mass_proportional", nullptr, K::number, "a number >= 0 (alpha, 1/s)"},
        {"damping.stiffness_proportional", nullptr, K::number, "a number >= 0 (beta, s)"},
        {"gravity.g", nullptr, K::number, "a finite number (g, m/s^2)"},
        {"motion.kind", nullptr, K::word, one_of(motion_kinds())},
        {"motion.omega0", nullptr, K::number, "a finite number (Omega0, rad/s)", {"spin-up"}},
        {"motion.tau0", nullptr, K::number, "a finite number (tau0, N m)", {"torque"}},
        {"motion.duration", nullptr, K::number, "a number > 0 (T_s or T_t, s)", {"spin-up", "torque"}},
        {"motion.theta0", nullptr, K::number, "a finite number (theta0, rad)", {"spin-up", "torque", "table", "torque-table"}},
        {"motion.angle", nullptr, K::number, "a finite number (the hub angle, rad)", {"held", "step"}},
        {"motion.file", nullptr, K::text, "a CSV file with columns t, theta (table) or t, tau (torque-table)",
         {"table", "torque-table"}},
        {"control.kp", nullptr, K::number, "a number >= 0 (kp, N m/rad)"},
        {"control.kd", nullptr, K::number, "a number >= 0 (kd, N m s/rad)"},
        {"control.ki", nullptr, K::number, "a number >= 0 (ki, N m/(rad s))"},
        {"control.tau_max", nullptr, K::number, "a number > 0 or inf (tau_max, N m)"},
        {"control.k_tip", nullptr, K::number, "a finite number (k_tip, N m/m)"},
        {"discretization.method", "--method", K::word, one_of(words<Method>())},
        {"discretization.ny", "--ny", K::integer, "an integer >= 1 (Ny)"},
        {"discretization.nx", "--nx", K::integer, "an integer >= 0 (Nx)"},
        {"discretization.spline_basis", "--spline-basis", K::word, one_of(words<SplineBasis>())},
        {"model.order", "--order", K::word, one_of(words<Order>())},
        {"model.source", "--source", K::word, one_of(words<ModelSource>())},
        {"model.axial", "--axial", K::word, one_of(words<Axial>())},
        {"solver.stepper", "--stepper", K::word, one_of(stepper_words())},
        {"solver.rtol", "--rtol", K::number, "a number in (0, 1) (relative tolerance)"},
        {"solver.atol", "--atol", K::number, "a number > 0 (absolute tolerance)"},
        {"solver.h0", "--h0", K::number, "a number > 0 (first trial step, s)"},
        {"solver.stepping", "--stepping", K::word, one_of(words<Stepping>())},
        {"solver.max_steps", "--max-steps", K::number, "a whole number from 1 to 1e15 (step budget)"},
        {"solver.error_check", "--error-check", K::word, one_of(words<ErrorCheck>())},
        {"output.t_end", "--t-end", K::number, "a number > 0 (end time, s)"},
        {"output.dt_out", "--dt-out", K::number, "a number > 0 and <= output.t_end (output interval, s)"},
        {"output.file", "-o,--output", K::text, "a file name"},
        {"output.sensitivities", "--sensitivities", K::text,
         "parameter symbols separated by commas, each once: L, rho, S, I, E, a, J_oh, m_tip, J_tip, g, alpha, beta, "
         "tip_ratio, kp, kd, ki, k_tip"},
    };
}

const std::string& expected(const std::string& key) { return scene_key(key).expected; }

/// A TOML value as the "got ..." part of a message, on one line.
std::string describe(const toml::node& n)
{
    switch (n.type()) {
    case toml::node_type::string: {
        return "a string \"" + printable(n.as_string()->get(), 40) + "\"";
    }
    case toml::node_type::integer: return "an integer " + std::to_string(n.as_integer()->get());
    case toml::node_type::floating_point: return "a float " + shortest(n.as_floating_point()->get());
    case toml::node_type::boolean: return std::string("a boolean ") + (n.as_boolean()->get() ? "true" : "false");
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "a value";
    }
}

std::string file_label(const std::string& path) { return path.empty() ? std::string("<scene>") : path; }

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& expected,
                       const std::string& got)
{
    throw SceneError(file, key, expected, got);
}

/// One table of the scene file ([beam], [hub], ...); an absent table reads as empty.
class Section {
public:
    Section(const std::string& file, const toml::table& root, std::string name) : file_(file), name_(std::move(name))
    {
        if (const toml::node* n = root.get(name_)) table_ = n->as_table();
    }

    std::string path(std::string_view key) const { return name_ + "." + std::string(key); }
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

    /// A TOML integer that fits an int (floats such as 4.0 are rejected: a DOF count is a count).
    int required_integer(std::string_view key) const
    {
        const toml::node* n = get(key);
        if (!n) fail(file_, path(key), expected(path(key)), missing);
        const auto* i = n->as_integer();
        if (!i || i->get() < INT_MIN || i->get() > INT_MAX) fail(file_, path(key), expected(path(key)), describe(*n));
        return static_cast<int>(i->get());
    }

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

/// A file's text, at most cap + 1 bytes of it (the caller refuses more).
std::string read_file(const std::string& path, std::size_t cap = max_scene_bytes)
{
    // Checked before opening: open() on a FIFO waits for a writer, and a device or a directory is no scene.
    if (const std::string kind = not_a_regular_file(path); !kind.empty())
        throw SceneError::with_detail(path, "", "cannot open: it is " + kind + ", not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError::with_detail(path, "", std::string("cannot open: ") + std::strerror(errno));
    // Read by the file's own size, in chunks, and at most one byte past the cap: a scene is a few kilobytes (a
    // buffer of the cap's size zero-filled for it cost a run's start-up millions of instructions), and /dev/zero
    // never ends.
    std::string text;
    std::array<char, 1 << 14> chunk;
    while (text.size() <= cap) {
        const std::size_t want = std::min(chunk.size(), cap + 1 - text.size());
        in.read(chunk.data(), static_cast<std::streamsize>(want));
        text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
        if (static_cast<std::size_t>(in.gcount()) < want) break;  // the end of the file, or an error (below)
    }
    if (in.bad()) throw SceneError::with_detail(path, "", std::string("cannot read: ") + std::strerror(errno));
    return text;
}

toml::table parse_toml(std::string_view text, const std::string& path)
{
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        std::string description(e.description());
        std::replace(description.begin(), description.end(), '\n', ' ');
        throw SceneError::with_detail(path + ":" + std::to_string(e.source().begin.line) + ":" +
                                          std::to_string(e.source().begin.column),
                                      "", description);
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
    case SceneKey::Kind::text: t.insert_or_assign(leaf, text); break;
    }
}

/// output.sensitivities: known symbols, each once, that this scene has (a gain needs [control], tip_ratio a taper,
/// rho, S, I and E a beam without a profile), and a run the sensitivity equations can follow (dynamic axial
/// coordinates, no torque law in code).
void check_sensitivities(const Scene& s)
{
    const char* key = "output.sensitivities";
    std::vector<std::string> seen;
    for (const std::string& name : s.output.sensitivities) {
        const bool gain = std::find(gain_names.begin(), gain_names.end(), name) != gain_names.end();
        if (!gain && std::find(param_names.begin(), param_names.end(), name) == param_names.end())
            fail(s.path, key, expected(key), "\"" + name + "\"");
        if (std::find(seen.begin(), seen.end(), name) != seen.end())
            fail(s.path, key, expected(key), "\"" + name + "\" twice");
        seen.push_back(name);
        if (gain && !s.control)
            fail(s.path, key, "a control gain only with a [control] table", "\"" + name + "\"");
        if (name == "tip_ratio" && s.variant.extras.taper == Taper::uniform)
            fail(s.path, key, "tip_ratio only with beam.taper \"width\" or \"depth\"", "\"tip_ratio\"");
        // A profile's table replaces E, rho, S and I (read_profile sets them from its root for reports only): their
        // derivatives would be columns of zeros.
        if (!s.parameters.profile.empty() && (name == "E" || name == "rho" || name == "S" || name == "I"))
            fail(s.path, key, "a parameter that the scene uses, not " + name + " with beam.profile (its table gives "
                 "m, EI and ES along the span in place of rho, S, I and E)", "\"" + name + "\"");
    }
    if (!s.output.sensitivities.empty() && s.axial == Axial::quasi_static)
        fail(s.path, key, "model.axial \"dynamic\" (the sensitivity equations follow the axial coordinates' own "
             "motion)", "model.axial \"quasi-static\"");
}

/// The bound on a hub angle, as messages state it.
std::string angle_bound()
{
    return shortest(max_hub_angle) + " rad (beyond it double precision no longer resolves an angle's small changes)";
}

// Range checks of validate(), naming the key.
void check_positive(const Scene& s, double v, const char* key)
{
    if (!(v > 0.0) || !std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
}
void check_finite(const Scene& s, double v, const char* key)
{
    if (!std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
}
/// A hub angle: finite, and no larger than max_hub_angle, within which double precision resolves it.
void check_angle(const Scene& s, double v, const char* key)
{
    check_finite(s, v, key);
    if (std::abs(v) > max_hub_angle)
        fail(s.path, key, "|" + std::string(key).substr(std::string(key).find('.') + 1) + "| <= " + angle_bound(),
             shortest(v));
}

/// [control]'s ranges, and the motions it can follow: a step is a reference only, a torque drive is none.
void check_control(const Scene& s)
{
    if (!s.control) {
        if (s.motion.kind == Motion::Kind::step)
            fail(s.path, "motion.kind", "a motion of its own without a [control] section (a step is the reference of a "
                 "controlled hub)", "\"step\"");
        return;
    }
    if (s.motion.drive() == Drive::torque)
        fail(s.path, "motion.kind", "a reference for [control]: \"spin-up\", \"held\", \"table\" or \"step\"",
             "\"" + word_of(s.motion.kind, kind_words) + "\"");
    const Control& c = *s.control;
    for (const auto& [v, key] : {std::pair{c.kp, "control.kp"}, {c.kd, "control.kd"}, {c.ki, "control.ki"}})
        if (!(v >= 0.0) || !std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
    if (!(c.tau_max > 0.0)) fail(s.path, "control.tau_max", expected("control.tau_max"), shortest(c.tau_max));
    check_finite(s, c.k_tip, "control.k_tip");
}

// The parts of parse_scene, in the order it calls them: the file as a whole, then one table each. A table's
// reader takes its keys' values; ranges and the checks that join keys are validate()'s.

void check_size(std::string_view text, const std::string& path)
{
    if (text.size() > max_scene_bytes)
        throw SceneError::with_detail(path, "", "is larger than a scene file can be (" +
                                                    std::to_string(max_scene_bytes / 1024) + " KB)");
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

/// s without the blanks around it.
std::string_view trimmed(std::string_view s)
{
    const std::size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// A numeric CSV table named by a scene key (beam.profile, motion.file): its header's column count and line and,
/// for each row, the values of the wanted columns and the row's line. Read whole by read_file (FIFOs, devices and
/// folders refused; at most cap bytes) and checked before anything runs; blank lines, lines starting with '#' and a
/// spreadsheet's byte-order mark are skipped. Every problem is "SCENE: KEY: FILE[:LINE]: what", what saying what was
/// expected and where (line, column, field), never what the file holds: a scene may name any file its reader can
/// read, and the message may reach someone who cannot.
struct NumericTable {
    std::size_t header_columns = 0;
    long header_line = 0;                   // comment and blank lines may come before the header
    std::vector<std::vector<double>> rows;  // the wanted columns' values, in the order asked for
    std::vector<long> lines;
};

/// The failure of a table's check, as read_numeric_table words it.
[[noreturn]] void table_problem(const std::string& scene, const std::string& key, const std::string& where,
                                const std::string& what)
{
    throw SceneError::with_detail(scene, key, where + ": " + what);
}

/// A column a table reader needs: its name in the header and what it holds (with its unit), for messages.
struct WantedColumn {
    std::string name;
    std::string meaning;
};

/// Reads file (resolved already) as a table with the columns `wanted` (found by name in its header, among others,
/// each once); each value a finite number.
NumericTable read_numeric_table(const std::string& scene, const std::string& key, const std::string& file,
                                std::size_t cap, const char* what_it_is, const std::vector<WantedColumn>& wanted)
{
    const std::string label = printable(file, 400);
    std::string text;
    try {
        text = read_file(file, cap);
    } catch (const SceneError& e) {
        table_problem(scene, key, label, e.detail);
    }
    if (text.size() > cap)
        table_problem(scene, key, label,
                      "is larger than " + std::string(what_it_is) + " can be (" +
                          (cap >= (1u << 20) ? std::to_string(cap >> 20) + " MB)" : std::to_string(cap >> 10) + " KB)"));
    if (text.rfind("\xef\xbb\xbf", 0) == 0) text.erase(0, 3);

    std::optional<CsvColumns> columns;
    std::vector<std::size_t> at;
    NumericTable table;
    long line_no = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string_view line = trimmed(std::string_view(text.data() + pos, end - pos));
        pos = end + 1;
        ++line_no;
        if (line.empty() || line.front() == '#') continue;
        const std::string where = label + ":" + std::to_string(line_no);
        std::vector<std::string> fields = csv_fields(line);
        for (std::string& f : fields) f = std::string(trimmed(f));
        if (!columns) {  // the header: "t, theta" as well as "t,theta"
            std::string header;
            for (const std::string& f : fields) header += (header.empty() ? "" : ",") + f;
            columns.emplace(where, header);
            for (const WantedColumn& w : wanted) {
                const std::vector<std::string>& names = columns->names();
                const auto count = std::count(names.begin(), names.end(), w.name);
                if (count != 1)  // a second column of the name would be ignored without a word
                    table_problem(scene, key, where,
                                  (count == 0 ? "expected a column " : "expected one column ") + w.name +
                                      " in its header (" + w.meaning + "), got " +
                                      (count == 0 ? "none among its " + std::to_string(names.size()) + " columns"
                                                  : std::to_string(count)));
                at.push_back(columns->at(w.name));
            }
            table.header_columns = columns->size();
            table.header_line = line_no;
            continue;
        }
        if (fields.size() != columns->size())
            table_problem(scene, key, where,
                          "expected " + std::to_string(columns->size()) + " fields as the header has, got " +
                              std::to_string(fields.size()));
        std::vector<double> row;
        for (std::size_t c = 0; c < wanted.size(); ++c) {
            const std::string& f = fields[at[c]];
            double x = 0.0;
            const auto [stop, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
            if (ec != std::errc() || stop != f.data() + f.size() || !std::isfinite(x))
                table_problem(scene, key, where,
                              "expected a finite number in column " + wanted[c].name + " (" + wanted[c].meaning +
                                  "), field " + std::to_string(at[c] + 1) + " of the line");
            row.push_back(x);
        }
        table.rows.push_back(std::move(row));
        table.lines.push_back(line_no);
    }
    if (!columns) {
        std::string names;
        for (const WantedColumn& w : wanted) names += (names.empty() ? "" : ", ") + w.name;
        table_problem(scene, key, label, "expected a header line with columns " + names + ", got an empty file");
    }
    return table;
}

/// The most stations a profile table may have: the generator's cost and the variant's name grow with them.
constexpr std::size_t max_profile_stations = 64;
/// The largest profile table read: a blade table of max_profile_stations rows is a few kilobytes.
constexpr std::size_t max_profile_bytes = 1 << 16;

/// beam.profile's table (docs/model.md section 11.2): stations x/L from 0 to 1, strictly increasing, and positive
/// finite m, EI, ES at each, into the variant's stations (structure) and p.profile (run-time values). Every error
/// names the scene, the key and the table's file and line.
std::string read_profile(const std::string& scene_path, const std::string& name, Parameters& p, Extras& extras)
{
    const std::string file = (std::filesystem::path(scene_path).parent_path() / name).string();
    const std::string label = printable(file, 400);
    const auto bad = [&](long line, const std::string& what) {
        table_problem(scene_path, "beam.profile", label + (line > 0 ? ":" + std::to_string(line) : std::string()), what);
    };
    const std::vector<WantedColumn> want = {{"x/L", "the station along the span, 0 at the root to 1 at the tip"},
                                            {"m", "mass per length, kg/m"},
                                            {"EI", "bending stiffness, N m^2"},
                                            {"ES", "axial stiffness, N"}};
    const NumericTable table =
        read_numeric_table(scene_path, "beam.profile", file, max_profile_bytes, "a profile table", want);
    if (table.header_columns != want.size())
        bad(table.header_line, "expected exactly the columns x/L, m, EI, ES in its header, got " +
                                   std::to_string(table.header_columns) + " columns");
    std::vector<double> x, values;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const std::vector<double>& v = table.rows[r];
        const long line = table.lines[r];
        if (x.size() == max_profile_stations)
            bad(line, "more than " + std::to_string(max_profile_stations) + " stations");
        for (std::size_t c = 1; c < want.size(); ++c)
            if (!(v[c] > 0.0)) bad(line, "expected " + want[c].name + " > 0, got " + shortest(v[c]));
        if (x.empty() && v[0] != 0.0) bad(line, "the first station must be x/L = 0, got " + shortest(v[0]));
        if (!x.empty() && !(v[0] > x.back()))
            bad(line, "the stations must increase strictly, got x/L = " + shortest(v[0]) + " after " + shortest(x.back()));
        if (v[0] > 1.0) bad(line, "expected x/L <= 1, got " + shortest(v[0]));
        x.push_back(v[0]);
        values.insert(values.end(), {v[1], v[2], v[3]});
    }
    if (x.size() < 2) bad(0, "expected at least 2 stations, got " + std::to_string(x.size()));
    if (x.back() != 1.0) bad(0, "the last station must be x/L = 1, got " + shortest(x.back()));
    if (const std::string why = set_stations(x, extras); !why.empty()) bad(0, why);
    p.profile = std::move(values);
    // The root's values stand for rho S, E I and E S wherever a single value of the beam is reported (the
    // frequency unit sqrt(EI / (m L^4))): S = 1 m^2 keeps the three products the table's.
    p.rho = p.profile[static_cast<std::size_t>(ProfileValue::m)];
    p.S = 1.0;
    p.E = p.profile[static_cast<std::size_t>(ProfileValue::ES)];
    p.I = p.profile[static_cast<std::size_t>(ProfileValue::EI)] / p.E;
    return file;
}

/// [beam]: docs/model.md section 1, the taper of section 11 (a taper kind without a ratio is refused: the default
/// ratio 1 would make it uniform without a word) and the tabulated profile of section 11.2 (the section's keys and
/// a taper with it are refused: the table gives the beam's distributions). Returns the profile table's file, or "".
std::string read_beam(const Section& beam, const std::string& scene_path, Parameters& p, Extras& extras)
{
    beam.only();
    p.L = beam.required_number("length");
    if (const auto profile = beam.string("profile"); profile && !profile->empty()) {
        for (const char* key : {"density", "area", "second_moment", "youngs_modulus", "taper", "tip_ratio"})
            if (beam.get(key))
                throw SceneError::with_detail(scene_path, beam.path(key),
                                              "not used with beam.profile (its table gives m, EI and ES along the span): "
                                              "remove it");
        return read_profile(scene_path, *profile, p, extras);
    }
    p.rho = beam.required_number("density");
    p.S = beam.required_number("area");
    p.I = beam.required_number("second_moment");
    p.E = beam.required_number("youngs_modulus");
    Taper& taper = extras.taper;
    taper = beam.word<Taper>("taper", parse_enum<Taper>).value_or(Taper::uniform);
    if (taper != Taper::uniform) p.tip_ratio = beam.required_number("tip_ratio", ", required for a taper");
    else if (const auto r = beam.number("tip_ratio"); r && *r != 1.0)
        beam.refuse("tip_ratio", shortest(*r) + " without beam.taper = \"width\" or \"depth\"");
    return {};
}

/// [tip], [damping], [gravity]: the extra terms of docs/model.md section 11; absent tables leave them out.
void read_extras(const toml::table& root, const std::string& path, Parameters& p)
{
    // Each term's own table and keys are the registry's (terms.hpp): every table is checked before any is read.
    for (const TermInfo& t : terms())
        if (!t.scene_keys.empty()) Section(path, root, t.scene_keys.front().table).only();
    for (const TermInfo& t : terms())
        for (const TermSceneKey& k : t.scene_keys) value(p, k.param) = Section(path, root, k.table).number(k.key, value(p, k.param));
}


/// A motion table's problem: "SCENE: motion.file: WHERE: WHAT" (WHERE the CSV file, with its line if one is at fault).
[[noreturn]] void table_fail(const std::string& scene, const std::string& where, const std::string& what)
{
    table_problem(scene, "motion.file", where, what);
}

/// The table of motion.file: columns t and `column` (found by name, in any order among others), one row a line,
/// read and checked whole before anything runs. file is already resolved against the scene's folder.
std::shared_ptr<const DriveTable> read_drive_table(const std::string& scene, const std::string& file,
                                                   const char* column, const char* meaning,
                                                   DriveTable::Interpolation interpolation)
{
    const std::string label = printable(file, 400);
    const NumericTable table = read_numeric_table(scene, "motion.file", file, max_table_bytes, "a motion table",
                                                  {{"t", "time, s"}, {column, meaning}});
    std::vector<double> t, v;
    const bool angle = std::string_view(column) == "theta";
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        t.push_back(table.rows[r][0]);
        v.push_back(table.rows[r][1]);
        if (angle && std::abs(v[r]) > max_hub_angle)
            table_fail(scene, label + ":" + std::to_string(table.lines[r]), "expected |theta| <= " + angle_bound());
        if (r > 0 && !(t[r] > t[r - 1]))
            table_fail(scene, label + ":" + std::to_string(table.lines[r]),
                       "expected times that increase strictly, got t = " + shortest(t[r]) + " after t = " +
                           shortest(t[r - 1]) + " (line " + std::to_string(table.lines[r - 1]) + ")");
    }
    const std::size_t need = DriveTable::min_rows(interpolation);
    if (t.size() < need)
        table_fail(scene, label,
                   "expected at least " + std::to_string(need) + " rows" +
                       (interpolation == DriveTable::Interpolation::cubic_spline ? " (a cubic spline)" : "") + ", got " +
                       std::to_string(t.size()));
    try {
        return std::make_shared<const DriveTable>(std::move(t), std::move(v), interpolation);
    } catch (const std::invalid_argument& e) {
        table_fail(scene, label, e.what());
    }
}

/// motion.file as a path: relative to the scene file's folder (a scene and its table travel together).
std::string table_path(const std::string& scene, const std::string& file)
{
    const std::filesystem::path p(file);
    if (p.is_absolute() || scene.empty()) return file;
    return (std::filesystem::path(scene).parent_path() / p).lexically_normal().string();
}

/// [motion]: paper eq. 58 (spin-up) or eq. 59 (torque), a held hub, or a table of theta or tau against time; the
/// kind decides which keys the table may hold.
void read_motion(const Section& motion, const std::string& path, Motion& m)
{
    m.kind = motion.required_word<Motion::Kind>("kind", parse_kind);
    motion.only(word_of(m.kind, kind_words));
    switch (m.kind) {
    case Motion::Kind::spin_up:
        m.omega0 = motion.required_number("omega0");
        m.spin_time = motion.required_number("duration");
        break;
    case Motion::Kind::torque:
        m.tau0 = motion.required_number("tau0");
        m.torque_time = motion.required_number("duration");
        break;
    case Motion::Kind::held: m.angle = motion.required_number("angle"); break;
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
        m.table = read_drive_table(path, m.table_file, angle ? "theta" : "tau", angle ? "the hub angle, rad" : "the hub torque, N m",
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
    const Motion::Kind kind = scene.motion.kind;
    if (scene.control) p.J_oh = hub.required_number("inertia", ", required for a controlled hub ([control])");
    else if (kind == Motion::Kind::torque || kind == Motion::Kind::torque_table)
        p.J_oh = hub.required_number("inertia", ", required for kind = \"" + word_of(kind, kind_words) + "\"");
    else p.J_oh = hub.number("inertia", p.J_oh);
}

/// [discretization]: docs/model.md section 4; the variant's drive follows the motion.
void read_discretization(const Section& disc, const Scene& scene, VariantKey& key)
{
    disc.only();
    key.method = disc.required_word<Method>("method", parse_enum<Method>);
    key.ny = disc.required_integer("ny");
    key.nx = disc.required_integer("nx");
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
}

}  // namespace

namespace {

/// The code point of the well-formed UTF-8 sequence at text[i] and its length, or length 0 for a byte that starts
/// no well-formed sequence (a stray continuation byte, an overlong form, a surrogate, beyond U+10FFFF, cut short).
std::pair<char32_t, std::size_t> decode_utf8(std::string_view text, std::size_t i)
{
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char b0 = byte(i);
    if (b0 < 0x80) return {b0, 1};
    std::size_t n = 0;
    char32_t cp = 0, min = 0;
    if (b0 >= 0xc2 && b0 <= 0xdf) n = 2, cp = b0 & 0x1f, min = 0x80;
    else if (b0 >= 0xe0 && b0 <= 0xef) n = 3, cp = b0 & 0x0f, min = 0x800;
    else if (b0 >= 0xf0 && b0 <= 0xf4) n = 4, cp = b0 & 0x07, min = 0x10000;
    else return {0, 0};
    if (i + n > text.size()) return {0, 0};
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xc0) != 0x80) return {0, 0};
        cp = (cp << 6) | (byte(i + k) & 0x3f);
    }
    if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return {0, 0};
    return {cp, n};
}

/// Whether a code point must not reach a terminal as it is: the controls (C0, DEL, C1), the format characters
/// (bidirectional overrides and isolates, zero-width characters, the language tags), the line and paragraph
/// separators, private use and the noncharacters. These are Unicode's categories Cc, Cf, Zl, Zp and Co that the
/// Python module escapes too (hubbeam.printable); it also escapes unassigned code points, which need a table.
bool needs_escape(char32_t c)
{
    struct Range {
        char32_t first, last;
    };
    static constexpr Range ranges[] = {
        {0x0000, 0x001f},   {0x007f, 0x009f},   {0x00ad, 0x00ad},   {0x0600, 0x0605},   {0x061c, 0x061c},
        {0x06dd, 0x06dd},   {0x070f, 0x070f},   {0x0890, 0x0891},   {0x08e2, 0x08e2},   {0x180e, 0x180e},
        {0x200b, 0x200f},   {0x2028, 0x202e},   {0x2060, 0x2064},   {0x2066, 0x206f},   {0xe000, 0xf8ff},
        {0xfdd0, 0xfdef},   {0xfeff, 0xfeff},   {0xfff9, 0xfffb},   {0x110bd, 0x110bd}, {0x110cd, 0x110cd},
        {0x13430, 0x1343f}, {0x1bca0, 0x1bca3}, {0x1d173, 0x1d17a}, {0xe0001, 0xe0001}, {0xe0020, 0xe007f},
        {0xf0000, 0x10ffff},
    };
    if ((c & 0xfffe) == 0xfffe) return true;  // U+FFFE, U+FFFF and their copies in every plane
    for (const Range& r : ranges)
        if (c >= r.first && c <= r.last) return true;
    return false;
}

}  // namespace

std::string printable(std::string_view text, std::size_t cap)
{
    std::string out;
    char escape[16];
    for (std::size_t i = 0; i < text.size();) {
        if (out.size() >= cap) return out + "...";
        const auto [cp, n] = decode_utf8(text, i);
        if (n == 0) {  // not UTF-8: the byte itself
            std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(text[i])));
            out += escape;
            ++i;
            continue;
        }
        if (!needs_escape(cp)) out.append(text.substr(i, n));
        else {
            const auto u = static_cast<unsigned long>(cp);
            // The forms of Python's repr, as hubbeam.printable writes them: \x1b, \u202e, \U000e0001.
            if (u < 0x100) std::snprintf(escape, sizeof escape, "\\x%02lx", u);
            else if (u < 0x10000) std::snprintf(escape, sizeof escape, "\\u%04lx", u);
            else std::snprintf(escape, sizeof escape, "\\U%08lx", u);
            out += escape;
        }
        i += n;
    }
    return out;
}

SceneError::SceneError(std::string file_, std::string key_, std::string expected_, std::string got_,
                       std::string detail_)
    : SceneError(Clean{}, printable(file_, 400), printable(key_, 80), std::move(expected_), printable(got_, 120),
                 printable(detail_, 400))
{
}

SceneError::SceneError(Clean, std::string file_, std::string key_, std::string expected_, std::string got_,
                       std::string detail_)
    : std::runtime_error(file_label(file_) + ": " + (key_.empty() ? "" : key_ + ": ") +
                         (detail_.empty() ? "expected " + expected_ + ", got " + got_ : detail_)),
      file(std::move(file_)), key(std::move(key_)), expected(std::move(expected_)), got(std::move(got_)),
      detail(std::move(detail_))
{
}

SceneError::SceneError(std::string file_, std::string key_, std::string expected_, std::string got_)
    : SceneError(std::move(file_), std::move(key_), std::move(expected_), std::move(got_), "")
{
}

SceneError SceneError::with_detail(std::string file, std::string key, std::string detail)
{
    return SceneError(std::move(file), std::move(key), "", "", std::move(detail));
}

std::string SceneError::problem() const { return detail.empty() ? "expected " + expected + ", got " + got : detail; }

const std::vector<SceneKey>& scene_keys()
{
    static const std::vector<SceneKey> keys = make_scene_keys();
    return keys;
}

const SceneKey& scene_key(const std::string& name)
{
    for (const SceneKey& k : scene_keys())
        if (name == k.name) return k;
    throw std::logic_error("no scene key " + name);
}

std::string SceneKey::table() const
{
    const std::string n = name;
    return n.substr(0, n.find('.'));
}

std::string SceneKey::leaf() const
{
    const std::string n = name;
    return n.substr(n.find('.') + 1);
}

std::vector<std::string> scene_tables()
{
    std::vector<std::string> tables;
    for (const SceneKey& k : scene_keys())
        if (std::find(tables.begin(), tables.end(), k.table()) == tables.end()) tables.push_back(k.table());
    return tables;
}

std::vector<std::string> table_keys(const std::string& table, const std::string& motion_kind)
{
    std::vector<std::string> leaves;
    for (const SceneKey& k : scene_keys())
        if (k.table() == table && (k.motion_kinds.empty() || motion_kind.empty() ||
                                   std::find(k.motion_kinds.begin(), k.motion_kinds.end(), motion_kind) != k.motion_kinds.end()))
            leaves.push_back(k.leaf());
    return leaves;
}

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
    if (std::string profile = read_beam(Section(path, root, "beam"), path, scene.parameters, scene.variant.extras);
        !profile.empty())
        scene.tables.emplace_back("beam.profile", std::move(profile));
    read_extras(root, path, scene.parameters);
    read_motion(Section(path, root, "motion"), path, scene.motion);
    if (scene.motion.table) scene.tables.emplace_back("motion.file", scene.motion.table_file);
    read_control(Section(path, root, "control"), scene.control);
    read_hub(Section(path, root, "hub"), scene, scene.parameters);
    read_discretization(Section(path, root, "discretization"), scene, scene.variant);
    read_model(Section(path, root, "model"), scene);
    read_solver(Section(path, root, "solver"), scene.solver);
    read_output(Section(path, root, "output"), scene.output);
    validate(scene);
    return scene;
}

void validate(const Scene& s)
{
    const Parameters& p = s.parameters;
    check_positive(s, p.L, "beam.length");
    check_positive(s, p.rho, "beam.density");
    check_positive(s, p.S, "beam.area");
    check_positive(s, p.I, "beam.second_moment");
    check_positive(s, p.E, "beam.youngs_modulus");
    if (!(p.a >= 0.0) || !std::isfinite(p.a)) fail(s.path, "hub.radius", expected("hub.radius"), shortest(p.a));
    check_positive(s, p.J_oh, "hub.inertia");
    if (s.variant.extras.taper != Taper::uniform) check_positive(s, p.tip_ratio, "beam.tip_ratio");
    for (const auto& [v, key] : {std::pair{p.m_tip, "tip.mass"}, {p.J_tip, "tip.inertia"},
                                 {p.alpha, "damping.mass_proportional"}, {p.beta, "damping.stiffness_proportional"}})
        if (!(v >= 0.0) || !std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
    check_finite(s, p.g, "gravity.g");

    switch (s.motion.kind) {
    case Motion::Kind::spin_up:
        check_finite(s, s.motion.omega0, "motion.omega0");
        check_positive(s, s.motion.spin_time, "motion.duration");
        break;
    case Motion::Kind::torque:
        check_finite(s, s.motion.tau0, "motion.tau0");
        check_positive(s, s.motion.torque_time, "motion.duration");
        break;
    case Motion::Kind::held:
    case Motion::Kind::step: check_angle(s, s.motion.angle, "motion.angle"); break;
    case Motion::Kind::table:
    case Motion::Kind::torque_table:
        if (!s.motion.table) fail(s.path, "motion.file", expected("motion.file"), missing);
        break;
    }
    if (s.motion.kind != Motion::Kind::held) check_angle(s, s.motion.theta0, "motion.theta0");
    check_control(s);

    // DOF counts: a problem that persists with nx = 0 is about ny.
    const VariantKey& key = s.variant;
    if (key.ny < 1) fail(s.path, "discretization.ny", expected("discretization.ny"), std::to_string(key.ny));
    if (key.nx < 0) fail(s.path, "discretization.nx", expected("discretization.nx"), std::to_string(key.nx));
    if (const std::string problem = key.dof_problem(); !problem.empty()) {
        VariantKey without_axial = key;
        without_axial.nx = 0;
        const char* name = without_axial.dof_problem().empty() ? "discretization.nx" : "discretization.ny";
        throw SceneError::with_detail(s.path, name, problem);
    }

    if (s.axial == Axial::quasi_static && key.nx == 0)
        fail(s.path, "model.axial", "\"dynamic\" for a scene without axial coordinates (quasi-static needs nx > 0)",
             "\"quasi-static\"");

    if (s.solver.stepper != automatic_stepper_word && !is_stepper(s.solver.stepper))
        fail(s.path, "solver.stepper", expected("solver.stepper"), "\"" + s.solver.stepper + "\"");
    check_positive(s, s.solver.rtol, "solver.rtol");
    if (!(s.solver.rtol < 1.0))  // a relative error of 100 % or more controls nothing
        fail(s.path, "solver.rtol", "a number in (0, 1) (relative tolerance)", shortest(s.solver.rtol));
    check_positive(s, s.solver.atol, "solver.atol");
    check_positive(s, s.solver.h0, "solver.h0");

    check_sensitivities(s);
    check_positive(s, s.output.t_end, "output.t_end");
    if (!(s.output.dt_out > 0.0) || !(s.output.dt_out <= s.output.t_end))
        fail(s.path, "output.dt_out", expected("output.dt_out"),
             shortest(s.output.dt_out) + " with t_end = " + shortest(s.output.t_end));
    // A bound on the rows, checked before anything runs: beyond it the CSV would be gigabytes and the row
    // clock's integer arithmetic would overflow.
    if (s.output.t_end / s.output.dt_out > static_cast<double>(max_output_rows))
        fail(s.path, "output.dt_out",
             "at most " + std::to_string(max_output_rows) + " rows (output.t_end / output.dt_out)",
             shortest(s.output.t_end / s.output.dt_out) + " rows (t_end = " + shortest(s.output.t_end) +
                 ", dt_out = " + shortest(s.output.dt_out) + ")");

    // A table is not extrapolated: a run past its rows would make up a drive no one wrote down.
    const bool tabled = s.motion.kind == Motion::Kind::table || s.motion.kind == Motion::Kind::torque_table;
    if (const DriveTable* t = s.motion.table.get();
        tabled && (t->first_time() > 0.0 || t->last_time() < s.output.t_end))
        table_fail(s.path, printable(s.motion.table_file, 400),
                   "its rows cover t = " + shortest(t->first_time()) + " to " + shortest(t->last_time()) +
                       " s, the run needs t = 0 to output.t_end = " + shortest(s.output.t_end) +
                       " s (a table is not extrapolated: extend it or shorten the run)");
}

std::string option_name(const SceneKey& k)
{
    if (k.option == nullptr) return k.name;  // overridden from code (the Python module), not an option
    const std::string names = k.option;
    return names.substr(0, names.find(','));
}

std::string message_for(const SceneError& e, const Overrides& overrides)
{
    for (const auto& [name, value] : overrides)
        if (name == e.key) return option_name(scene_key(name)) + ": " + e.problem();
    return e.what();
}

}  // namespace hubbeam
