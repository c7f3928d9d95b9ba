// Comma-separated option values ("4,8,16", "amm,fem"), checked item by item, for the benchmark commands:
// every bad item is reported as "--option: expected ..., got ITEM".
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hubbeam {

/// A bad option value of a command ("--ny: expected ..., got ..."): the message is the whole line to print.
struct OptionError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// The items of a comma-separated list (empty items kept, so that "4,,8" is reported).
inline std::vector<std::string> split_list(std::string_view text)
{
    std::vector<std::string> items;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        items.emplace_back(text.substr(start, comma == std::string_view::npos ? comma : comma - start));
        if (comma == std::string_view::npos) return items;
        start = comma + 1;
    }
}

/// Throws Error("OPTION: expected EXPECTED, got GOT").
template <class Error>
[[noreturn]] void bad_option(const std::string& option, const std::string& expected, const std::string& got)
{
    throw Error(option + ": expected " + expected + ", got " + (got.empty() ? "an empty item" : got));
}

/// A whole item as an integer in [lo, hi], or false.
inline bool parse_int(const std::string& s, int lo, int hi, int& v)
{
    if (s.empty()) return false;
    std::size_t used = 0;
    try {
        v = std::stoi(s, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == s.size() && v >= lo && v <= hi;
}

/// A whole item as a finite number > 0, or false.
inline bool parse_positive(const std::string& s, double& v)
{
    if (s.empty()) return false;
    std::size_t used = 0;
    try {
        v = std::stod(s, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == s.size() && v > 0.0 && v < 1e300;
}

template <class T>
void add_unique(std::vector<T>& v, const T& x)
{
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}

}  // namespace hubbeam
