// The effective scene: every key a loaded Scene runs with, defaults filled, as TOML that reads back to the same Scene
// (hubbeam run --print-scene) and as the values the metadata beside an output records.
#pragma once

#include <hubbeam/config.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace hubbeam {

/// One key of an effective scene: its dotted name (the key table's) and its value.
struct SceneValue {
    enum class Kind { number, integer, text, numbers } kind;
    std::string key;
    double number = 0.0;    // Kind::number
    long long integer = 0;  // Kind::integer
    std::string text;       // Kind::text: a word or a file name
    std::vector<double> numbers = {};  // Kind::numbers
};

/// Every key of scene_keys() that applies to the scene, in the key table's order, with the value the scene runs
/// with: a default where the file left the key out, the motion's keys for its kind only, [control] only with a
/// controller, [beam]'s section keys only without a profile (its table gives them), [blade_scale] only with a blade
/// file (it scales its columns). A table's file is its absolute path, so that the printed scene reads the same table
/// from any folder. A scene driven by a torque law given as code (Python) has no [control] to print: the law is no key.
std::vector<SceneValue> effective_scene(const Scene& scene);

/// effective_scene as a scene file: one [table] per table, one `key = value` line per key, numbers in their
/// shortest round-trip form. Loading it gives a Scene whose effective_scene_toml is the same text.
std::string effective_scene_toml(const Scene& scene);

/// The language a quoted string is for: they spell a character beyond U+FFFF differently (TOML \UXXXXXXXX, JSON
/// a surrogate pair of \uXXXX).
enum class Quoting { toml, json };
/// s as a quoted basic string that TOML (or JSON) reads back as s: quote and backslash escaped, and every character
/// printable escapes (controls, bidirectional overrides, ...) written as an escape, so that printing the string
/// never drives a terminal. A byte that is not UTF-8 (a file name's, from the command line) is written as the code
/// point of its value, which reads back as that character, not the byte.
std::string quoted_string(std::string_view s, Quoting quoting = Quoting::toml);

/// A number as TOML writes it: the shortest round-trip form, inf and nan as TOML's words.
std::string toml_number(double v);

}  // namespace hubbeam
