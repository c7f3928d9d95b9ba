// Word tables: an enum's words in scene files and on the command line, one table per enum serving
// parsing, printing and the lists of allowed words in messages and --help.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hubbeam {

template <class E, std::size_t N>
using WordTable = std::pair<E, const char*>[N];

/// Sets out to the value of word; false if the table has no such word.
template <class E, std::size_t N>
bool parse_word(std::string_view word, const WordTable<E, N>& table, E& out)
{
    for (const auto& [value, text] : table)
        if (word == text) {
            out = value;
            return true;
        }
    return false;
}

/// The word of value ("?" if the table lacks it).
template <class E, std::size_t N>
std::string word_of(E value, const WordTable<E, N>& table)
{
    for (const auto& [v, text] : table)
        if (v == value) return text;
    return "?";
}

/// Every word of the table, in table order.
template <class E, std::size_t N>
std::vector<std::string> all_words(const WordTable<E, N>& table)
{
    std::vector<std::string> words;
    for (const auto& entry : table) words.emplace_back(entry.second);
    return words;
}

/// "a, b, c" (each word between quote marks, if given; another separator, e.g. " " for a command's words).
inline std::string joined(const std::vector<std::string>& words, const char* quote = "", const char* separator = ", ")
{
    std::string s;
    for (std::size_t i = 0; i < words.size(); ++i) s += (i ? separator : "") + std::string(quote) + words[i] + quote;
    return s;
}

}  // namespace hubbeam
