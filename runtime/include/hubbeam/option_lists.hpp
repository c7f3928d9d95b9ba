// Comma-separated option values ("4,8,16", "amm,fem", "0.0,0.5"), checked item by item, for every command that
// takes lists: every bad item is reported as "--option: expected ..., got ITEM".
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "variant.hpp"

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

/// A whole item as an integer in [lo, hi] (an optional sign, then digits only), or false.
inline bool parse_int(std::string_view s, int lo, int hi, int& v)
{
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return !s.empty() && ec == std::errc() && end == s.data() + s.size() && v >= lo && v <= hi;
}

/// A whole item as a finite decimal number (an optional sign, digits with an optional point and exponent:
/// "0", "0.0", "0e0", "+2.5", "1e-3"), or false. The one reader of numbers in option lists, so that "0.0" from
/// seq or numpy means what "0" means; -0 reads as 0 (so that it prints as 0).
inline bool parse_number(std::string_view s, double& v)
{
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    if (s.empty()) return false;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::general);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return false;
    v += 0.0;  // -0 + 0 = +0
    return true;
}

/// A whole item as a finite number > 0, or false.
inline bool parse_positive(std::string_view s, double& v) { return parse_number(s, v) && v > 0.0 && v < 1e300; }

/// A whole item as a finite number >= 0 (a time, a spin rate), or false.
inline bool parse_non_negative(std::string_view s, double& v) { return parse_number(s, v) && v >= 0.0 && v < 1e300; }

template <class T>
void add_unique(std::vector<T>& v, const T& x)
{
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}

/// The largest DOF count (Nx or Ny) that any method takes: max_dof() of variant.hpp, where the variants are
/// capped. A list item above it can never be a variant, so lists refuse it as they are read; per method the
/// limit is VariantKey::dof_problem()'s, checked where the grid of variants is formed.
inline int largest_dof_count()
{
    int most = 0;
    for (const std::string& word : words<Method>()) {
        Method m{};
        if (parse(word, m)) most = std::max(most, max_dof(m));
    }
    return most;
}

/// The methods of a --methods list ("amm,fem"), each once, in the order given; throws Error naming option.
template <class Error>
std::vector<Method> parse_method_list(const std::string& option, const std::string& text)
{
    std::vector<Method> methods;
    for (const std::string& s : split_list(text)) {
        Method v{};
        if (!parse(s, v)) bad_option<Error>(option, "a comma-separated list of " + joined(words<Method>()), s);
        add_unique(methods, v);
    }
    return methods;
}

/// The DOF counts of a --ny or --nx list, integers from lo to largest_dof_count(), each once; throws Error naming
/// option. extra names another word the caller accepts (e.g. "ny"), for the message only.
template <class Error>
std::vector<int> parse_dof_list(const std::string& option, const std::string& text, int lo, const std::string& extra = "")
{
    const int hi = largest_dof_count();
    std::vector<int> counts;
    for (const std::string& s : split_list(text)) {
        int v = 0;
        if (!parse_int(s, lo, hi, v))
            bad_option<Error>(option,
                              "a comma-separated list of integers from " + std::to_string(lo) + " to " +
                                  std::to_string(hi) + (extra.empty() ? "" : " or " + extra),
                              s);
        add_unique(counts, v);
    }
    return counts;
}

/// The excitation lines a Campbell table and diagram take when --harmonics is not given: 1P, 2P and 3P.
inline constexpr const char* default_harmonics = "1,2,3";

/// The harmonics n of a --harmonics list (a Campbell diagram's excitation lines omega = n Omega), integers from 1
/// to 1000, each once, or none at all for the word none (no critical speed searched, no line drawn); throws Error
/// naming option.
template <class Error>
std::vector<int> parse_harmonics(const std::string& option, const std::string& text)
{
    std::vector<int> harmonics;
    if (text == "none") return harmonics;
    for (const std::string& s : split_list(text)) {
        int n = 0;
        if (!parse_int(s, 1, 1000, n))
            bad_option<Error>(option, "a comma-separated list of integers from 1 to 1000, or none", s);
        add_unique(harmonics, n);
    }
    return harmonics;
}

}  // namespace hubbeam
