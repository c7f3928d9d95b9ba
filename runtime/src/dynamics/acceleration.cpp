// The right-hand-side strategies of FirstOrderSystem and the factory that picks one from the model's structure.
#include "dynamics/acceleration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gsl/gsl_errno.h>

#include "generated_abi.h"
#include "models/model_operations.hpp"

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
    double* qdd = dydt + n_;
    if (const int status = accelerations(u, q, qd, qdd); status != GSL_SUCCESS) return status;
    // One test for all entries: a product with zero is NaN exactly where an entry is not finite. (The copy shares
    // the loop, which also keeps it from becoming a call to memmove. Scalar on purpose: vector loads of qdd, just
    // stored entry by entry, stall on store forwarding; vectorized on the bits, this loop took 8 % longer on torque
    // AMM Nx = Ny = 4 under rk8pd, in fewer instructions.)
    double probe = 0.0;
    for (int i = 0; i < n_; ++i) {
        dydt[i] = qd[i];
        probe += qdd[i] * 0.0;
    }
    return probe == 0.0 ? GSL_SUCCESS : GSL_EBADFUNC;
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

FoldedProduct::FoldedProduct(const TermForces& terms, const FoldedForceKernel* kernel, const RowMajorMatrix& P,
                             bool hub_alone)
    : terms_(terms), kernel_(kernel), m_(static_cast<std::size_t>(P.cols()))
{
    const auto rows = P.rows(), K = P.cols();
    start_.push_back(0);
    for (Eigen::Index i = 0; i < rows; ++i) {
        for (Eigen::Index k = 0; k < K; ++k)
            if (P(i, k) != 0.0) {
                column_.push_back(static_cast<int>(k));
                value_.push_back(P(i, k));
            }
        start_.push_back(static_cast<int>(value_.size()));
    }
    if (kernel_ == nullptr) return;
    // The kernel reads P by groups of W rows, row i in slot j = i + offset (generated_abi.h), padding slots zero.
    constexpr Eigen::Index W = generated::folded_lanes;
    const Eigen::Index offset = hub_alone ? W - 1 : 0;
    groups_.assign(static_cast<std::size_t>((rows + offset + W - 1) / W * W * K), 0.0);
    for (Eigen::Index i = 0; i < rows; ++i) {
        const Eigen::Index j = i + offset;
        for (Eigen::Index k = 0; k < K; ++k)
            groups_[static_cast<std::size_t>((j / W) * W * K + W * k + j % W)] = P(i, k);
    }
    // The kernel reads only the entries its generator proved can be nonzero: it must agree with the walk over every
    // nonzero at a state where every monomial is (an older generator's object, or a pattern rule that missed an
    // entry, would not). The tolerance allows for the order of the sums only.
    std::vector<double> q(static_cast<std::size_t>(rows)), qd(q), by_kernel(q), by_walk(q);
    for (std::size_t i = 0; i < q.size(); ++i) {
        q[i] = 0.31 + 0.071 * static_cast<double>(i);
        qd[i] = -0.23 + 0.057 * static_cast<double>(i);
    }
    HubInput u;
    u.tau = 0.61, u.theta_dot = 0.83, u.theta_ddot = 0.29, u.theta = 0.47;
    kernel_->accelerations(groups_.data(), u, q.data(), qd.data(), by_kernel.data());
    terms_.terms(u, q.data(), qd.data(), m_.data());
    walk(m_.data(), by_walk.data());
    for (Eigen::Index i = 0; i < rows; ++i) {
        double scale = 0.0;
        for (int e = start_[static_cast<std::size_t>(i)]; e < start_[static_cast<std::size_t>(i) + 1]; ++e)
            scale += std::abs(value_[static_cast<std::size_t>(e)] * m_[static_cast<std::size_t>(column_[static_cast<std::size_t>(e)])]);
        const auto at = static_cast<std::size_t>(i);
        if (!(std::abs(by_kernel[at] - by_walk[at]) <= 1e-12 * scale)) {
            kernel_ = nullptr;
            break;
        }
    }
    if (kernel_ == nullptr) groups_.clear();
}

void FoldedProduct::walk(const double* m, double* y) const
{
    const double* value = value_.data();
    const int* column = column_.data();
    const std::size_t rows = start_.size() - 1;
    for (std::size_t i = 0; i < rows; ++i) {
        double sum = 0.0;
        for (const double* end = value_.data() + start_[i + 1]; value != end; ++value, ++column) sum += *value * m[*column];
        y[i] = sum;
    }
}

Folded::Folded(const Model& model, const TermForces& terms, const FoldedForceKernel* kernel, const Eigen::MatrixXd& W)
    : Accelerations(model), product_(terms, kernel, W), columns_(W.cols()), offered_(kernel != nullptr)
{
}

int Folded::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    product_.apply(u, q, qd, qdd);
    return GSL_SUCCESS;
}

std::string Folded::describe() const
{
    const char* how = !offered_ ? "" : product_.by_kernel() ? ", by the generated kernel" : ", by rows: the kernel disagreed";
    return "M^-1 folded into the forces once (" + std::to_string(n_) + " x " + std::to_string(columns_) + ", " +
           std::to_string(product_.nonzeros()) + " nonzeros" + how + ")";
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

HubSchur::HubSchur(const Model& model, const TermForces& terms, const HubInput& u0) : Accelerations(model), M_(n_, n_)
{
    const int K = terms.term_count(), r = n_ - 1;
    const std::string pattern = model.mass_pattern();
    for (int i = 1; i < n_; ++i)
        for (int j = 1; j < n_; ++j)
            if (pattern[static_cast<std::size_t>(i * n_ + j)] == 'v')
                throw std::invalid_argument("the mass matrix of " + model.key().name() + " varies outside the hub's row");
    RowMatrix F(n_, K);
    terms.term_matrix(F.data());
    const std::vector<double> rest(static_cast<std::size_t>(n_), 0.0);
    // Evaluated at rest once: the hub row's constant couplings stay in M_, where each call's varying entries join
    // them, so that M_'s row holds the whole of b.
    model.mass(u0, rest.data(), M_.data());
    const Eigen::MatrixXd C = M_.bottomRightCorner(r, r).selfadjointView<Eigen::Upper>();
    Eigen::VectorXd b_c = Eigen::VectorXd::Zero(r);  // the upper triangle holds the coupling
    for (int j = 1; j < n_; ++j) {
        const bool varies = pattern[static_cast<std::size_t>(j)] == 'v';
        if (varies) varying_.push_back(j);
        b_c[j - 1] = varies ? 0.0 : M_(0, j);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success)
        throw std::invalid_argument("the mass matrix of " + model.key().name() + " is not positive definite");
    const Eigen::MatrixXd W = llt.solve(Eigen::MatrixXd(F.bottomRows(r)));
    c_c_ = llt.solve(b_c);
    for (const int j : varying_) {
        const Eigen::VectorXd z = llt.solve(Eigen::VectorXd::Unit(r, j - 1));
        for (int i = 0; i < r; ++i)
            if (z[i] != 0.0) z_.push_back({i, j, z[i]});
    }
    RowMatrix P(n_, K);
    // With constant couplings only, b^T C^-1 F_C is folded into the hub's row too, and b^T c is the constant s0.
    P.row(0) = varying_.empty() ? Eigen::RowVectorXd(F.row(0) - b_c.transpose() * W) : Eigen::RowVectorXd(F.row(0));
    s0_ = b_c.dot(c_c_);
    P.bottomRows(r) = W;
    product_ = std::make_unique<FoldedProduct>(terms, model.folded_kernel(), P, true);
    columns_ = K;
    c_.resize(static_cast<std::size_t>(r));
    y_.resize(static_cast<std::size_t>(n_));
}

int HubSchur::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    const int r = n_ - 1;
    double* y = y_.data();
    product_->apply(u, q, qd, y);
    model_.mass_varying_upper(u, q, M_.data());
    const double* m0 = M_.data();  // the hub's row: m00, then the couplings b
    const double* y_C = y + 1;
    double schur = m0[0] - s0_, numerator = y[0];
    const double* c = c_c_.data();
    if (!varying_.empty()) {
        // c = C^-1 b = c_c + C^-1 b_v, theta_ddot = (F_0 m - b^T y_C) / (m00 - b^T c).
        double* cv = c_.data();
        std::copy_n(c, r, cv);
        for (const ColumnEntry& e : z_) cv[e.row] += e.value * m0[e.column];
        const double* b = m0 + 1;
        schur = m0[0];
        for (int i = 0; i < r; ++i) {
            numerator -= b[i] * y_C[i];
            schur -= b[i] * cv[i];
        }
        c = cv;
    }
    if (!(schur > 0.0)) return indefinite_mass_at(q);  // > 0 exactly when M is positive definite (C is)
    const double theta_ddot = numerator / schur;
    qdd[0] = theta_ddot;
    for (int i = 0; i < r; ++i) qdd[i + 1] = y_C[i] - c[i] * theta_ddot;
    return GSL_SUCCESS;
}

std::string HubSchur::describe() const
{
    return "the hub's row by its Schur complement, the constant block's inverse folded into the forces once (" +
           std::to_string(n_) + " x " + std::to_string(columns_) + ", " + std::to_string(product_->nonzeros()) +
           " nonzeros" + (product_->by_kernel() ? ", by the generated kernel" : "") +
           (varying_.empty() ? ")" : "; the hub's varying couplings through C^-1's columns)");
}

int MassSolved::accelerations(const HubInput& u, const double* q, const double* qd, double* qdd)
{
    model_.forces(u, q, qd, qdd);
    if (!solver_->prepare_and_solve(u, q, qdd)) return indefinite_mass_at(q);
    return GSL_SUCCESS;
}

QuasiStaticAxial::QuasiStaticAxial(const Model& model)
    : RightHandSide(model), q_(static_cast<std::size_t>(n_), 0.0), qd_(q_),
      A_(Eigen::VectorXd::Zero(model.coordinates().count(FieldKind::axial))), Q_(n_), dQdq_(n_, n_), dQdqd_(n_, n_),
      dQdu_(n_, static_cast<Eigen::Index>(drive_value_count))
{
    if (model.coordinates().count(FieldKind::axial) == 0)
        throw std::invalid_argument("quasi-static axial coordinates need axial coordinates (nx > 0)");
    if (model.jacobian() == nullptr)  // every model of the library has them: a test's stand-in may not
        throw std::invalid_argument("quasi-static axial coordinates need the model's exact derivatives");
    kept_ = kept_coordinates(model.coordinates(), Axial::quasi_static);
}

std::string QuasiStaticAxial::describe() const
{
    return "quasi-static axial coordinates (A by Newton on the axial rows), dense Cholesky of M without them";
}

bool QuasiStaticAxial::full_state(const HubInput& u, const double* y, double* q, double* qd)
{
    const CoordinateField& axial = *model_.coordinates().find(FieldKind::axial);
    const int r = static_cast<int>(kept_.size()), a = axial.first, nx = axial.count;
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
    const ExactJacobian& exact = *model_.jacobian();
    Eigen::MatrixXd J(nx, nx);
    double previous = 0.0;
    for (int iteration = 0; iteration < 20; ++iteration) {
        model_.forces(ua, q, qd, Q_.data());
        exact.force_derivatives(ua, q, qd, dQdq_.data(), dQdqd_.data(), dQdu_.data());
        J = dQdq_.block(a, a, nx, nx);
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
        // Folding pays while W's nonzeros cost no more than the forces' own terms plus a dense solve; the generated
        // kernel reads W's structural nonzeros only, else by rows when that skips most of W.
        const long nnz = nonzeros(W);
        if (nnz <= forces_nonzeros() + dense_solve) {
            const FoldedForceKernel* kernel = model.folded_kernel();
            if (kernel != nullptr || 2 * nnz < static_cast<long>(n) * K)
                return std::make_unique<Folded>(model, *terms, kernel, W);
            return std::make_unique<FoldedDense>(model, *terms, std::move(W));
        }
    }
    const std::string pattern = model.mass_pattern();
    bool hub_row_only = true;  // every varying entry of M in the hub's row (and column)
    for (int i = 1; i < n; ++i)
        for (int j = 1; j < n; ++j) hub_row_only = hub_row_only && pattern[static_cast<std::size_t>(i * n + j)] != 'v';
    if (!model.mass_is_constant() && hub_row_only && n > 1) {
        auto hub = std::make_unique<HubSchur>(model, *terms, motion.at(0.0));
        // With constant couplings, as above with the hub's own folded row (K entries at most) on top of W_C's. With
        // varying ones, against what the mass solver pays per call: the forces and two solves with C (banded, by
        // the mass solver's rule, or dense), the hub's row and the couplings.
        if (hub->coupling_nonzeros() == 0) {
            if (hub->nonzeros() <= forces_nonzeros() + dense_solve + K) return hub;
        } else {
            const int r = n - 1;
            int p = 0;  // C's bandwidth
            for (int i = 1; i < n; ++i)
                for (int j = i + 1; j < n; ++j)
                    if (pattern[static_cast<std::size_t>(i * n + j)] != '0') p = std::max(p, j - i);
            // Instructions of one solve with C as measured against the kernel's (about 3 per entry): diagonal,
            // GSL's banded Cholesky (with some 400 of its own per call), the dense one in loops.
            const long solve = p == 0                            ? r
                               : r >= 16 && 3 * (p + 1) <= r ? 4L * r * (p + 1) + 400
                                                               : 2L * r * r;
            // A walk over P costs about twice the unrolled kernel per entry, as much as the forces' own table form.
            const long product = (hub->by_kernel() ? 1 : 2) * hub->nonzeros();
            if (product + hub->coupling_nonzeros() <= forces_nonzeros() + 2 * solve + 4L * n) return hub;
        }
    }
    return std::make_unique<MassSolved>(model);
}

}  // namespace hubbeam
