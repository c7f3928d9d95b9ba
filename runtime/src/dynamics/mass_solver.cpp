// The three mass solvers and the choice between them from the mass pattern.
#include "dynamics/mass_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <Eigen/Dense>

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The largest |i - j| of a nonzero entry of the square submatrix of M (row-major pattern of size n) on idx.
int bandwidth(const std::string& pattern, int n, const std::vector<int>& idx)
{
    int p = 0;
    const int m = static_cast<int>(idx.size());
    for (int i = 0; i < m; ++i)
        for (int j = i + 1; j < m; ++j)
            if (pattern[static_cast<std::size_t>(idx[i] * n + idx[j])] != '0') p = std::max(p, j - i);
    return p;
}

/// Cholesky factorization A = L L^T in plain loops, confined to A's band (bandwidth p: A(i, j) = 0 for |i - j| > p;
/// p = n - 1 is dense). Eigen's LLT costs about 470 instructions to solve a 4 x 4 system through its dynamic-size
/// machinery, several times the arithmetic, and GSL's banded solve goes through the reference CBLAS (some 2000
/// instructions for FEM's n = 32, p = 3, six times the arithmetic); the mass matrices here are small and solved
/// millions of times.
class SmallCholesky {
public:
    /// Factors the n x n matrix a(i, j) of bandwidth p (-1: dense); false when it is not positive definite.
    template <class Access>
    bool factor(int n, Access a, int p = -1)
    {
        n_ = n;
        p_ = p < 0 ? std::max(n - 1, 0) : std::min(p, std::max(n - 1, 0));
        L_.assign(static_cast<std::size_t>(n) * n, 0.0);
        inv_diag_.resize(static_cast<std::size_t>(n));
        for (int j = 0; j < n; ++j) {
            double d = a(j, j);
            for (int k = first(j); k < j; ++k) d -= L(j, k) * L(j, k);
            if (!(d > 0.0)) return false;
            const double ljj = std::sqrt(d);
            L(j, j) = ljj;
            inv_diag_[static_cast<std::size_t>(j)] = 1.0 / ljj;
            for (int i = j + 1; i <= std::min(n - 1, j + p_); ++i) {
                double s = a(i, j);
                for (int k = first(i); k < j; ++k) s -= L(i, k) * L(j, k);
                L(i, j) = s / ljj;
            }
        }
        return true;
    }
    /// a := A^-1 a and b := A^-1 b in one pass: two independent chains, so each hides the other's latency.
    void solve_pair(double* a, double* b) const
    {
        double* const v[2] = {a, b};
        solve_all(v);
    }
    /// b := A^-1 b.
    void solve(double* b) const
    {
        double* const v[1] = {b};
        solve_all(v);
    }

private:
    /// A^-1 on C vectors at once, each by the same operations in the same order as alone.
    template <int C>
    void solve_all(double* const (&v)[C]) const
    {
        if (p_ == 3) return band_solve<3>(v);  // FEM's and the cubic B-splines' bands
        if (p_ == 4) return band_solve<4>(v);
        const double* inv = inv_diag_.data();
        for (int i = 0; i < n_; ++i) {  // L y = b
            double s[C];
            for (int c = 0; c < C; ++c) s[c] = v[c][i];
            for (int k = first(i); k < i; ++k)
                for (int c = 0; c < C; ++c) s[c] -= L(i, k) * v[c][k];
            for (int c = 0; c < C; ++c) v[c][i] = s[c] * inv[i];
        }
        for (int i = n_ - 1; i >= 0; --i) {  // L^T x = y, by columns of L^T: row i of L, in the band
            double x[C];
            for (int c = 0; c < C; ++c) v[c][i] = x[c] = v[c][i] * inv[i];
            for (int k = first(i); k < i; ++k)
                for (int c = 0; c < C; ++c) v[c][k] -= L(i, k) * x[c];
        }
    }
    /// solve_all at bandwidth P, the same operations in the same order (so the same bits), with the P values a row
    /// reads held in registers: the general loops read each back from b just after storing it, and that store-to-load forwarding lay on every row's dependency chain (FEM at Ny = 64:
    /// 0.64 us a solve, a third of the run).
    template <int P, int C>
    void band_solve(double* const (&v)[C]) const
    {
        const double* inv = inv_diag_.data();
        for (int i = 0; i < P; ++i)  // L y = b: the first rows, shorter than the band
            for (double* b : v) {
                double s = b[i];
                for (int k = 0; k < i; ++k) s -= L(i, k) * b[k];
                b[i] = s * inv[i];
            }
        double w[C][P];  // y_(i-P) .. y_(i-1)
        for (int c = 0; c < C; ++c)
            for (int k = 0; k < P; ++k) w[c][k] = v[c][k];
        for (int i = P; i < n_; ++i) {
            const double* row = &L_[static_cast<std::size_t>(i) * n_ + i - P];
            for (int c = 0; c < C; ++c) {
                double s = v[c][i];
                for (int k = 0; k < P; ++k) s -= row[k] * w[c][k];
                const double y = s * inv[i];
                v[c][i] = y;
                for (int k = 0; k + 1 < P; ++k) w[c][k] = w[c][k + 1];
                w[c][P - 1] = y;
            }
        }
        // L^T x = y, rows from the last: pending holds b(i) and window b(i-P) .. b(i-1), each updated by the rows
        // after it in the same order as solve()'s column loop.
        double pending[C], window[C][P];
        for (int c = 0; c < C; ++c) {
            pending[c] = v[c][n_ - 1];
            for (int k = 0; k < P; ++k) window[c][k] = v[c][n_ - 1 - P + k];
        }
        for (int i = n_ - 1; i >= P; --i) {
            const double* row = &L_[static_cast<std::size_t>(i) * n_ + i - P];
            for (int c = 0; c < C; ++c) {
                const double x = pending[c] * inv[i];
                v[c][i] = x;
                for (int k = 0; k < P; ++k) window[c][k] -= row[k] * x;
                pending[c] = window[c][P - 1];
                for (int k = P - 1; k > 0; --k) window[c][k] = window[c][k - 1];
                window[c][0] = i - 1 - P >= 0 ? v[c][i - 1 - P] : 0.0;
            }
        }
        for (int c = 0; c < C; ++c) {
            v[c][P - 1] = pending[c];
            for (int k = 1; k < P; ++k) v[c][k - 1] = window[c][k];
        }
        for (int i = P - 1; i >= 0; --i)
            for (double* b : v) {
                const double x = b[i] * inv[i];
                b[i] = x;
                for (int k = 0; k < i; ++k) b[k] -= L(i, k) * x;
            }
    }
    int first(int i) const { return std::max(0, i - p_); }
    double& L(int i, int j) { return L_[static_cast<std::size_t>(i) * n_ + j]; }
    double L(int i, int j) const { return L_[static_cast<std::size_t>(i) * n_ + j]; }
    int n_ = 0, p_ = 0;
    std::vector<double> L_, inv_diag_;
};

/// A constant symmetric positive definite matrix factored once: the factorization and its solve.
class ConstantFactor {
public:
    virtual ~ConstantFactor() = default;
    /// False when A is not positive definite.
    virtual bool factor(const MatrixXd& A) = 0;
    /// b := A^-1 b, b of A's size.
    virtual void solve(double* b) const = 0;
    /// Both solves; together where that is faster.
    virtual void solve_pair(double* a, double* b) const
    {
        solve(a);
        solve(b);
    }
    virtual std::string describe() const = 0;
};

/// Cholesky in A's band: dense (p = -1), or banded, as the FEM and B-spline mass matrices are (bandwidth 3 or 4
/// whatever their size).
class CholeskyFactor final : public ConstantFactor {
public:
    explicit CholeskyFactor(int p = -1) : p_(p) {}
    bool factor(const MatrixXd& A) override
    {
        return llt_.factor(
            static_cast<int>(A.rows()), [&](int i, int j) { return A(i, j); }, p_);
    }
    void solve(double* b) const override { llt_.solve(b); }
    void solve_pair(double* a, double* b) const override { llt_.solve_pair(a, b); }
    std::string describe() const override
    {
        return p_ < 0 ? "dense Cholesky" : "banded Cholesky (bandwidth " + std::to_string(p_) + ")";
    }

private:
    int p_;
    SmallCholesky llt_;
};

/// A diagonal matrix (AMM's orthogonal modes): one multiplication per entry.
class DiagonalFactor final : public ConstantFactor {
public:
    bool factor(const MatrixXd& A) override
    {
        inverse_ = A.diagonal().cwiseInverse();
        return (A.diagonal().array() > 0.0).all();
    }
    void solve(double* b) const override
    {
        for (Eigen::Index i = 0; i < inverse_.size(); ++i) b[i] *= inverse_[i];
    }
    std::string describe() const override { return "diagonal"; }

private:
    VectorXd inverse_;
};

/// Diagonal where the pattern is; banded where the band leaves out part of the matrix; else dense.
std::unique_ptr<ConstantFactor> constant_factor(const std::string& pattern, int n, const std::vector<int>& idx)
{
    const int p = bandwidth(pattern, n, idx), size = static_cast<int>(idx.size());
    if (p == 0) return std::make_unique<DiagonalFactor>();
    return std::make_unique<CholeskyFactor>(p + 1 < size ? p : -1);
}

/// M(q) as the model writes it (row-major, symmetric, so read as column-major it is the same matrix).
class Evaluated {
public:
    explicit Evaluated(const Model& model) : model_(model), M_(model.nq(), model.nq()) {}
    const MatrixXd& full(const HubInput& u, const double* q)
    {
        model_.mass(u, q, M_.data());
        return M_;
    }
    const MatrixXd& varying(const HubInput& u, const double* q)
    {
        model_.mass_varying(u, q, M_.data());
        return M_;
    }
    const MatrixXd& matrix() const { return M_; }

private:
    const Model& model_;
    MatrixXd M_;
};

/// M constant: factored at the first prepare(), dense or banded.
class ConstantSolver final : public MassSolver {
public:
    ConstantSolver(const Model& model, std::unique_ptr<ConstantFactor> factor)
        : mass_(model), factor_(std::move(factor)), n_(model.nq())
    {
    }
    bool prepare(const HubInput& u, const double* q) override
    {
        if (factored_) return true;
        return factored_ = factor_->factor(mass_.full(u, q));
    }
    void solve(double* b, int columns) const override
    {
        for (int k = 0; k < columns; ++k) factor_->solve(b + static_cast<std::ptrdiff_t>(k) * n_);
    }
    std::string describe() const override { return factor_->describe() + " of a constant M, factored once"; }

private:
    Evaluated mass_;
    std::unique_ptr<ConstantFactor> factor_;
    int n_;
    bool factored_ = false;
};

/// M depends on q everywhere: a dense Cholesky factorization at every prepare().
class DenseSolver final : public MassSolver {
public:
    explicit DenseSolver(const Model& model) : mass_(model), n_(model.nq()) {}
    bool prepare(const HubInput& u, const double* q) override
    {
        const MatrixXd& M = mass_.full(u, q);
        return llt_.factor(n_, [&](int i, int j) { return M(i, j); });
    }
    void solve(double* b, int columns) const override
    {
        for (int k = 0; k < columns; ++k) llt_.solve(b + static_cast<std::ptrdiff_t>(k) * n_);
    }
    std::string describe() const override { return "dense Cholesky of M(q) at every evaluation"; }

private:
    Evaluated mass_;
    int n_;
    SmallCholesky llt_;
};

/// Only the rows and columns R depend on q (under hub torque, the hub's): with C the rest,
///   [M_RR M_RC; M_CR M_CC] [x_R; x_C] = [b_R; b_C],  M_CC constant, factored once;
///   X = M_CC^-1 M_CR, S = M_RR - M_RC X (r x r), x_R = S^-1 (b_R - M_RC M_CC^-1 b_C), x_C = M_CC^-1 b_C - X x_R.
class SchurSolver final : public MassSolver {
public:
    /// constant_coupling: M_CR does not vary either (no axial coordinates under torque), so X is computed once.
    SchurSolver(const Model& model, std::vector<int> R, std::vector<int> C, std::unique_ptr<ConstantFactor> block,
                bool constant_coupling)
        : mass_(model),
          R_(std::move(R)),
          C_(std::move(C)),
          block_(std::move(block)),
          constant_coupling_(constant_coupling),
          X_(static_cast<Eigen::Index>(C_.size()), static_cast<Eigen::Index>(R_.size())),
          z_(static_cast<Eigen::Index>(C_.size())),
          x_R_(static_cast<Eigen::Index>(R_.size()))
    {
    }
    bool prepare(const HubInput& u, const double* q) override
    {
        const MatrixXd& M = factored_ ? mass_.varying(u, q) : mass_.full(u, q);
        const auto r = static_cast<Eigen::Index>(R_.size()), c = static_cast<Eigen::Index>(C_.size());
        const bool first = !factored_;
        if (first) {
            MatrixXd block(c, c);
            for (Eigen::Index i = 0; i < c; ++i)
                for (Eigen::Index j = 0; j < c; ++j) block(i, j) = M(C_[i], C_[j]);
            if (!block_->factor(block)) return false;
            factored_ = true;
        }
        if (first || !constant_coupling_)
            for (Eigen::Index k = 0; k < r; ++k) {
                for (Eigen::Index i = 0; i < c; ++i) X_(i, k) = M(C_[i], R_[k]);
                block_->solve(X_.col(k).data());
            }
        return factor_schur();
    }
    /// Where the coupling varies with q and one row is eliminated (a free hub with axial coordinates), X's solve and
    /// b's constant-block solve run as a pair.
    bool prepare_and_solve(const HubInput& u, const double* q, double* b) override
    {
        if (!factored_ || constant_coupling_ || R_.size() != 1) return MassSolver::prepare_and_solve(u, q, b);
        const MatrixXd& M = mass_.varying(u, q);
        const auto c = static_cast<Eigen::Index>(C_.size());
        for (Eigen::Index i = 0; i < c; ++i) {
            X_(i, 0) = M(C_[i], R_[0]);
            z_(i) = b[C_[i]];
        }
        block_->solve_pair(X_.col(0).data(), z_.data());
        if (!factor_schur()) return false;
        finish_solve(b, M);
        return true;
    }
    void solve(double* b, int columns) const override
    {
        const MatrixXd& M = mass_.matrix();
        const auto r = static_cast<Eigen::Index>(R_.size()), c = static_cast<Eigen::Index>(C_.size());
        for (int col = 0; col < columns; ++col) {
            double* x = b + static_cast<std::ptrdiff_t>(col) * (r + c);
            for (Eigen::Index i = 0; i < c; ++i) z_(i) = x[C_[i]];
            block_->solve(z_.data());
            finish_solve(x, M);
        }
    }
    std::string describe() const override
    {
        return "Schur complement over " + std::to_string(R_.size()) + " varying row(s), " + block_->describe() +
               " of the constant block, factored once";
    }

private:
    /// S = M_RR - M_RC X, factored.
    /// M_RC read as M_CR's transpose, M being symmetric (Model::mass): down a column, contiguous, where along a row
    /// each entry was a cache line of its own (FEM Nx = 16, Ny = 64: these two sums were a tenth of the run).
    bool factor_schur()
    {
        const MatrixXd& M = mass_.matrix();
        const auto c = static_cast<Eigen::Index>(C_.size());
        return schur_.factor(static_cast<int>(R_.size()), [&](int i, int j) {
            double s = M(R_[i], R_[j]);
            for (Eigen::Index k = 0; k < c; ++k) s -= M(C_[k], R_[i]) * X_(k, j);
            return s;
        });
    }
    /// The rest of x = M^-1 b once z_ = M_CC^-1 b_C: x_R from the Schur complement, then x_C.
    void finish_solve(double* x, const MatrixXd& M) const
    {
        const auto r = static_cast<Eigen::Index>(R_.size()), c = static_cast<Eigen::Index>(C_.size());
        for (Eigen::Index i = 0; i < r; ++i) {
            double s = x[R_[i]];
            for (Eigen::Index k = 0; k < c; ++k) s -= M(C_[k], R_[i]) * z_(k);
            x_R_(i) = s;
        }
        schur_.solve(x_R_.data());
        for (Eigen::Index i = 0; i < r; ++i) x[R_[i]] = x_R_(i);
        for (Eigen::Index i = 0; i < c; ++i) x[C_[i]] = z_(i) - X_.row(i).dot(x_R_);
    }

    Evaluated mass_;
    std::vector<int> R_, C_;
    std::unique_ptr<ConstantFactor> block_;
    bool constant_coupling_;
    MatrixXd X_;
    mutable VectorXd z_, x_R_;
    SmallCholesky schur_;
    bool factored_ = false;
};

}  // namespace

std::unique_ptr<MassSolver> MassSolver::make(const Model& model)
{
    const int n = model.nq();
    const std::string pattern = model.mass_pattern();
    const auto varies = [&](int i, int j) { return pattern[static_cast<std::size_t>(i * n + j)] == 'v'; };
    // R: rows (and columns) that together hold every varying entry, so that the block on the rest is constant.
    // A varying diagonal entry forces its row in; the remaining entries are covered greedily, the row with the
    // most uncovered entries first (under hub torque R = {theta}, whose row holds every varying entry).
    std::vector<bool> in_R(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) in_R[static_cast<std::size_t>(i)] = varies(i, i);
    for (;;) {
        int best = -1, best_count = 0;
        for (int i = 0; i < n; ++i) {
            if (in_R[static_cast<std::size_t>(i)]) continue;
            int count = 0;
            for (int j = 0; j < n; ++j) count += varies(i, j) && !in_R[static_cast<std::size_t>(j)];
            if (count > best_count) best = i, best_count = count;
        }
        if (best < 0) break;
        in_R[static_cast<std::size_t>(best)] = true;
    }
    std::vector<int> R, C;
    for (int i = 0; i < n; ++i) (in_R[static_cast<std::size_t>(i)] ? R : C).push_back(i);
    if (R.empty()) return std::make_unique<ConstantSolver>(model, constant_factor(pattern, n, C));
    // Eliminating r varying rows costs about r solves with the constant block per evaluation: worth it while
    // r is small against n (a dense factorization costs n^3/6).
    if (!C.empty() && 4 * R.size() <= C.size()) {
        auto block = constant_factor(pattern, n, C);
        bool constant_coupling = true;
        for (const int i : R)
            for (const int j : C) constant_coupling = constant_coupling && !varies(i, j);
        return std::make_unique<SchurSolver>(model, std::move(R), std::move(C), std::move(block), constant_coupling);
    }
    return std::make_unique<DenseSolver>(model);
}

}  // namespace hubbeam
