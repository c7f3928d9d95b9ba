// gauss4: the two-stage Gauss-Legendre method (order 4, A-stable and symmetric, so it neither damps nor excites the
// undamped stiff modes it does not resolve) with simplified Newton iterations that reuse the Jacobian and the factored
// Newton matrices across steps (Hairer & Wanner, Solving ODEs II, section IV.8, the design of RADAU5), and its error
// from step doubling, as GSL's rk4imp, which factors and forms its Jacobian at every step.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <gsl/gsl_errno.h>

#include "dynamics/band_lu.hpp"
#include "dynamics/small_product.hpp"
#include "dynamics/stepper.hpp"

namespace hubbeam {

namespace {

// The method: nodes c, matrix A, weights b = (1/2, 1/2), and d = b^T A^-1, which gives the step's end from the stage
// increments without evaluating f there (as in RADAU5).
const double root3 = std::sqrt(3.0);
const double c1 = 0.5 - root3 / 6.0, c2 = 0.5 + root3 / 6.0;
const double a11 = 0.25, a12 = 0.25 - root3 / 6.0, a21 = 0.25 + root3 / 6.0, a22 = 0.25;
const double d1 = -root3, d2 = root3;

/// The collocation polynomial u(s) over a step (s in units of it) has degree 2, u(0) = y0 and u(c_i) = y0 + Z_i:
/// the Lagrange weights of Z1 and Z2, for the next step's starting values.
double l1(double s)
{
    return s * (s - c2) / (c1 * (c1 - c2));
}
double l2(double s)
{
    return s * (s - c1) / (c2 * (c2 - c1));
}

/// A factored Newton matrix and the step it was formed for: dense, or in the mass form a bordered band (a copy of the
/// stepper's plan for a version of the pattern).
struct Newton {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    // The matrix's inverse, formed once the LU has served twice as many solves as the matrix has rows (solve_with).
    mutable Eigen::MatrixXd inverse;
    mutable int solves = 0;
    std::optional<BorderedBandLU> band;
    int planned = -1;
    double h = 0.0;
};

/// Up to this size a dense Newton matrix that serves many solves is applied as its inverse, one matrix-vector
/// product, where its LU's two triangular solves of dynamic size cost several times the flops.
constexpr int small_inverse_size = 64;

/// The larger of a running maximum and e, and NaN from the first NaN on: std::max drops a NaN, so that a step of
/// NaNs would pass the error test.
double max_keeping_nan(double maximum, double e)
{
    return e > maximum || std::isnan(e) ? e : maximum;
}

/// x = newton's matrix's solution of b (x of b's size, so that no call allocates). Forming the inverse costs about as
/// many solves as the matrix has rows: it is formed after twice that many, so that a matrix refactored every step or
/// two (a torque on a fine mesh, its steps often rejected: BIM at Nx = Ny = 8 under the torque pulse, 34 x 34, took
/// 1.38 times the CPU time with the inverse formed at once, 0.99 so) keeps its LU, and one kept for many steps (the
/// paper's spin-up with axial coordinates, 16 x 16: 0.89) gets its inverse.
void solve_with(const Newton& newton, const Eigen::VectorXd& b, Eigen::VectorXd& x)
{
    const Eigen::Index n = newton.lu.rows();
    if (newton.inverse.size() == 0 && n <= small_inverse_size && ++newton.solves > 2 * n)
        newton.inverse = newton.lu.inverse();
    if (newton.inverse.size() > 0) {
        x.resize(b.size());  // sized by its callers already: no allocation
        small_product(newton.inverse, b.data(), 1.0, false, x.data());
    }
    else
        x = newton.lu.solve(b);
}

/// The mass form of the condensed Newton matrices pays where M, K and C are banded but for the hub's row and column
/// (FEM and B-spline meshes) and the system is large enough for the dense LU's n^3 to be the cost: it is used where
/// its factorization takes at most a quarter of the dense one's flops.
constexpr int mass_form_min_size = 16;
constexpr double mass_form_max_share = 0.25;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class GaussStepper final : public Stepper {
public:
    GaussStepper(FirstOrderSystem& system, double h0, double atol, double rtol)
        : system_(system),
          m_(system.size()),
          blocks_(system.blocks()),
          n_(m_ / blocks_),
          controlled_(system.controlled_size()),
          h_(h0),
          h0_(h0),
          atol_(atol),
          rtol_(rtol),
          y1_(m_),
          y_half_(m_),
          y2_(m_),
          inverse_w_(m_),
          stage_(m_),
          z_(2 * m_),
          dz_(2 * n_),
          g_(2 * n_),
          f_(2 * m_),
          J_(n_, n_),
          dfdt_(n_),
          rows_(static_cast<std::size_t>(n_) * n_),
          k_((n_ - system.FirstOrderSystem::auxiliary_count()) / 2),
          aux_(system.FirstOrderSystem::auxiliary_count()),
          rhs2_(2 * k_),
          dv_(2 * k_),
          mix_(k_)
    {
        mass_form_ = k_ >= mass_form_min_size && system.has_mass_form();
        // Auxiliary states that are quadratures of the state (a controlled or damped hub's work and dissipated energy)
        // leave the Newton systems of (q, qd) as they are: on a mesh, where the mass form pays, they are integrated
        // from the state's stages and the Newton systems stay condensed and banded; elsewhere they stay in the dense
        // Newton matrix, as the controller's integral, which the torque reads, must.
        condensed_ = aux_ == 0 || (blocks_ == 1 && mass_form_ && system.auxiliary_are_quadratures());
        mass_form_ = mass_form_ && condensed_;
        // Sensitivities left out of the error test ride the state's longer steps, where a simplified Newton iteration
        // on them took about four corrections per stage solve (the spin-up with axial coordinates) and at times did
        // not converge: their linear stage equations are solved exactly instead (solve_blocks). Controlled, their
        // steps are short, the iteration converges in one or two corrections with whole right-hand sides, and the
        // exact solve took 1.5 to 3.4 times the instructions.
        direct_blocks_ = blocks_ > 1 && controlled_ < m_ && system.has_exact_jacobian() && n_ <= small_inverse_size;
    }

    StepStatus step(double& t, double target, double* y, double h_max) override
    {
        return from_gsl(take_step(t, target, y, h_max));
    }

    StepStatus advance(double& t, double t1, double* y) override
    {
        while (t < t1)
            if (const StepStatus s = step(t, t1, y, INFINITY); s != StepStatus::success) return s;
        return StepStatus::success;
    }

    void restart(double, const double*) override
    {
        have_guess_ = false;
        stale_jacobian_ = true;
        h_ = std::min(h_, h0_);
    }

private:
    /// One step, with the statuses of the system's GSL interface (GSL_EBADFUNC, GSL_FAILURE when no step size met
    /// the tolerance): step() translates them.
    int take_step(double& t, double target, double* y, double h_max)
    {
        Eigen::Map<Eigen::VectorXd> y0(y, m_);
        bool bad_function = false;
        for (int attempt = 0;; ++attempt) {
            const double h = share_of(t, target, h_max);
            // Out of steps to try: equations that failed to evaluate on the way are the cause (M not positive
            // definite, which GSL's steppers report at once).
            if (h <= 64.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t), 1.0) || attempt > 60)
                return bad_function ? GSL_EBADFUNC : GSL_FAILURE;
            if (!fresh_jacobian_ && stale_jacobian_)
                if (const int s = jacobian(t, y); s != GSL_SUCCESS) return s;
            // A Newton matrix of a step within a fifth of this one still converges fast: refactored only beyond that.
            if (!factored_ || std::abs(h / h_factored_ - 1.0) > 0.2) factor(h);
            for (int i = 0; i < m_; ++i) inverse_w_[i] = 1.0 / (atol_ + rtol_ * std::abs(y[i]));
            if (const int status = whole_and_halves(t, y0, h); status != GSL_SUCCESS) {
                // no convergence: a fresh Jacobian, then a shorter step
                bad_function = bad_function || status == GSL_EBADFUNC;
                if (!fresh_jacobian_)
                    stale_jacobian_ = true;
                else
                    h_ = 0.5 * h;
                have_guess_ = false;
                continue;
            }
            const double ratio = error_ratio(y);
            const double factor = std::clamp(0.9 * std::pow(std::max(ratio, 1e-10), -0.2), 0.2, 4.0);
            if (!(ratio <= 1.0)) {
                h_ = h * std::min(factor, 0.9);
                calm_ = 0;
                ++rejected_;
                have_guess_ = false;
                continue;
            }
            accept(t, target, y0, h, factor, h_max);
            return GSL_SUCCESS;
        }
    }

    /// The next step's length toward target, no longer than h_ and h_max.
    double share_of(double t, double target, double h_max) const
    {
        // The steps to the target share its distance evenly (no sliver before it, and one Newton matrix for all of
        // them: with rows every dt_out that steps end at, the clipped last step of each row interval was
        // refactored for and then again for the next interval's first step).
        const double reach = std::min(h_, h_max), distance = target - t;
        const double pieces = distance <= 1.01 * reach ? 1.0 : std::ceil(distance / reach);
        return pieces <= 1.0 ? distance : distance / pieces;
    }

    /// One step of h and two of h/2 from (t, y0): the whole step's end in y1_, the halves' in y2_; GSL_SUCCESS when
    /// all three converged.
    int whole_and_halves(double t, const Eigen::Map<Eigen::VectorXd>& y0, double h)
    {
        // The halves' result is kept, and their difference from the whole step, (2^4 - 1) times the halves' error,
        // is the estimate.
        guess(h);
        int status = solve_stages(t, y0, h, whole_, y1_);
        if (status == GSL_SUCCESS) {
            // The whole step's collocation polynomial, inside its interval, starts the halves' iterations.
            z_last_ = z_;
            h_last_ = h;
            interpolate(0.0);
            status = solve_stages(t, y0, 0.5 * h, half_, y_half_);
            if (status == GSL_SUCCESS) {
                interpolate(0.5);
                status = solve_stages(t + 0.5 * h, y_half_, 0.5 * h, half_, y2_);
            }
        }
        return status;
    }

    /// The step's error against the tolerance at its ends (at most 1 passes) in the entries it weighs (controlled_):
    /// the halves' error, (y2 - y1) / 15.
    double error_ratio(const double* y) const
    {
        double ratio = 0.0;
        for (int i = 0; i < controlled_; ++i)
            ratio = max_keeping_nan(
                ratio, std::abs(y2_[i] - y1_[i]) / 15.0 / (atol_ + rtol_ * std::max(std::abs(y[i]), std::abs(y2_[i]))));
        return ratio;
    }

    /// An accepted step of h from t: t and y0 at its end, and the next step's length h_ from the error's factor.
    void accept(double& t, double target, Eigen::Map<Eigen::VectorXd>& y0, double h, double factor, double h_max)
    {
        // Accepted. The Jacobian is kept while the iteration converges fast; the second half's polynomial
        // extrapolates to the next step's starting values.
        z_last_ = z_;
        h_last_ = 0.5 * h;
        have_guess_ = true;
        t = h == target - t ? target : t + h;
        y0 = y2_;
        ++steps_;
        fresh_jacobian_ = false;
        stale_jacobian_ = rate_ > 0.05;
        // A growth of less than a fifth is not taken (as RADAU5 does): the Newton matrices stay factored. A step
        // the target shortened says nothing against the step before it, which the next one resumes unless this
        // one's error calls for less. Where h_max, not the target, shortened the step, h_ follows the step: held
        // above the bound, it was tried, and rejected, each time the bound let go (FEM at Ny = 16, rtol 1e-10:
        // 29,634 steps instead of 18,332).
        // Once calm_steps steps in a row have passed, a decrease the error asks for after a step that passed (to
        // no less than 0.9 of it) is not taken either, as CVODE keeps its step after a success: small decreases
        // drifted the step until its Newton matrices had to be refactored, and the next growth refactored them
        // again (FEM at Nx = Ny = 32 under torque: 28,371 steps in 1.5 s against 32,944 in 1.85 s). After a
        // rejection they are taken until the steps are calm again: at once, FEM at Ny = 16, rtol 1e-10 took
        // 32,537 steps instead of 19,880.
        calm_ = std::min(calm_ + 1, calm_steps);
        const double keep_from = calm_ == calm_steps ? 0.9 : 1.0;
        const double next = factor >= keep_from && factor <= 1.2 ? h : h * factor;
        const bool target_shortened = h < h_ && h_ <= h_max;
        h_ = target_shortened && factor >= 1.0 ? std::max(next, h_) : next;
    }

public:
    void retake(double, const double*) override { have_guess_ = false; }

    long steps() const override { return steps_; }
    long rejected() const override { return rejected_; }
    bool has_midpoint() const override { return true; }
    std::string newton_form() const override
    {
        const int size = 2 * (condensed_ ? k_ : n_);
        if (!mass_form_ || !whole_.band) return "dense LU of " + std::to_string(size) + " x " + std::to_string(size);
        const BorderedBandLU& b = *whole_.band;
        return "mass form, band LU of " + std::to_string(size) + " x " + std::to_string(size) + " (half-widths " +
               std::to_string(b.lower()) + " and " + std::to_string(b.upper()) +
               ", reverse Cuthill-McKee) bordered by " + std::to_string(b.border()) + " dense rows";
    }
    std::optional<std::pair<double, double>> banded_newton_flops() const override
    {
        if (!mass_form_ || !whole_.band) return std::nullopt;
        return std::pair(whole_.band->factor_flops(), whole_.band->solve_flops());
    }
    bool midpoint(double* y) const override
    {
        if (steps_ == 0) return false;
        std::copy_n(y_half_.data(), m_, y);
        return true;
    }

private:
    /// The state's rates (the first block's; of all of y where there is one block).
    int state_rhs(double t, const double* y, double* f)
    {
        return blocks_ > 1 ? system_.FirstOrderSystem::rhs(t, y, f) : system_.rhs(t, y, f);
    }

    /// The state's Jacobian (n_ x n_), which the Newton matrices of every block are made of.
    int jacobian(double t, const double* y)
    {
        if (mass_form_) {
            const int s = mass_form_jacobian(t, y);
            if (s != GSL_SUCCESS || mass_form_) return s;
        }
        const int s = blocks_ > 1 ? system_.FirstOrderSystem::jacobian(t, y, rows_.data(), dfdt_.data())
                                  : system_.jacobian(t, y, rows_.data(), dfdt_.data());
        if (s != GSL_SUCCESS) return s;
        J_ = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(rows_.data(), n_,
                                                                                                      n_);
        if (condensed_) {
            Jq_ = J_.block(k_, 0, k_, k_);
            Jv_ = J_.block(k_, k_, k_, k_);
        }
        fresh_jacobian_ = true;
        stale_jacobian_ = false;
        factored_ = false;
        return GSL_SUCCESS;
    }

    /// The Jacobian's lower blocks in mass form, M^-1 K and M^-1 C with K and C kept apart from M (their union
    /// pattern grows as entries appear: the centrifugal terms are zero at rest); the mass form is left for the
    /// dense one where the pattern is too full to pay.
    int mass_form_jacobian(double t, const double* y)
    {
        const int k = k_;
        Md_.resize(k, k);
        Kd_.resize(k, k);
        Cd_.resize(k, k);
        const int s = system_.mass_form_jacobian(t, y, Md_.data(), Kd_.data(), Cd_.data());
        if (s != GSL_SUCCESS) return s;
        if (pattern_.empty()) pattern_.assign(static_cast<std::size_t>(k) * k, 0);
        bool grew = false;
        for (int i = 0; i < k; ++i)
            for (int j = 0; j < k; ++j) {
                char& p = pattern_[static_cast<std::size_t>(i) * k + j];
                if (!p && (Md_(i, j) != 0.0 || Kd_(i, j) != 0.0 || Cd_(i, j) != 0.0)) p = 1, grew = true;
            }
        if (grew) {
            // The condensed system's pattern: every stage block has the coordinates' pattern. Planned once here; the
            // Newton matrices of h and h/2 take copies.
            std::vector<char> stages(static_cast<std::size_t>(4) * k * k, 0);
            for (int bi = 0; bi < 2; ++bi)
                for (int bj = 0; bj < 2; ++bj)
                    for (int i = 0; i < k; ++i)
                        for (int j = 0; j < k; ++j)
                            stages[static_cast<std::size_t>(bi * k + i) * 2 * k + bj * k + j] =
                                pattern_[static_cast<std::size_t>(i) * k + j];
            plan_.emplace(stages, 2 * k);
            const double dense = 2.0 / 3.0 * std::pow(2.0 * k, 3);
            if (plan_->factor_flops() > mass_form_max_share * dense) {
                mass_form_ = false;  // no narrow band: the dense Newton matrices cost no more
                return GSL_SUCCESS;
            }
            ++pattern_version_;
        }
        Ms_ = sparse_on_pattern(Md_);
        Ks_ = sparse_on_pattern(Kd_);
        fresh_jacobian_ = true;
        stale_jacobian_ = false;
        factored_ = false;
        return GSL_SUCCESS;
    }

    /// The entries of a k_ x k_ matrix on the pattern, as a sparse row-major matrix for products.
    Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_on_pattern(const RowMatrix& A) const
    {
        std::vector<Eigen::Triplet<double>> entries;
        for (int i = 0; i < k_; ++i)
            for (int j = 0; j < k_; ++j)
                if (pattern_[static_cast<std::size_t>(i) * k_ + j] && A(i, j) != 0.0)
                    entries.emplace_back(i, j, A(i, j));
        Eigen::SparseMatrix<double, Eigen::RowMajor> S(k_, k_);
        S.setFromTriplets(entries.begin(), entries.end());
        return S;
    }

    /// The condensed Newton matrix times I (x) M, I (x) M - h^2 A^2 (x) K - h A (x) C, factored as a bordered band.
    bool factor_mass_form(double step, Newton& newton)
    {
        const int k = k_;
        if (newton.planned != pattern_version_) {
            newton.band = plan_;
            newton.planned = pattern_version_;
        }
        const double a[2][2] = {{a11, a12}, {a21, a22}};
        double cm[2][2], ck[2][2], cc[2][2];
        for (int bi = 0; bi < 2; ++bi)
            for (int bj = 0; bj < 2; ++bj) {
                cm[bi][bj] = bi == bj ? 1.0 : 0.0;
                ck[bi][bj] = -step * step * (a[bi][0] * a[0][bj] + a[bi][1] * a[1][bj]);  // -h^2 (A^2)_ij
                cc[bi][bj] = -step * a[bi][bj];
            }
        newton.h = step;
        return newton.band->factor([&](int i, int j) {
            const int bi = i >= k, bj = j >= k, r = i - bi * k, c = j - bj * k;  // no division: called per entry
            return cm[bi][bj] * Md_(r, c) + ck[bi][bj] * Kd_(r, c) + cc[bi][bj] * Cd_(r, c);
        });
    }

    /// The Newton matrices of the two stages for the whole step h and its halves, factored: I - h A (x) J, or where y
    /// is (q, qd) alone, so that J = [[0, I], [Jq, Jv]], its velocity part I - h^2 A^2 (x) Jq - h A (x) Jv, half the
    /// size (an eighth of the factorization's work, a quarter of each solve's); in the mass form that part times
    /// I (x) M, sparse.
    void factor(double h)
    {
        if (mass_form_) {
            if (factor_mass_form(h, whole_) && factor_mass_form(0.5 * h, half_)) {
                factored_ = true;
                h_factored_ = h;
                return;
            }
            // A singular band or border: the dense form, with its pivoting across the whole matrix, from here on.
            mass_form_ = false;
            const Eigen::PartialPivLU<Eigen::MatrixXd> mass(Md_);
            Jq_ = mass.solve(Kd_);
            Jv_ = mass.solve(Cd_);
        }
        const auto factor_one = [&](double step, Newton& newton) {
            const int k = condensed_ ? k_ : n_;
            Eigen::MatrixXd N(2 * k, 2 * k);
            const double a[2][2] = {{a11, a12}, {a21, a22}};
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    auto block = N.block(i * k, j * k, k, k);
                    if (condensed_) {
                        const double a2 = a[i][0] * a[0][j] + a[i][1] * a[1][j];  // (A^2)_ij
                        block = -step * step * a2 * Jq_ - step * a[i][j] * Jv_;
                    } else {
                        block = -step * a[i][j] * J_;
                    }
                    if (i == j) block.diagonal().array() += 1.0;
                }
            newton.lu.compute(N);
            newton.inverse.resize(0, 0);
            newton.solves = 0;
            newton.h = step;
        };
        factor_one(h, whole_);
        factor_one(0.5 * h, half_);
        factored_ = true;
        h_factored_ = h;
    }

    /// The Newton correction dz_ of one block's stage residuals g_ (stage by stage, each (q, qd)) with newton's
    /// factored matrix.
    void newton_solve(const Newton& newton)
    {
        if (!condensed_) {
            solve_with(newton, g_, dz_);
            return;
        }
        // dQ_i = g_q,i + h sum_j a_ij dV_j, and the velocity rows with dQ substituted (in the mass form, times M).
        // Loops on raw entries: at these sizes Eigen's expressions of segments cost more than their arithmetic.
        const int k = k_, n = n_;
        const double h = newton.h, a[2][2] = {{a11, a12}, {a21, a22}};
        const double* const g = g_.data();
        double* const mix = mix_.data();
        double* const rhs2 = rhs2_.data();
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < k; ++j) mix[j] = a[i][0] * g[j] + a[i][1] * g[n + j];
            if (mass_form_) {
                rhs2_.segment(i * k, k).noalias() = Ms_ * g_.segment(i * n + k, k);
                rhs2_.segment(i * k, k).noalias() += h * (Ks_ * mix_);
            } else {
                std::copy_n(g + i * n + k, k, rhs2 + i * k);
                small_product(Jq_, mix_.data(), h, true, rhs2 + i * k);
            }
        }
        if (mass_form_) {
            dv_ = rhs2_;
            newton.band->solve(dv_.data());
        } else {
            solve_with(newton, rhs2_, dv_);
        }
        const double* const dv = dv_.data();
        double* const dz = dz_.data();
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < k; ++j) dz[i * n + j] = g[i * n + j] + h * (a[i][0] * dv[j] + a[i][1] * dv[k + j]);
            std::copy_n(dv + i * k, k, dz + i * n + k);
            // Quadratures: Z = h (A (x) I) g(stages) solves their stage equations once the state's stages are known,
            // so their correction is their residual (a step behind the state's, which the convergence test sees).
            std::copy_n(g + i * n + 2 * k, aux_, dz + i * n + 2 * k);
        }
    }

    /// One simplified Newton correction of block b's stage increments from the stage rates in f_: g_ = h (A (x) I)
    /// F - Z, then Z += dz_; returns the correction's weighted norm.
    double correct_block(int b, double h, const Newton& newton)
    {
        const int n = n_;
        const double* const f1 = f_.data() + b * n;
        const double* const f2 = f1 + m_;
        double* const z1 = z_.data() + b * n;
        double* const z2 = z1 + m_;
        double* const g = g_.data();
        for (int i = 0; i < n; ++i) {
            g[i] = h * (a11 * f1[i] + a12 * f2[i]) - z1[i];
            g[n + i] = h * (a21 * f1[i] + a22 * f2[i]) - z2[i];
        }
        newton_solve(newton);
        // The weighted norm by the weights' reciprocals and without branches (a division and a mispredicted jump per
        // entry cost more than the correction's arithmetic); the sum catches a NaN or infinity, which the maximum
        // would drop, so that a correction of NaNs cannot pass as converged.
        const double* const d = dz_.data();
        const double* const inverse_w = inverse_w_.data() + b * n;
        double norm = 0.0, sum = 0.0;
        for (int i = 0; i < n; ++i) {
            z1[i] += d[i];
            z2[i] += d[n + i];
            const double e = std::max(std::abs(d[i]), std::abs(d[n + i])) * inverse_w[i];
            norm = std::max(norm, e);
            sum += e;
        }
        return std::isfinite(sum) ? norm : sum;
    }

    /// The stage increments' starting values for a step of h from the last step's end: that step's collocation
    /// polynomial extrapolated (zero at a start).
    void guess(double h)
    {
        if (!have_guess_) {
            z_.setZero();
            return;
        }
        // u(s) over the last step, in units of it: the new stages sit at s = 1 + c_i h / h_last.
        const double r = h / h_last_;
        start_from(1.0, r);
    }

    /// The starting values of a half step from s0 (0 or 1/2) of the whole step z_last_: its polynomial's increments.
    void interpolate(double s0) { start_from(s0, 0.5); }

    /// z_ = u(s0 + c_i r) - u(s0) for the polynomial u of z_last_ (Lagrange weights l1, l2 of its two stages).
    void start_from(double s0, double r)
    {
        const double w1[2] = {l1(s0 + c1 * r) - l1(s0), l1(s0 + c2 * r) - l1(s0)};
        const double w2[2] = {l2(s0 + c1 * r) - l2(s0), l2(s0 + c2 * r) - l2(s0)};
        for (int i = 0; i < 2; ++i) z_.segment(i * m_, m_) = w1[i] * z_last_.head(m_) + w2[i] * z_last_.tail(m_);
    }

    /// Simplified Newton on Z = (Y1 - y0, Y2 - y0): Z = h (A (x) I) F(y0 + Z), with the factored matrix lu, from the
    /// starting values in z_; y1 = y0 + d Z. The rate estimate carried from the last solve lets a linear step stop
    /// after one iteration (RADAU5's test). With more blocks than the state (sensitivities), the state's stages are
    /// solved first and then the other blocks' together (the staggered corrector of CVODES), each with the state's
    /// Newton matrix, or exactly (solve_blocks).
    int solve_stages(double t, const Eigen::Ref<const Eigen::VectorXd>& y0, double h, const Newton& newton,
                     Eigen::VectorXd& y1)
    {
        double eta = std::pow(std::max(eta_, std::numeric_limits<double>::epsilon()), 0.8);
        const auto iterate = [&](bool state, double& eta_out) {
            double previous = 0.0, eta_in = eta;
            for (int k = 0; k < 7; ++k) {
                stage_ = y0 + z_.head(m_);
                const auto evaluate = [&](double at, double* f) {
                    return state ? state_rhs(at, stage_.data(), f) : system_.rhs(at, stage_.data(), f);
                };
                if (evaluate(t + c1 * h, f_.data()) != GSL_SUCCESS) return GSL_EBADFUNC;
                stage_ = y0 + z_.tail(m_);
                if (evaluate(t + c2 * h, f_.data() + m_) != GSL_SUCCESS) return GSL_EBADFUNC;
                double norm = 0.0;
                for (int b = state ? 0 : 1; b < (state ? 1 : blocks_); ++b)
                    norm = std::max(norm, correct_block(b, h, newton));
                if (!std::isfinite(norm)) return GSL_EBADFUNC;
                if (k > 0) {
                    const double rate = norm / previous;
                    if (state) rate_ = rate;
                    if (rate >= 0.99) return GSL_EMAXITER;
                    eta_in = rate / (1.0 - rate);
                }
                previous = norm;
                if (eta_in * norm <= newton_tol || norm == 0.0) {
                    if (state && k == 0) rate_ = 0.0;
                    eta_out = eta_in;
                    return GSL_SUCCESS;
                }
            }
            return GSL_EMAXITER;
        };
        if (const int s = iterate(true, eta_); s != GSL_SUCCESS) return s;
        if (direct_blocks_) {
            // The whole step's result serves the error estimate alone, which does not weigh these blocks.
            if (&newton != &whole_)
                if (const int s = solve_blocks(t, y0, h); s != GSL_SUCCESS) return s;
        } else if (blocks_ > 1) {
            double eta_blocks = 0.0;
            if (const int s = iterate(false, eta_blocks); s != GSL_SUCCESS) return s;
        }
        y1 = y0 + d1 * z_.head(m_) + d2 * z_.tail(m_);
        return GSL_SUCCESS;
    }

    /// The later blocks' stage increments solved exactly, once the state's stages have converged: their equations
    /// Z_i = h sum_j a_ij (J_j (s0 + Z_j) + b_j) are linear, with J_j = J(Y_j) and b_j their forcing
    /// (FirstOrderSystem::blocks_forcing). The positions' rows of J_j are (0 I 0) and their b_j zero, so only the rows
    /// below them are kept. Condensed as the state's Newton systems are: the positions' increments are
    /// Q_i = h c_i v0 + h sum_j a_ij V_j, and the rows below them, W_i = (V_i, auxiliary), solve
    /// W_i - h sum_l (a_il Lw_l + h (A diag(Lq) A)_il) W_l = h sum_j a_ij (J_j s0 + b_j + h c_j Lq_j v0), with
    /// J_j's lower rows split into the positions' columns Lq_j and the rest Lw_j: one LU of twice their count for all
    /// blocks, in place of a simplified Newton iteration per block.
    int solve_blocks(double t, const Eigen::Ref<const Eigen::VectorXd>& y0, double h)
    {
        const int k = k_, r = n_ - k_, p = blocks_ - 1;
        const double a[2][2] = {{a11, a12}, {a21, a22}}, c[2] = {c1, c2};
        for (int i = 0; i < 2; ++i) {
            stage_ = y0 + z_.segment(i * m_, m_);
            const double at = t + c[i] * h;
            double* const f = f_.data() + i * m_;
            if (system_.blocks_forcing(at, stage_.data(), f) != GSL_SUCCESS ||
                system_.FirstOrderSystem::jacobian(at, stage_.data(), rows_.data(), dfdt_.data()) != GSL_SUCCESS)
                return GSL_EBADFUNC;
            stage_J_[i] = Eigen::Map<const RowMatrix>(rows_.data(), n_, n_).bottomRows(r);
            stage_b_[i].resize(r, p);
            for (int b = 0; b < p; ++b) stage_b_[i].col(b) = Eigen::Map<const Eigen::VectorXd>(f + (b + 1) * n_ + k, r);
        }
        // The matrix, entry by entry (Eigen's expressions of blocks cost more than the arithmetic at these sizes).
        Eigen::MatrixXd& N = blocks_matrix_;
        N.resize(2 * r, 2 * r);
        for (int i = 0; i < 2; ++i)
            for (int l = 0; l < 2; ++l) {
                const double wl = -h * a[i][l];
                const double q0 = -h * h * a[i][0] * a[0][l], q1 = -h * h * a[i][1] * a[1][l];
                for (int col = 0; col < r; ++col) {
                    double* const to = N.data() + (l * r + col) * 2 * r + i * r;
                    const double* const w = stage_J_[l].data() + (k + col) * r;
                    for (int row = 0; row < r; ++row) to[row] = wl * w[row];
                    if (col < k) {
                        const double* const j0 = stage_J_[0].data() + col * r;
                        const double* const j1 = stage_J_[1].data() + col * r;
                        for (int row = 0; row < r; ++row) to[row] += q0 * j0[row] + q1 * j1[row];
                    }
                    if (i == l) to[col] += 1.0;
                }
            }
        blocks_lu_.compute(N);
        // All blocks at once: U_j = J_j S_j + B_j, S_j the blocks' starting values with their positions moved on by
        // h c_j times their velocities (the positions' increments' known part), then the right-hand sides
        // h sum_j a_ij U_j and one solve.
        const Eigen::Map<const Eigen::MatrixXd> s0(y0.data() + n_, n_, p);
        blocks_rhs_.resize(2 * r, p);
        for (int j = 0; j < 2; ++j) {
            blocks_s_ = s0;
            blocks_s_.topRows(k) += (h * c[j]) * s0.middleRows(k, k);
            blocks_u_[j].noalias() = stage_J_[j] * blocks_s_;
            blocks_u_[j] += stage_b_[j];
        }
        for (int i = 0; i < 2; ++i)
            blocks_rhs_.middleRows(i * r, r) = h * (a[i][0] * blocks_u_[0] + a[i][1] * blocks_u_[1]);
        blocks_w_.resize(2 * r, p);
        for (int b = 0; b < p; ++b) blocks_w_.col(b) = blocks_lu_.solve(blocks_rhs_.col(b));  // vector solves: cheaper
        for (int b = 1; b <= p; ++b) {
            const auto v0 = s0.col(b - 1).segment(k, k);
            const auto w = blocks_w_.col(b - 1);
            for (int i = 0; i < 2; ++i) {
                auto z = z_.segment(i * m_ + b * n_, n_);
                z.head(k) = h * c[i] * v0 + h * (a[i][0] * w.head(k) + a[i][1] * w.segment(r, k));
                z.tail(r) = w.segment(i * r, r);
            }
        }
        if (!blocks_w_.allFinite()) return GSL_EBADFUNC;
        return GSL_SUCCESS;
    }

    FirstOrderSystem& system_;
    int m_, blocks_, n_;  // y's size; its blocks (the state, then its sensitivities) and their size
    int controlled_;      // the leading entries of y the error test weighs (FirstOrderSystem::controlled_size)
    double h_, h0_, atol_, rtol_;
    // The Newton iteration stops when its predicted remaining error is below this fraction of the tolerance: the
    // step-doubling estimate compares three solves, each converged well within it (0.03 measured as accurate as 1e-4
    // on the paper's spin-up and torque; with growths under a fifth not taken, 6 % fewer instructions than 0.01 on
    // the main job, its tip as close to a tight run; keeping the Jacobian up to a rate of 0.2 saved 1 % more but let
    // the torque case's error reach 30 times its estimate).
    static constexpr double newton_tol = 0.03;
    static constexpr int calm_steps = 5;
    int calm_ = 0;  // steps accepted since the last rejection by the error test, up to calm_steps
    long rejected_ = 0;
    Eigen::VectorXd y1_, y_half_, y2_, inverse_w_, stage_, z_, dz_, g_, f_, z_last_;
    // The later blocks solved exactly (solve_blocks): each stage's Jacobian and forcing below the positions' rows,
    // the condensed matrix and its LU, and scratch.
    bool direct_blocks_ = false;
    Eigen::MatrixXd stage_J_[2], stage_b_[2], blocks_matrix_, blocks_s_, blocks_u_[2], blocks_rhs_, blocks_w_;
    Eigen::PartialPivLU<Eigen::MatrixXd> blocks_lu_;
    Eigen::MatrixXd J_;
    Eigen::VectorXd dfdt_;
    std::vector<double> rows_;  // the system's row-major Jacobian
    Newton whole_, half_;       // the Newton matrices of h and h/2
    // y = (q, qd) with no auxiliary states, or only quadratures of the state: the Newton systems condensed to the
    // velocities, with J's lower blocks.
    int k_, aux_;
    bool condensed_ = false;
    Eigen::MatrixXd Jq_, Jv_;
    // The mass form (mass_form_jacobian): M, K and C, their union pattern and its version, the band LU planned for it,
    // and M and K sparse for the Newton corrections' products.
    bool mass_form_ = false;
    RowMatrix Md_, Kd_, Cd_;
    std::vector<char> pattern_;  // row-major, k_ x k_
    int pattern_version_ = 0;
    std::optional<BorderedBandLU> plan_;  // for the condensed system's pattern (2k_ x 2k_) of pattern_version_
    Eigen::SparseMatrix<double, Eigen::RowMajor> Ms_, Ks_;
    Eigen::VectorXd rhs2_, dv_, mix_;
    bool have_guess_ = false, factored_ = false, fresh_jacobian_ = false, stale_jacobian_ = true;
    double h_factored_ = 0.0, h_last_ = 0.0, eta_ = 1.0, rate_ = 0.0;
    long steps_ = 0;
};

}  // namespace

std::unique_ptr<Stepper> make_gauss_stepper(FirstOrderSystem& system, double h0, double atol, double rtol)
{
    return std::make_unique<GaussStepper>(system, h0, atol, rtol);
}

}  // namespace hubbeam
