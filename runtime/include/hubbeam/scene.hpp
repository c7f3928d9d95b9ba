// Scene: everything one simulation needs, read and validated from a TOML file (format in docs/scene.md), with
// command-line overrides applied to the file's keys before anything is checked.
#pragma once

#include <array>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "integrate.hpp"
#include "make_model.hpp"
#include "motion.hpp"
#include "variant.hpp"
#include "terms.hpp"

namespace hubbeam {

/// Whether a run checks its own error by re-running windows at a tighter tolerance (RunSummary::estimated_error):
/// on by default; off saves its cost (about 13 % of the main job) where the tolerance is known to be adequate.
enum class ErrorCheck { on, off };
std::string to_string(ErrorCheck);
bool parse(std::string_view, ErrorCheck&);
template <> std::vector<std::string> words<ErrorCheck>();

struct SolverOptions {
    std::string stepper = automatic_stepper_word;  // a name from stepper_names() (integrate.hpp), or automatic
    double rtol = 1e-8;
    double atol = 1e-10;
    double h0 = 1e-4;  // first trial step (s)
    Stepping stepping = Stepping::free;
    long max_steps = 10'000'000;  // a run that needs more steps stops with the reason its steps are short
    ErrorCheck error_check = ErrorCheck::on;
};

/// The most rows a run may write (t_end / dt_out): 10^8 rows is about 20 GB of CSV.
inline constexpr long max_output_rows = 100'000'000;

/// The control gains a sensitivity can be taken by (beside the physical parameters, Param): [control]'s keys.
inline constexpr std::array<const char*, 4> gain_names = {"kp", "kd", "ki", "k_tip"};

struct OutputOptions {
    double t_end = 30.0;   // s
    double dt_out = 0.01;  // s; rows fall on exact multiples of dt_out
    std::string file;      // CSV path; empty: derived from the scene name by the command line (a file or an
                           // override cannot set it empty, nor put a NUL in it)
    /// Parameters whose derivatives the run integrates and writes (docs/sensitivities.md): symbols of Param
    /// (interface.hpp) and the control gains kp, kd, ki, k_tip; empty: none.
    std::vector<std::string> sensitivities;
};

struct Scene {
    std::string path;  // the file it came from, for messages
    /// The other files it was read from, each with its key: {"beam.profile", FILE}, {"motion.file", FILE}. A
    /// command's outputs are checked against these and path (output_file.hpp's scene_inputs).
    std::vector<std::pair<std::string, std::string>> tables;
    Parameters parameters;
    Motion motion;
    std::optional<Control> control;  // [control]: motion is then the reference of a torque-driven hub
    VariantKey variant;  // drive follows motion, or control
    ModelSource source = ModelSource::automatic;
    Axial axial = Axial::dynamic;  // quasi-static: A follows the axial equilibrium (integrate.hpp)
    SolverOptions solver;
    OutputOptions output;

    /// The control, or nullptr: what the integrator and the linearization take.
    const Control* controller() const { return control ? &*control : nullptr; }
    /// The hub's drive: torque under a control (its motion is a reference), else the one the motion implies.
    Drive drive() const { return control ? Drive::torque : motion.drive(); }
    /// The variant this scene runs: its discretization with the drive its motion and control imply and the extra
    /// terms its parameters use (either may have been changed in code since loading). A term whose values are all
    /// zero is left out: the paper's scenes run the paper's variants.
    /// Whether output.sensitivities asks for any of names: a term (or the controller's integral) it asks for is
    /// kept even where its value is zero.
    bool wants(std::initializer_list<const char*> names) const
    {
        for (const std::string& s : output.sensitivities)
            for (const char* n : names)
                if (s == n) return true;
        return false;
    }
    VariantKey key() const
    {
        VariantKey k = variant;
        k.drive = drive();
        // A sensitivity to a term's value needs the term, even at zero (where it reproduces the scene).
        const std::vector<double> p = parameters.packed();
        for (const TermInfo& t : terms()) {
            if (!t.selected_by_values) continue;
            bool used = false;
            for (Param q : t.params) used = used || p[index(q)] != 0.0 || wants({param_names[index(q)]});
            t.set(k.extras, used);
        }
        return k;
    }
};

/// Bad scene input, as data: the file, the key ("discretization.ny"; empty when the file itself is the
/// problem) and what was wrong, either as expected/got or as a sentence (detail).
struct SceneError : std::runtime_error {
    std::string file, key, expected, got, detail;

    SceneError(std::string file, std::string key, std::string expected, std::string got);
    /// A problem stated as a sentence ("FEM needs an even ny ..."); key may be empty.
    static SceneError with_detail(std::string file, std::string key, std::string detail);
    /// "expected E, got G", or the detail.
    std::string problem() const;

private:
    SceneError(std::string file, std::string key, std::string expected, std::string got, std::string detail);
    struct Clean {};  // the fields are printable already
    SceneError(Clean, std::string file, std::string key, std::string expected, std::string got, std::string detail);
};

/// User text as it may be echoed on a terminal, in the forms of the Python module's hubbeam.printable: controls
/// (C0, DEL, C1) as \xNN, format characters such as the bidirectional overrides and line separators as \uNNNN
/// (or \UNNNNNNNN), bytes that are not UTF-8 as \xNN; cut after about `cap` bytes, between characters. Every
/// message that quotes a value, a file name or an option given by the user passes it through here.
std::string printable(std::string_view text, std::size_t cap = 120);

/// The largest scene file read (bytes).
inline constexpr std::size_t max_scene_bytes = 1 << 20;
/// The largest motion table read (bytes): about half a million rows, a test rig's kilohertz record of minutes.
inline constexpr std::size_t max_table_bytes = 16 << 20;

/// A scene key: its dotted name, what it must hold, and the command-line option that sets it (or null).
/// One table of these serves reading, validation (the keys a table may hold), messages, the command line and
/// its --help.
struct SceneKey {
    const char* name;    // "discretization.ny"
    const char* option;  // "--ny", or nullptr; CLI11's form ("-o,--output"): messages use the first name
    enum class Kind { number, integer, word, text } kind;
    std::string expected;  // "an integer >= 1 (Ny)", or for words "one of \"amm\", \"fem\", ..."
    std::vector<std::string> motion_kinds = {};  // the [motion] kinds that take the key ("spin-up", ...); empty: all

    /// "discretization" of "discretization.ny".
    std::string table() const;
    /// "ny" of "discretization.ny".
    std::string leaf() const;
};
const std::vector<SceneKey>& scene_keys();
/// The entry of a dotted key name; throws std::logic_error for a name not in the table.
const SceneKey& scene_key(const std::string& name);
/// The tables of a scene file ("beam", "hub", ...), in the key table's order.
std::vector<std::string> scene_tables();
/// The keys table may hold (leaf names, in the key table's order); for [motion], those motion_kind takes.
std::vector<std::string> table_keys(const std::string& table, const std::string& motion_kind = "");

/// Key name -> value as typed on the command line, e.g. {"discretization.ny", "8"}.
using Overrides = std::vector<std::pair<std::string, std::string>>;

/// The key's option name in messages: the first of CLI11's names ("-o" of "-o,--output"), or the key's own name
/// for a key without an option.
std::string option_name(const SceneKey& k);
/// A scene problem as the user should read it: against the option when an option set the key
/// ("--ny: FEM needs an even ny ..."), else against the file and key.
std::string message_for(const SceneError& e, const Overrides& overrides);

/// Reads a scene file, sets the overridden keys, then validates it; throws SceneError before any computation.
Scene load_scene(const std::string& path, const Overrides& overrides = {});
/// load_scene of a scene's text; path names it in messages.
Scene parse_scene(std::string_view text, const std::string& path, const Overrides& overrides = {});
/// Re-checks a scene changed in code (ranges, DOF counts, tolerances, times); throws SceneError naming the key.
void validate(const Scene& scene);

}  // namespace hubbeam
