// The bordered band LU: its ordering (reverse Cuthill-McKee), LAPACK's band factorization and the border's Schur
// complement.
#include "dynamics/band_lu.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <dlfcn.h>
#include <queue>
#include <stdexcept>
#include <string>

#include "generated_abi.h"  // HUBBEAM_WIDE_KERNEL

namespace hubbeam {

namespace {

/// LAPACK's (Fortran) LU with partial pivoting of a band matrix.
using BandFactorization = void(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
                               int* ipiv, int* info);

/// dgbtrf, from LAPACK opened at its first use, once per process: LAPACK is linked with immediate binding, and loaded
/// with the program it cost every run 1,760 symbol bindings (its own and the BLAS's), about a quarter of the start-up's
/// instructions, where only gauss4's banded Newton matrices on fine meshes call it (docs/performance.md, start-up).
/// The library is found as the program's own would be (the system's library path; HUBBEAM_LAPACK, set at build).
BandFactorization& dgbtrf()
{
    static BandFactorization* const function = [] {
        void* lapack = ::dlopen(HUBBEAM_LAPACK, RTLD_NOW | RTLD_LOCAL);
        void* symbol = lapack != nullptr ? ::dlsym(lapack, "dgbtrf_") : nullptr;
        if (symbol == nullptr) {
            const char* why = ::dlerror();
            throw std::runtime_error(std::string("gauss4's band LU needs LAPACK's dgbtrf from ") + HUBBEAM_LAPACK +
                                     ", which could not be loaded" + (why != nullptr ? std::string(": ") + why : "") +
                                     " (install liblapack3, or give --stepper rk8pd)");
        }
        return reinterpret_cast<BandFactorization*>(symbol);
    }();
    return *function;
}

using Graph = std::vector<std::vector<int>>;

/// The pattern's entries (row-major flags of an n x n matrix), row by row.
std::vector<std::pair<int, int>> pattern_entries(const std::vector<char>& pattern, int n)
{
    std::vector<std::pair<int, int>> entries;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            if (pattern[static_cast<std::size_t>(i) * n + j] != 0) entries.emplace_back(i, j);
    return entries;
}

/// The pattern's symmetrized graph, without the diagonal: each vertex's neighbours in increasing order.
Graph symmetric_graph(const std::vector<char>& pattern, int n)
{
    const auto at = [&](int i, int j) { return pattern[static_cast<std::size_t>(i) * n + j] != 0; };
    Graph neighbours(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            if (i != j && (at(i, j) || at(j, i))) neighbours[static_cast<std::size_t>(i)].push_back(j);
    return neighbours;
}

/// The graph's dense vertices, the border: each coupled to over a third of the others and to three times as many
/// as the median vertex.
std::vector<bool> border_vertices(const Graph& neighbours, int n)
{
    const auto degree = [&](int i) { return neighbours[static_cast<std::size_t>(i)].size(); };
    std::vector<std::size_t> degrees;
    for (int i = 0; i < n; ++i) degrees.push_back(degree(i));
    std::nth_element(degrees.begin(), degrees.begin() + n / 2, degrees.end());
    const std::size_t median = n > 0 ? degrees[static_cast<std::size_t>(n / 2)] : 0;
    std::vector<bool> border(static_cast<std::size_t>(n), false);
    for (int i = 0; i < n; ++i)
        border[static_cast<std::size_t>(i)] = 3 * degree(i) > static_cast<std::size_t>(n) && degree(i) > 3 * median;
    return border;
}

/// The band part's vertices (those not in border) in reverse Cuthill-McKee order.
std::vector<int> reverse_cuthill_mckee(const Graph& neighbours, const std::vector<bool>& border, int n)
{
    const auto degree = [&](int i) { return neighbours[static_cast<std::size_t>(i)].size(); };
    // Cuthill-McKee, a component at a time from a vertex of least degree, then reversed.
    std::vector<bool> seen(border);
    std::vector<int> band;
    for (;;) {
        int start = -1;
        for (int i = 0; i < n; ++i)
            if (!seen[static_cast<std::size_t>(i)] && (start < 0 || degree(i) < degree(start))) start = i;
        if (start < 0) break;
        std::queue<int> next;
        next.push(start);
        seen[static_cast<std::size_t>(start)] = true;
        while (!next.empty()) {
            const int v = next.front();
            next.pop();
            band.push_back(v);
            std::vector<int> fresh;
            for (const int w : neighbours[static_cast<std::size_t>(v)])
                if (!seen[static_cast<std::size_t>(w)]) fresh.push_back(w), seen[static_cast<std::size_t>(w)] = true;
            std::stable_sort(fresh.begin(), fresh.end(), [&](int a, int b) { return degree(a) < degree(b); });
            for (const int w : fresh) next.push(w);
        }
    }
    std::reverse(band.begin(), band.end());
    return band;
}

}  // namespace

BorderedBandLU::BorderedBandLU(const std::vector<char>& pattern, int n) : n_(n)
{
    entries_ = pattern_entries(pattern, n);
    const Graph neighbours = symmetric_graph(pattern, n);
    const std::vector<bool> border = border_vertices(neighbours, n);
    const std::vector<int> band = reverse_cuthill_mckee(neighbours, border, n);
    order_ = band;
    for (int i = 0; i < n; ++i)
        if (border[static_cast<std::size_t>(i)]) order_.push_back(i);
    nb_ = static_cast<int>(band.size());
    r_ = n - nb_;
    position_.assign(static_cast<std::size_t>(n), 0);
    for (int p = 0; p < n; ++p) position_[static_cast<std::size_t>(order_[static_cast<std::size_t>(p)])] = p;
    for (const auto& [i, j] : entries_) {
        const int pi = position_[static_cast<std::size_t>(i)], pj = position_[static_cast<std::size_t>(j)];
        if (pi >= nb_ || pj >= nb_) continue;
        kl_ = std::max(kl_, pi - pj);
        ku_ = std::max(ku_, pj - pi);
    }
    ldab_ = 2 * kl_ + ku_ + 1;  // dgbtrf's fill-in needs kl_ rows above the band
    for (const auto& [i, j] : entries_) {
        const int pi = position_[static_cast<std::size_t>(i)], pj = position_[static_cast<std::size_t>(j)];
        if (pi < nb_ && pj < nb_)
            places_.push_back({0, kl_ + ku_ + pi - pj + static_cast<std::ptrdiff_t>(pj) * ldab_});
        else if (pi < nb_)
            places_.push_back({1, pi + static_cast<std::ptrdiff_t>(pj - nb_) * nb_});
        else if (pj < nb_)
            places_.push_back({2, (pi - nb_) + static_cast<std::ptrdiff_t>(pj) * r_});
        else
            places_.push_back({3, (pi - nb_) + static_cast<std::ptrdiff_t>(pj - nb_) * r_});
    }
    band_.assign(static_cast<std::size_t>(ldab_) * std::max(nb_, 1), 0.0);
    pivots_.assign(static_cast<std::size_t>(std::max(nb_, 1)), 0);
    inverse_diagonal_.assign(static_cast<std::size_t>(std::max(nb_, 1)), 0.0);
    E_.resize(nb_, r_);
    F_.resize(r_, nb_);
    D_.resize(r_, r_);
    x_.resize(n);
}

double BorderedBandLU::factor_flops() const
{
    const double nb = nb_, r = r_;
    // The band's LU, its solves for the border's columns, and the border's dense LU and Schur complement.
    return 2.0 * nb * kl_ * (kl_ + ku_ + 1) + r * 2.0 * nb * (2 * kl_ + ku_ + 1) + 2.0 * r * r * nb +
           2.0 / 3.0 * r * r * r;
}

double BorderedBandLU::solve_flops() const
{
    const double nb = nb_, r = r_;
    // The band's two triangular solves (L's kl and U's kl + ku entries per column), the border's coupling both ways
    // and its dense solve.
    return 2.0 * nb * (2 * kl_ + ku_ + 1) + 4.0 * r * nb + 2.0 * r * r;
}

bool BorderedBandLU::factor_filled()
{
    int info = 0;
    if (nb_ > 0) {
        dgbtrf()(&nb_, &nb_, &kl_, &ku_, band_.data(), &ldab_, pivots_.data(), &info);
        if (info != 0) return false;
        for (int j = 0; j < nb_; ++j)  // U's diagonal, inverted once: the solves multiply
            inverse_diagonal_[static_cast<std::size_t>(j)] =
                1.0 / band_[static_cast<std::size_t>(kl_ + ku_ + j * ldab_)];
    }
    if (r_ == 0) return true;
    for (int c = 0; c < r_; ++c) band_solve(E_.col(c).data());
    schur_.compute(D_ - F_ * E_);  // E_ now holds B^-1 E
    // PartialPivLU does not report a zero pivot: a singular Schur complement shows as a non-finite determinant's
    // inverse, or a zero determinant.
    const double det = schur_.determinant();
    return std::isfinite(det) && det != 0.0;
}

void BorderedBandLU::solve(double* b) const
{
    for (int p = 0; p < n_; ++p) x_[p] = b[order_[static_cast<std::size_t>(p)]];
    band_solve(x_.data());
    if (r_ > 0) {
        // x_border = S^-1 (b_border - F B^-1 b_band), x_band = B^-1 b_band - (B^-1 E) x_border.
        t_ = schur_.solve(x_.tail(r_) - F_ * x_.head(nb_));
        x_.tail(r_) = t_;
        x_.head(nb_).noalias() -= E_ * t_;
    }
    for (int p = 0; p < n_; ++p) b[order_[static_cast<std::size_t>(p)]] = x_[p];
}

// The band solve's column loops run four wide where the processor has AVX2, compiled twice as the generated folded
// kernels are, with bitwise the same results (a quarter fewer instructions for FEM at Ny = 32).
HUBBEAM_WIDE_KERNEL void BorderedBandLU::band_solve(double* x) const
{
    // dgbtrs's algorithm in plain loops (LAPACK's goes through a BLAS call per column, costly at these sizes): the
    // row interchanges and L's multipliers column by column, then U, whose kl + ku superdiagonals dgbtrf stored.
    // The columns' loops are short (kl and kl + ku long): restrict spares them the compiler's overlap checks.
    const int kd = kl_ + ku_;
    const double* __restrict const band = band_.data();
    const int* __restrict const pivots = pivots_.data();
    for (int j = 0; j + 1 < nb_ && kl_ > 0; ++j) {
        const int l = pivots[j] - 1;
        const double xj = x[l];  // the interchange, unconditional (l == j is no interchange)
        x[l] = x[j];
        x[j] = xj;
        const double* __restrict const multipliers = band + static_cast<std::ptrdiff_t>(j) * ldab_ + kd + 1;
        double* __restrict const below = x + j + 1;
        const int lm = std::min(kl_, nb_ - 1 - j);
        for (int i = 0; i < lm; ++i) below[i] -= multipliers[i] * xj;
    }
    const double* __restrict const inverse = inverse_diagonal_.data();
    for (int j = nb_ - 1; j >= 0; --j) {
        const double xj = x[j] * inverse[j];
        x[j] = xj;
        const int first = std::max(0, j - kd);
        const double* __restrict const u = band + static_cast<std::ptrdiff_t>(j) * ldab_ + kd - (j - first);
        double* __restrict const above = x + first;
        for (int i = 0, count = j - first; i < count; ++i) above[i] -= xj * u[i];
    }
}

}  // namespace hubbeam
