// CSV tables by column name: a header built from one list of column names, and the lookup by which a reader
// finds the columns it needs in a file's header (so that no reader depends on a column's position).
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/option_lists.hpp>

namespace hubbeam {

/// A CSV file that is not what its reader needs ("FILE: expected a column NAME ..."): the whole line to print.
struct CsvColumnError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// The header line of a table from its column names, in order.
inline std::string csv_header(std::initializer_list<std::string_view> names)
{
    std::string header;
    for (const std::string_view name : names) header += (header.empty() ? "" : ",") + std::string(name);
    return header;
}

/// The fields of one CSV line (no quoting: the tables hubbeam reads back have none in their numbers and names).
inline std::vector<std::string> csv_fields(std::string_view line) { return split_list(line); }

/// The columns of a file's header, looked up by name.
class CsvColumns {
public:
    /// file is the name used in messages; header is the file's first line.
    CsvColumns(std::string file, std::string_view header) : file_(std::move(file)), names_(csv_fields(header)) {}

    /// The position of column name; throws CsvColumnError "FILE: expected a column NAME in its header (what), got
    /// none among its N columns" when the header has none. The header itself is not quoted: a message quotes no
    /// file's content (the file may be one the user was not meant to read, named by mistake or by someone else).
    std::size_t at(std::string_view name, std::string_view what = {}) const
    {
        for (std::size_t i = 0; i < names_.size(); ++i)
            if (names_[i] == name) return i;
        throw CsvColumnError(file_ + ": expected a column " + std::string(name) + " in its header" +
                             (what.empty() ? std::string() : " (" + std::string(what) + ")") + ", got none among its " +
                             std::to_string(names_.size()) + " columns");
    }
    /// Whether the header has column name.
    bool has(std::string_view name) const
    {
        for (const std::string& n : names_)
            if (n == name) return true;
        return false;
    }
    std::size_t size() const { return names_.size(); }
    const std::vector<std::string>& names() const { return names_; }

private:
    std::string file_;
    std::vector<std::string> names_;
};

}  // namespace hubbeam
