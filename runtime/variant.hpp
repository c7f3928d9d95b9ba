// VariantKey: what a model is specialised on (method, DOF counts, order, drive, spline basis), its
// canonical name (which names generated kernels) and the DOF counts each method can take.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "basis/basis.hpp"

namespace hubbeam {

/// Model order of MODEL.md section 3.
enum class Order { zero, first, full };
/// Prescribed hub rotation theta(t) (no hub equation) or applied hub torque tau(t) (theta is a coordinate).
enum class Drive { prescribed, torque };

struct VariantKey {
    Method method = Method::amm;
    int nx = 0, ny = 4;
    Order order = Order::first;
    Drive drive = Drive::prescribed;
    SplineBasis spline = SplineBasis::paper;  // BSIM transverse basis; ignored by other methods

    /// Number of generalized coordinates: theta (torque only), A (nx), B (ny).
    int nq() const { return (drive == Drive::torque ? 1 : 0) + nx + ny; }
    /// Index of A_1 and B_1 in q.
    int first_a() const { return drive == Drive::torque ? 1 : 0; }
    int first_b() const { return first_a() + nx; }

    /// e.g. "bim_nx4_ny4_torque_first", "bsim_nx0_ny4_prescribed_first_open": a C identifier.
    std::string name() const;
    /// Inverse of name(); throws std::invalid_argument.
    static VariantKey parse(std::string_view name);

    /// Empty if the method can take these DOF counts, else why not (e.g. "FEM needs an even ny").
    std::string dof_problem() const;

    FieldBasis axial_basis() const { return {method, Field::axial, nx, SplineBasis::open}; }
    FieldBasis transverse_basis() const { return {method, Field::transverse, ny, spline}; }

    bool operator==(const VariantKey&) const = default;
};

/// An enum's words in scene files and on the command line: one table per enum serves parsing, printing
/// and the lists of allowed words in messages and --help.
template <class E, std::size_t N>
using WordTable = std::pair<E, const char*>[N];

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

template <class E, std::size_t N>
std::string word_of(E value, const WordTable<E, N>& table)
{
    for (const auto& [v, text] : table)
        if (v == value) return text;
    return "?";
}

template <class E, std::size_t N>
std::vector<std::string> all_words(const WordTable<E, N>& table)
{
    std::vector<std::string> words;
    for (const auto& entry : table) words.emplace_back(entry.second);
    return words;
}

/// Every word of enum E, in table order (e.g. words<Method>() = amm, fem, bim, bsim).
template <class E>
std::vector<std::string> words();
template <> std::vector<std::string> words<Method>();
template <> std::vector<std::string> words<Order>();
template <> std::vector<std::string> words<Drive>();
template <> std::vector<std::string> words<SplineBasis>();

std::string to_string(Method);
std::string to_string(Order);
std::string to_string(Drive);
std::string to_string(SplineBasis);
/// Parsers for the names above; return false for an unknown word.
bool parse(std::string_view, Method&);
bool parse(std::string_view, Order&);
bool parse(std::string_view, Drive&);
bool parse(std::string_view, SplineBasis&);

}  // namespace hubbeam
