// The reading order of state monomials, the one order that the emitted temporaries, each output's terms and the
// term matrix's monomials m_k share (the runtime's folded M^-1 F relies on m_k being in one agreed order).
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "poly.hpp"

namespace hubbeam::gen {

/// The total degree of a monomial.
inline int degree(const Exponents& e)
{
    int d = 0;
    for (int x : e) d += x;
    return d;
}

/// Whether x (of degree dx) reads before y (of degree dy): lower degree first, then larger exponents of earlier
/// variables first (x^2 before x y before y^2). The degrees are passed in, as callers sort many monomials.
inline bool reads_before(const Exponents& x, int dx, const Exponents& y, int dy) { return dx != dy ? dx < dy : x > y; }

/// The indices of items in reading order of exponents(item), each degree computed once.
template <class T, class Exponents_of>
std::vector<std::size_t> reading_permutation(const std::vector<T>& items, Exponents_of exponents)
{
    std::vector<std::pair<int, std::size_t>> keyed;
    keyed.reserve(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) keyed.emplace_back(degree(exponents(items[i])), i);
    std::sort(keyed.begin(), keyed.end(), [&](const auto& a, const auto& b) {
        return reads_before(exponents(items[a.second]), a.first, exponents(items[b.second]), b.first);
    });
    std::vector<std::size_t> order;
    order.reserve(keyed.size());
    for (const auto& k : keyed) order.push_back(k.second);
    return order;
}

/// Sorts monomials into reading order.
inline void sort_reading(std::vector<Exponents>& monomials)
{
    std::vector<Exponents> sorted;
    sorted.reserve(monomials.size());
    for (std::size_t i : reading_permutation(monomials, [](const Exponents& e) -> const Exponents& { return e; }))
        sorted.push_back(std::move(monomials[i]));
    monomials = std::move(sorted);
}

}  // namespace hubbeam::gen
