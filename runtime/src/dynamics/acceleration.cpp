// The right-hand-side strategies of FirstOrderSystem and the factory that picks one from the model's structure.
#include "acceleration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gsl/gsl_errno.h>

namespace hubbeam {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// y = W x for a column-major W with N rows: the row count fixed at compile time so that each column's
/// update is unrolled and vectorized.
template <int N>
void multiply_fixed(const double* W, const double* x, Eigen::Index columns, double* y)
{
    double sum[N] = {};
    for (Eigen::Index k = 0; k < columns; ++k, W += N)
        for (int i = 0; i < N; ++i) sum[i] += W[i] * x[k];
    for (int i = 0; i < N; ++i) y[i] = sum[i];
}

/// y = W x. At the sizes of the paper's cases (4 x 9 for the Ny = 4 spin-up) Eigen's dynamic-size product
/// costs several times the multiply-adds themselves.
void multiply(const Eigen::MatrixXd& W, const Eigen::VectorXd& x, double* y)
{
    const auto K = W.cols();
    switch (W.rows()) {
    case 1: return multiply_fixed<1>(W.data(), x.data(), K, y);
    case 2: return multiply_fixed<2>(W.data(), x.data(), K, y);
    case 3: return multiply_fixed<3>(W.data(), x.data(), K, y);
    case 4: return multiply_fixed<4>(W.data(), x.data(), K, y);
    case 5: return multiply_fixed<5>(W.data(), x.data(), K, y);
    case 6: return multiply_fixed<6>(W.data(), x.data(), K, y);
    case 7: return multiply_fixed<7>(W.data(), x.data(), K, y);
    case 8: return multiply_fixed<8>(W.data(), x.data(), K, y);
    default: Eigen::Map<Eigen::VectorXd>(y, W.rows()).noalias() = W * x;
    }
}

/// Nonzero entries of a matrix.
template <class Matrix> long nonzeros(const Matrix& A) { return static_cast<long>((A.array() != 0.0).count()); }

}  // namespace

bool RightHandSide::full_state(const HubInput&, const double* y, double* q, double* qd)
{
    std::copy(y, y + n_, q);
    std::copy(y + n_, y + 2 * n_, qd);
    return true;
}

int RightHandSide::indefinite_mass_at(const double* q)
{
    indefinite_mass_tip_ = model_.tip(q).uy;
    return GSL_EBADFUNC;
}

int Accelerations::derivative(const HubInput& u, const double* y, double* dydt)
{
    const double* q = y;
    const double* qd = y + n_;
    if (const int status = accelerations(u, q, qd, qdd_.data()); status != GSL_SUCCESS) return status;
    for (int i = 0; i < n_; ++i) {
        dydt[i] = qd[i];
        dydt[n_ + i] = qdd_[static_cast<std::size_t>(i)];
        if (!std::isfinite(qdd_[static_cast<std::size_t>(i)])) return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

Eigen::MatrixXd folded_forces(const Model& model, const TermForces& terms, const HubInput& u0)
{
    const int n = model.nq(), K = terms.term_count();
    RowMatrix F(n, K);
    terms.term_matrix(F.data());
    const std::unique_ptr<MassSolver> solver = MassSolver::make(model);
    const std::vector<double> rest(static_cast<std::size_t>(n), 0.0);
    if (!solver->prepare(u0, rest.data()))
        throw std::invalid_argument("the mass matrix of " + model.key().name() + " is not positive definite");
    Eigen::MatrixXd W = F;  // column-major: the solver takes columns
    solver->solve(W.data(), K);
    return W;
}

int FoldedKernel::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    kernel_.accelerations(W_.data(), u, q, qd, qdd);
    return GSL_SUCCESS;
}

std::string FoldedKernel::describe() const
{
    return "M^-1 folded into the forces once (" + std::to_string(n_) + " x " + std::to_string(W_.cols()) +
           ", dense, by the generated kernel)";
}

int FoldedDense::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    terms_.terms(u, q, qd, m_.data());
    multiply(W_, m_, qdd);
    return GSL_SUCCESS;
}

std::string FoldedDense::describe() const
{
    return "M^-1 folded into the forces once (" + std::to_string(n_) + " x " + std::to_string(W_.cols()) + ", dense)";
}

FoldedSparse::FoldedSparse(const Model& model, const TermForces& terms, const Eigen::MatrixXd& W)
    : Accelerations(model), terms_(terms), m_(W.cols())
{
    start_.push_back(0);
    for (int i = 0; i < n_; ++i) {
        for (Eigen::Index k = 0; k < W.cols(); ++k)
            if (W(i, k) != 0.0) {
                column_.push_back(static_cast<int>(k));
                value_.push_back(W(i, k));
            }
        start_.push_back(static_cast<int>(value_.size()));
    }
}

int FoldedSparse::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    terms_.terms(u, q, qd, m_.data());
    for (int i = 0; i < n_; ++i) {
        double sum = 0.0;
        for (int e = start_[static_cast<std::size_t>(i)]; e < start_[static_cast<std::size_t>(i) + 1]; ++e)
            sum += value_[static_cast<std::size_t>(e)] * m_[column_[static_cast<std::size_t>(e)]];
        qdd[i] = sum;
    }
    return GSL_SUCCESS;
}

std::string FoldedSparse::describe() const
{
    return "M^-1 folded into the forces once (" + std::to_string(n_) + " x " + std::to_string(m_.size()) + ", " +
           std::to_string(value_.size()) + " nonzeros)";
}

HubSchur::HubSchur(const Model& model, const TermForces& terms, const HubInput& u0)
    : Accelerations(model), terms_(terms), m_(terms.term_count()), M_(n_, n_)
{
    const int K = terms.term_count();
    RowMatrix F(n_, K), M(n_, n_);
    terms.term_matrix(F.data());
    const std::vector<double> rest(static_cast<std::size_t>(n_), 0.0);
    model.mass(u0, rest.data(), M.data());
    const int r = n_ - 1;
    const Eigen::MatrixXd C = M.bottomRightCorner(r, r).selfadjointView<Eigen::Upper>();
    const Eigen::VectorXd b = M.row(0).tail(r).transpose();  // the upper triangle holds the coupling
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success)
        throw std::invalid_argument("the mass matrix of " + model.key().name() + " is not positive definite");
    W_ = llt.solve(Eigen::MatrixXd(F.bottomRows(r)));
    c_ = llt.solve(b);
    g_ = F.row(0) - b.transpose() * W_;
    s0_ = b.dot(c_);
}

int HubSchur::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    terms_.terms(u, q, qd, m_.data());
    model_.mass_varying(u, q, M_.data());
    const double schur = M_(0, 0) - s0_;  // > 0 exactly when M is positive definite (C is)
    if (!(schur > 0.0)) return indefinite_mass_at(q);
    const double theta_ddot = g_.dot(m_) / schur;
    qdd[0] = theta_ddot;
    Eigen::Map<Eigen::VectorXd>(qdd + 1, n_ - 1).noalias() = W_ * m_ - c_ * theta_ddot;
    return GSL_SUCCESS;
}

std::string HubSchur::describe() const
{
    return "the hub's row by its Schur complement, the constant beam block's inverse folded into the forces once (" +
           std::to_string(n_ - 1) + " x " + std::to_string(m_.size()) + ")";
}

int MassSolved::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    if (!solver_->prepare(u, q)) return indefinite_mass_at(q);
    model_.forces(u, q, qd, qdd);
    solver_->solve(qdd);
    return GSL_SUCCESS;
}

QuasiStaticAxial::QuasiStaticAxial(const Model& model)
    : RightHandSide(model), q_(static_cast<std::size_t>(n_), 0.0), qd_(q_), A_(Eigen::VectorXd::Zero(model.key().nx)),
      Q_(n_), dQdq_(n_, n_), dQdqd_(n_, n_), dQdu_(n_, static_cast<Eigen::Index>(drive_value_count))
{
    const VariantKey& key = model.key();
    if (key.nx == 0) throw std::invalid_argument("quasi-static axial coordinates need axial coordinates (nx > 0)");
    kept_ = kept_coordinates(key, Axial::quasi_static);
}

std::string QuasiStaticAxial::describe() const
{
    return "quasi-static axial coordinates (A by Newton on the axial rows), dense Cholesky of M without them";
}

bool QuasiStaticAxial::full_state(const HubInput& u, const double* y, double* q, double* qd)
{
    const VariantKey& key = model_.key();
    const int r = static_cast<int>(kept_.size()), a = key.first_a(), nx = key.nx;
    for (int i = 0; i < r; ++i) {
        q[kept_[static_cast<std::size_t>(i)]] = y[i];
        qd[kept_[static_cast<std::size_t>(i)]] = y[r + i];
    }
    for (int k = 0; k < nx; ++k) {
        q[a + k] = A_[k];
        qd[a + k] = 0.0;
    }
    // Newton on the axial rows Q_A(A) = 0 (linear in A at orders zero and first: one step, and one to confirm).
    // Every acceleration term leaves the axial rows: under torque theta_ddot is on the mass side already, under
    // a prescribed rotation the generator moved it into Q, so it is zeroed there.
    HubInput ua = u;
    ua.theta_ddot = 0.0;
    Eigen::MatrixXd J(nx, nx);
    double previous = 0.0;
    for (int iteration = 0; iteration < 20; ++iteration) {
        model_.forces(ua, q, qd, Q_.data());
        if (const ExactJacobian* exact = model_.jacobian()) {
            exact->force_derivatives(ua, q, qd, dQdq_.data(), dQdqd_.data(), dQdu_.data());
            J = dQdq_.block(a, a, nx, nx);
        } else {
            for (int k = 0; k < nx; ++k) {
                const double h = 1e-6 * std::max(std::abs(q[a + k]), 1e-3);
                q[a + k] += h;
                Eigen::VectorXd Qh(n_);
                model_.forces(ua, q, qd, Qh.data());
                q[a + k] -= h;
                J.col(k) = (Qh.segment(a, nx) - Q_.segment(a, nx)) / h;
            }
        }
        const Eigen::VectorXd step = J.partialPivLu().solve(-Q_.segment(a, nx));
        if (!step.allFinite()) return false;
        A_ += step;
        for (int k = 0; k < nx; ++k) q[a + k] = A_[k];
        // Converged at 1e-12 relative, or once the steps stop shrinking at round-off (a few ulps of A times
        // the condition of the axial stiffness).
        const double size = step.lpNorm<Eigen::Infinity>(), scale = A_.lpNorm<Eigen::Infinity>();
        const bool stalled = iteration > 0 && size >= 0.5 * previous && size <= 1e-8 * scale;
        previous = size;
        if (size <= 1e-12 * scale || size == 0.0 || stalled) {
            model_.forces(u, q, qd, Q_.data());
            return true;
        }
    }
    return false;
}

int QuasiStaticAxial::derivative(const HubInput& u, const double* y, double* dydt)
{
    // The rows of theta and B with A_ddot = 0: M_rr qdd_r = Q_r (docs/model.md section 9).
    if (!full_state(u, y, q_.data(), qd_.data())) return GSL_EBADFUNC;
    const int r = static_cast<int>(kept_.size());
    if (!reduced_factored_) {
        Eigen::MatrixXd M(n_, n_), Mr(r, r);
        model_.mass(u, q_.data(), M.data());
        for (int i = 0; i < r; ++i)
            for (int j = 0; j < r; ++j) Mr(i, j) = M(kept_[static_cast<std::size_t>(i)], kept_[static_cast<std::size_t>(j)]);
        reduced_llt_.compute(Mr);
        if (reduced_llt_.info() != Eigen::Success) return indefinite_mass_at(q_.data());
        reduced_factored_ = model_.mass_is_constant();
    }
    Eigen::VectorXd Qr(r);
    for (int i = 0; i < r; ++i) Qr[i] = Q_[kept_[static_cast<std::size_t>(i)]];
    const Eigen::VectorXd qdd = reduced_llt_.solve(Qr);
    for (int i = 0; i < r; ++i) {
        dydt[i] = y[r + i];
        dydt[r + i] = qdd[i];
        if (!std::isfinite(qdd[i])) return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

std::unique_ptr<RightHandSide> make_right_hand_side(const Model& model, const Motion& motion, Axial axial)
{
    if (axial == Axial::quasi_static) return std::make_unique<QuasiStaticAxial>(model);
    const TermForces* terms = model.term_forces();
    if (terms == nullptr) return std::make_unique<MassSolved>(model);
    const int n = model.nq(), K = terms->term_count();
    const long dense_solve = static_cast<long>(n) * n;
    // F's nonzeros: the cost of the forces' own terms, what a folded form must not exceed.
    const auto forces_nonzeros = [&] {
        RowMatrix F(n, K);
        terms->term_matrix(F.data());
        return nonzeros(F);
    };
    if (model.mass_is_constant()) {
        Eigen::MatrixXd W = folded_forces(model, *terms, motion.at(0.0));
        // Folding pays while W's nonzeros cost no more than the forces' own terms plus a dense solve; by rows only
        // when that skips most of W.
        const long nnz = nonzeros(W);
        if (nnz <= forces_nonzeros() + dense_solve) {
            if (2 * nnz < static_cast<long>(n) * K) return std::make_unique<FoldedSparse>(model, *terms, W);
            if (const FoldedForceKernel* kernel = model.folded_kernel())
                return std::make_unique<FoldedKernel>(model, *kernel, W);
            return std::make_unique<FoldedDense>(model, *terms, std::move(W));
        }
    }
    const std::string pattern = model.mass_pattern();
    const bool hub_only_varies = pattern[0] == 'v' && pattern.find('v', 1) == std::string::npos;
    if (!model.mass_is_constant() && hub_only_varies && n > 1) {
        auto hub = std::make_unique<HubSchur>(model, *terms, motion.at(0.0));
        if (hub->nonzeros() <= forces_nonzeros() + dense_solve) return hub;
    }
    return std::make_unique<MassSolved>(model);
}

}  // namespace hubbeam
