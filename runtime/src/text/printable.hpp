// printable: user text made safe to echo on a terminal, for every message that quotes a value, a file name or an
// option given by the user.
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

}  // namespace hubbeam
