// Reading a scene: a Scene (config.hpp: everything one simulation needs) read and validated from a TOML file
// (format in docs/scene.md), with command-line overrides applied to the file's keys before anything is checked.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <hubbeam/config.hpp>

namespace hubbeam {

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

/// The largest scene file read (bytes).
inline constexpr std::size_t max_scene_bytes = 1 << 20;
/// The largest motion table read (bytes): about half a million rows, a test rig's kilohertz record of minutes.
inline constexpr std::size_t max_table_bytes = 16 << 20;
/// The largest angle a section may be turned by, beam.pitch or a table's twist, either way: one turn (rad). An angle
/// beyond it names the same section as one within it, and a huge one (1e308) only loses every digit of its cosine.
inline constexpr double max_section_angle = 6.283185307179586;

/// A scene key: its dotted name, what it must hold, and the command-line option that sets it (or null).
/// One table of these serves reading, validation (the keys a table may hold), messages, the command line and
/// its --help, and says which files a scene reads (the keys of Kind::file: scene_files, output_file.hpp's
/// scene_inputs, the Python module and its sweeps).
struct SceneKey {
    const char* name;    // "discretization.ny"
    const char* option;  // "--ny", or nullptr; CLI11's form ("-o,--output"): messages use the first name
    /// file: the name of a file the scene reads (relative to the scene's folder), which every writer must leave
    /// alone and a sweep's resuming keys by content; text: any other string (a word list, an output's name).
    /// numbers: a TOML array of numbers (an override: numbers separated by commas).
    enum class Kind { number, integer, word, text, file, numbers } kind;
    std::string expected;  // "an integer >= 1 (Ny)", or for words "one of \"amm\", \"fem\", ..."
    std::vector<std::string> motion_kinds = {};  // the [motion] kinds that take the key ("spin-up", ...); empty: all
    std::size_t max_bytes = 0;                   // Kind::file: the most bytes the reader reads of the file

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

/// The keys of the table that name a file the scene reads (Kind::file), in the table's order.
std::vector<const SceneKey*> file_keys();

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
/// The files a scene's text names with the overrides set, as {file key, path} in the key table's order: every
/// Kind::file key that holds a non-empty string, resolved against the scene's folder as the reader opens it. Nothing
/// else is read or checked (a scene refused for another key still names its files): what a sweep keys its points by.
/// Throws SceneError for text that is no TOML or an override of the wrong kind.
std::vector<std::pair<std::string, std::string>> scene_files(std::string_view text, const std::string& path,
                                                             const Overrides& overrides = {});
/// Re-checks a scene changed in code (ranges, DOF counts, tolerances, times); throws SceneError naming the key.
void validate(const Scene& scene);

}  // namespace hubbeam
