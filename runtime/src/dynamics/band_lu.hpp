// LU of a sparse square matrix that is banded once reordered but for a few dense rows and columns (a free hub's):
// the band by LAPACK's dgbtrf, the border by its Schur complement. gauss4's Newton matrices in mass form, whose
// factorization then costs O(n b^2) instead of O(n^3).
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <utility>
#include <vector>

#include "linalg/factorizations.hpp"

namespace hubbeam {

class BorderedBandLU {
public:
    /// Plans for the matrices of one pattern (n x n, row-major nonzero flags): the rows or columns coupled to more than
    /// a third of the others, and to three times as many as the median, form the border, ordered last; the rest are
    /// ordered by reverse Cuthill-McKee, which narrows their band.
    BorderedBandLU(const std::vector<char>& pattern, int n);

    /// Flops of one factorization, to weigh against a dense LU's 2/3 n^3.
    double factor_flops() const;
    /// Flops of one solve with the factors, to weigh against a dense LU's 2 n^2.
    double solve_flops() const;
    /// The band's half-widths below and above the diagonal, and the border's size.
    int lower() const { return kl_; }
    int upper() const { return ku_; }
    int border() const { return r_; }

    /// Factors the matrix whose entries on the pattern are a(i, j) (those off it are zero); false when it is singular.
    template <class Entry>
    bool factor(Entry a)
    {
        std::fill(band_.begin(), band_.end(), 0.0);
        E_.setZero();
        F_.setZero();
        D_.setZero();
        double* const parts[4] = {band_.data(), E_.data(), F_.data(), D_.data()};
        for (std::size_t e = 0; e < entries_.size(); ++e)
            parts[places_[e].part][places_[e].offset] = a(entries_[e].first, entries_[e].second);
        return factor_filled();
    }

    /// b := A^-1 b.
    void solve(double* b) const;

private:
    bool factor_filled();
    /// x := B^-1 x for the band part B, factored.
    void band_solve(double* x) const;

    int n_, nb_ = 0, r_ = 0;  // size, the band part's size, the border's
    int kl_ = 0, ku_ = 0, ldab_ = 1;
    std::vector<int> order_, position_;         // order_[new] = old, position_[old] = new
    std::vector<std::pair<int, int>> entries_;  // the pattern's entries (old indices)
    struct Place {
        int part;               // 0 the band, 1 E, 2 F, 3 D
        std::ptrdiff_t offset;  // in that part's storage
    };
    std::vector<Place> places_;  // where each entry goes, found once: factor() is called at every refactorization
    std::vector<double> band_;   // dgbtrf's storage: ldab_ x nb_, column-major
    std::vector<int> pivots_;
    std::vector<double> inverse_diagonal_;  // of U
    Eigen::MatrixXd E_, F_, D_;  // band rows x border columns (then B^-1 E), border rows x band columns, border block
    Eigen::PartialPivLU<Eigen::MatrixXd> schur_;
    mutable Eigen::VectorXd x_, t_;
};

}  // namespace hubbeam
