// Numbers as text in the shortest form that reads back as the same double: 0.03, not 0.029999999999999999.
#pragma once

#include <string>

namespace hubbeam {

/// The most characters write_shortest writes: -1.7976931348623157e+308.
constexpr int max_shortest_chars = 24;
/// The bytes at out write_shortest may touch: past the text's end it may leave scratch (fixed-size stores are
/// cheaper than counted ones).
constexpr int shortest_room = 40;

/// Writes v at out in its shortest round-trip form, the text std::to_chars(out, end, v) writes, and returns the
/// end; out must have room for shortest_room bytes. A fraction of libstdc++'s instructions (shortest.cpp).
char* write_shortest(char* out, double v) noexcept;

/// Appends v to s in its shortest round-trip form.
inline void append_shortest(std::string& s, double v)
{
    char buf[shortest_room];
    s.append(buf, write_shortest(buf, v));
}

/// v in its shortest round-trip form.
inline std::string shortest(double v)
{
    std::string s;
    append_shortest(s, v);
    return s;
}

}  // namespace hubbeam
