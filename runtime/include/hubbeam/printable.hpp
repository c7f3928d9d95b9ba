// printable: user text made safe to echo on a terminal, for every message that quotes a value, a file name or an
// option given by the user; and the one check of text handed to another program (a gnuplot script's strings, an
// output's name), which refuses what printable would have to escape.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace hubbeam {

/// User text as it may be echoed on a terminal, in the forms of the Python module's hubbeam.printable: controls
/// (C0, DEL, C1) as \xNN, format characters such as the bidirectional overrides and line separators as \uNNNN
/// (or \UNNNNNNNN), bytes that are not UTF-8 as \xNN; cut after about `cap` bytes, between characters. Every
/// message that quotes a value, a file name or an option given by the user passes it through here.
std::string printable(std::string_view text, std::size_t cap = 120);

/// The character at text[i] for a writer with escapes of its own (a TOML string's): its code point and length in
/// bytes, and whether printable escapes it. A byte that starts no well-formed UTF-8 sequence is a character of
/// length 1 whose code point is the byte's value, escaped.
struct TextChar {
    char32_t code;
    std::size_t length;
    bool escaped;
};
TextChar text_char(std::string_view text, std::size_t i);

/// Why text may not be handed to another program as it is (a string in a gnuplot script, a file name it opens, an
/// output's name), or empty when it may: its first character that printable() would escape, as "a control character
/// (\x0a) at byte 3". Such a character could end a script's line and start another (gnuplot runs a line that begins
/// with '!' in the shell), or show a reader of a name or a script something other than what is there. The answer
/// quotes no other byte of text, so that a message may give it for text read from a file.
std::string unsafe_character(std::string_view text);

/// The one check of text handed to another program and of an output's name: throws Error("NAME: expected WHAT
/// without control or format characters, got ...") naming unsafe_character(text) when it finds one.
template <class Error>
void check_handed_text(const std::string& name, std::string_view text, const std::string& what)
{
    if (const std::string why = unsafe_character(text); !why.empty())
        throw Error(name + ": expected " + what + " without control or format characters, got " + why);
}

}  // namespace hubbeam
