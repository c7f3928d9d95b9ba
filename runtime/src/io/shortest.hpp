// Numbers as text in the shortest form that reads back as the same double: 0.03, not 0.029999999999999999.
#pragma once

#include <charconv>
#include <string>

namespace hubbeam {

/// Appends v to s in its shortest round-trip form.
inline void append_shortest(std::string& s, double v)
{
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    s.append(buf, res.ptr);
}

/// v in its shortest round-trip form.
inline std::string shortest(double v)
{
    std::string s;
    append_shortest(s, v);
    return s;
}

}  // namespace hubbeam
