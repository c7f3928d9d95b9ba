// LU of a sparse square matrix that is banded once reordered but for a few dense rows and columns (a free hub's):
// the band by LAPACK's dgbtrf, the border by its Schur complement. gauss4's Newton matrices in mass form, whose
// factorization then costs O(n b^2) instead of O(n^3).
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace hubbeam {

class BorderedBandLU {
public:
    /// Plans for the matrices of one pattern (n x n, row-major nonzero flags): the rows or columns coupled to more than
    /// a third of the others, and to three times as many as the median, form the border, ordered last; the rest are
    /// ordered by reverse Cuthill-McKee, which narrows their band.
    BorderedBandLU(const std::vector<char>& pattern, int n);

    /// Flops of one factorization, to weigh against a dense LU's 2/3 n^3.
    double factor_flops() const;
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
        for (const auto& [i, j] : entries_) {
            const int pi = position_[static_cast<std::size_t>(i)], pj = position_[static_cast<std::size_t>(j)];
            const double v = a(i, j);
            if (pi < nb_ && pj < nb_) band_[static_cast<std::size_t>(kl_ + ku_ + pi - pj + pj * ldab_)] = v;
            else if (pi < nb_) E_(pi, pj - nb_) = v;
            else if (pj < nb_) F_(pi - nb_, pj) = v;
            else D_(pi - nb_, pj - nb_) = v;
        }
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
    std::vector<int> order_, position_;        // order_[new] = old, position_[old] = new
    std::vector<std::pair<int, int>> entries_;  // the pattern's entries (old indices)
    std::vector<double> band_;                  // dgbtrf's storage: ldab_ x nb_, column-major
    std::vector<int> pivots_;
    Eigen::MatrixXd E_, F_, D_;  // band rows x border columns (then B^-1 E), border rows x band columns, border block
    Eigen::PartialPivLU<Eigen::MatrixXd> schur_;
    mutable Eigen::VectorXd x_, t_;
};

}  // namespace hubbeam
