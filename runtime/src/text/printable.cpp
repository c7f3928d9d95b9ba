// printable (printable.hpp): user text escaped, as the Python module's hubbeam.printable does, so that a
// message quoting it cannot drive the terminal; and unsafe_character, which finds what printable would escape.
#include <hubbeam/printable.hpp>

#include <cstdio>
#include <utility>

namespace hubbeam {

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
    if (b0 >= 0xc2 && b0 <= 0xdf)
        n = 2, cp = b0 & 0x1f, min = 0x80;
    else if (b0 >= 0xe0 && b0 <= 0xef)
        n = 3, cp = b0 & 0x0f, min = 0x800;
    else if (b0 >= 0xf0 && b0 <= 0xf4)
        n = 4, cp = b0 & 0x07, min = 0x10000;
    else
        return {0, 0};
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
        {0x0000, 0x001f},    {0x007f, 0x009f},   {0x00ad, 0x00ad},   {0x0600, 0x0605},   {0x061c, 0x061c},
        {0x06dd, 0x06dd},    {0x070f, 0x070f},   {0x0890, 0x0891},   {0x08e2, 0x08e2},   {0x180e, 0x180e},
        {0x200b, 0x200f},    {0x2028, 0x202e},   {0x2060, 0x2064},   {0x2066, 0x206f},   {0xe000, 0xf8ff},
        {0xfdd0, 0xfdef},    {0xfeff, 0xfeff},   {0xfff9, 0xfffb},   {0x110bd, 0x110bd}, {0x110cd, 0x110cd},
        {0x13430, 0x1343f},  {0x1bca0, 0x1bca3}, {0x1d173, 0x1d17a}, {0xe0001, 0xe0001}, {0xe0020, 0xe007f},
        {0xf0000, 0x10ffff},
    };
    if ((c & 0xfffe) == 0xfffe) return true;  // U+FFFE, U+FFFF and their copies in every plane
    for (const Range& r : ranges)
        if (c >= r.first && c <= r.last) return true;
    return false;
}

/// A code point as Python's repr writes it, as hubbeam.printable does: \x1b, \u202e, \U000e0001.
std::string escaped(char32_t cp)
{
    char escape[16];
    const auto u = static_cast<unsigned long>(cp);
    if (u < 0x100) std::snprintf(escape, sizeof escape, "\\x%02lx", u);
    else if (u < 0x10000) std::snprintf(escape, sizeof escape, "\\u%04lx", u);
    else std::snprintf(escape, sizeof escape, "\\U%08lx", u);
    return escape;
}

}  // namespace

TextChar text_char(std::string_view text, std::size_t i)
{
    const auto [cp, n] = decode_utf8(text, i);
    if (n == 0) return {static_cast<unsigned char>(text[i]), 1, true};
    return {cp, n, needs_escape(cp)};
}

std::string printable(std::string_view text, std::size_t cap)
{
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        if (out.size() >= cap) return out + "...";
        const auto [cp, n] = decode_utf8(text, i);
        if (n == 0) {  // not UTF-8: the byte itself
            out += escaped(static_cast<unsigned char>(text[i]));
            ++i;
            continue;
        }
        if (!needs_escape(cp)) out.append(text.substr(i, n));
        else out += escaped(cp);
        i += n;
    }
    return out;
}

std::string unsafe_character(std::string_view text)
{
    for (std::size_t i = 0; i < text.size();) {
        const auto [cp, n] = decode_utf8(text, i);
        const std::string at = " at byte " + std::to_string(i + 1);
        if (n == 0) return "a byte that is not UTF-8 (" + escaped(static_cast<unsigned char>(text[i])) + ")" + at;
        if (needs_escape(cp))
            return std::string(cp < 0x20 || (cp >= 0x7f && cp <= 0x9f) ? "a control character ("
                                                                       : "an invisible or format character (") +
                   escaped(cp) + ")" + at;
        i += n;
    }
    return {};
}

}  // namespace hubbeam
