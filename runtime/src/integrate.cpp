// FirstOrderSystem: accelerations through the mass solver the model's structure allows (or M^-1 folded into
// the forces for a constant M), exact or finite-difference Jacobians, and GSL glue.
#include "integrate.hpp"

#include "mass_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gsl/gsl_errno.h>

namespace hubbeam {

namespace {

struct StepperInfo {
    const char* name;
    const gsl_odeiv2_step_type* const* type;
};

const StepperInfo steppers[] = {
    {"msadams", &gsl_odeiv2_step_msadams}, {"msbdf", &gsl_odeiv2_step_msbdf},   {"rk8pd", &gsl_odeiv2_step_rk8pd},
    {"rkck", &gsl_odeiv2_step_rkck},       {"rkf45", &gsl_odeiv2_step_rkf45},   {"rk4", &gsl_odeiv2_step_rk4},
    {"rk2", &gsl_odeiv2_step_rk2},         {"bsimp", &gsl_odeiv2_step_bsimp},   {"rk4imp", &gsl_odeiv2_step_rk4imp},
    {"rk2imp", &gsl_odeiv2_step_rk2imp},   {"rk1imp", &gsl_odeiv2_step_rk1imp},
};

int gsl_rhs(double t, const double y[], double dydt[], void* self)
{
    return static_cast<FirstOrderSystem*>(self)->rhs(t, y, dydt);
}

int gsl_jacobian(double t, const double y[], double* dfdy, double dfdt[], void* self)
{
    return static_cast<FirstOrderSystem*>(self)->jacobian(t, y, dfdy, dfdt);
}

}  // namespace

namespace {

const WordTable<Axial, 2> axial_words = {{Axial::dynamic, "dynamic"}, {Axial::quasi_static, "quasi-static"}};
const WordTable<Stepping, 2> stepping_words = {{Stepping::free, "free"}, {Stepping::rows, "rows"}};

}  // namespace

std::string to_string(Axial v) { return word_of(v, axial_words); }
bool parse(std::string_view w, Axial& v) { return parse_word(w, axial_words, v); }
template <> std::vector<std::string> words<Axial>() { return all_words(axial_words); }
std::string to_string(Stepping v) { return word_of(v, stepping_words); }
bool parse(std::string_view w, Stepping& v) { return parse_word(w, stepping_words, v); }
template <> std::vector<std::string> words<Stepping>() { return all_words(stepping_words); }

void interpolate_state(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                       double t, int size, double* y)
{
    const double h = t1 - t0, s = (t - t0) / h, s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    // Quintic Hermite basis on [0, 1] (value, first and second derivative at 0, then at 1) and its derivative.
    const double h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, h1 = s - 6 * s3 + 8 * s4 - 3 * s5,
                 h2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), h3 = 10 * s3 - 15 * s4 + 6 * s5, h4 = -4 * s3 + 7 * s4 - 3 * s5,
                 h5 = 0.5 * (s3 - 2 * s4 + s5);
    const double d0 = -30 * s2 + 60 * s3 - 30 * s4, d1 = 1 - 18 * s2 + 32 * s3 - 15 * s4,
                 d2 = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4), d3 = 30 * s2 - 60 * s3 + 30 * s4,
                 d4 = -12 * s2 + 28 * s3 - 15 * s4, d5 = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
    const int k = size / 2;
    for (int i = 0; i < k; ++i) {
        const double p0 = y0[i], v0 = y0[k + i], a0 = f0[k + i], p1 = y1[i], v1 = y1[k + i], a1 = f1[k + i];
        y[i] = h0 * p0 + h * (h1 * v0 + h4 * v1) + h * h * (h2 * a0 + h5 * a1) + h3 * p1;
        y[k + i] = (d0 * p0 + d3 * p1) / h + d1 * v0 + d4 * v1 + h * (d2 * a0 + d5 * a1);
    }
}

double interpolation_error(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                           const double* y_mid, const double* f_mid, int size, double atol, double rtol)
{
    const double h = t1 - t0;
    // Second derivatives in s of the quintic Hermite basis at s = 1/2 (those of the end values vanish there).
    const double b0 = 0.0, b1 = -1.5, b2 = -0.25, b3 = 0.0, b4 = 1.5, b5 = -0.25;
    const int k = size / 2;
    double worst = 0.0;
    for (int i = 0; i < k; ++i) {
        const double acc = (b0 * y0[i] + b3 * y1[i]) / (h * h) + (b1 * y0[k + i] + b4 * y1[k + i]) / h +
                           (b2 * f0[k + i] + b5 * f1[k + i]);
        const double error = std::abs(acc - f_mid[k + i]) * h * h / 24.0;
        worst = std::max(worst, error / (atol + rtol * std::abs(y_mid[i])));
    }
    return worst;
}

std::vector<std::string> stepper_names()
{
    std::vector<std::string> names;
    for (const StepperInfo& s : steppers) names.emplace_back(s.name);
    return names;
}

const gsl_odeiv2_step_type* step_type(const std::string& name)
{
    for (const StepperInfo& s : steppers)
        if (name == s.name) return *s.type;
    return nullptr;
}

struct FirstOrderSystem::Work {
    using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    std::unique_ptr<MassSolver> solver;
    // Constant M with Q = F m: W = M^-1 F once, so that a right-hand side is qdd = W m, one pass of
    // multiply-adds (docs/model.md section 5.3: the prescribed-rotation M is constant). Dense (column-major)
    // or, where W is mostly zeros, by rows: row i holds W_value[W_start[i] .. W_start[i+1]) in W_column.
    Eigen::MatrixXd W;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> W_rows;  // for the generated kernel
    std::vector<int> W_start, W_column;
    std::vector<double> W_value;
    bool folded() const { return W.size() > 0 || W_rows.size() > 0 || !W_start.empty(); }
    // Hub torque where only M's hub entry m00(q) varies (no axial coordinates): with C the constant beam block
    // and b the constant coupling column, W_B = C^-1 F_B, c = C^-1 b, g = F_0 - b^T W_B and s0 = b^T c once, then
    // theta_ddot = g m / (m00(q) - s0) and B_ddot = W_B m - c theta_ddot. Besides saving the solves, the beam's
    // ill-conditioned C (BIM) is applied through fixed products of smooth monomials: its round-off is the same
    // at every evaluation instead of noise that an error control chases down to tiny steps.
    Eigen::MatrixXd hub_W;
    Eigen::VectorXd hub_c;
    Eigen::RowVectorXd hub_g;
    double hub_s0 = 0.0;
    RowMatrix hub_M;  // the varying entry's evaluation
    bool hub_folded() const { return hub_W.size() > 0; }
    Eigen::VectorXd m;
    Eigen::VectorXd qdd;
    std::vector<double> y_plus, y_minus, f_plus, f_minus;
    // Quasi-static axial coordinates: the full q, qd of the last evaluation, A's last solution (the next
    // Newton start), Q, and the factorization of M without the axial rows.
    std::vector<double> q, qd;
    Eigen::VectorXd A, Q;
    Eigen::LLT<Eigen::MatrixXd> reduced_llt;
    bool reduced_factored = false;
    // Exact Jacobian: row-major like the kernels (RowMajor maps them as written).
    RowMatrix dQdq, dQdqd, dQdu, dMv;
};

namespace {

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
void multiply(const Eigen::MatrixXd& W, const Eigen::VectorXd& x, Eigen::VectorXd& y)
{
    const auto K = W.cols();
    switch (W.rows()) {
    case 1: return multiply_fixed<1>(W.data(), x.data(), K, y.data());
    case 2: return multiply_fixed<2>(W.data(), x.data(), K, y.data());
    case 3: return multiply_fixed<3>(W.data(), x.data(), K, y.data());
    case 4: return multiply_fixed<4>(W.data(), x.data(), K, y.data());
    case 5: return multiply_fixed<5>(W.data(), x.data(), K, y.data());
    case 6: return multiply_fixed<6>(W.data(), x.data(), K, y.data());
    case 7: return multiply_fixed<7>(W.data(), x.data(), K, y.data());
    case 8: return multiply_fixed<8>(W.data(), x.data(), K, y.data());
    default: y.noalias() = W * x;
    }
}

/// dy/dt = (qd, qdd) of n coordinates; GSL_EBADFUNC when an acceleration is not finite.
int store_derivative(const double* qd, const double* qdd, int n, double* dydt)
{
    for (int i = 0; i < n; ++i) {
        dydt[i] = qd[i];
        dydt[n + i] = qdd[i];
        if (!std::isfinite(qdd[i])) return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

/// Nonzero entries of a row-major matrix.
long nonzeros(const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& A)
{
    return static_cast<long>((A.array() != 0.0).count());
}

}  // namespace

FirstOrderSystem::FirstOrderSystem(const Model& model, const Motion& motion, Axial axial)
    : model_(model), motion_(motion), n_(model.nq()), axial_(axial), work_(std::make_unique<Work>())
{
    const VariantKey& key = model.key();
    if (axial_ == Axial::quasi_static && key.nx == 0)
        throw std::invalid_argument("quasi-static axial coordinates need axial coordinates (nx > 0)");
    kept_ = kept_coordinates(key, axial_);
    Work& w = *work_;
    w.solver = MassSolver::make(model);
    w.qdd.resize(n_);
    w.dQdq.resize(n_, n_);
    w.dQdqd.resize(n_, n_);
    w.dQdu.resize(n_, static_cast<Eigen::Index>(drive_value_count));
    w.dMv.resize(n_, n_);
    const int K = model.force_terms();
    if (axial_ == Axial::dynamic && model.mass_is_constant() && K > 0) {
        Work::RowMatrix F(n_, K);
        model.forces_matrix(F.data());
        const std::vector<double> rest(static_cast<std::size_t>(n_), 0.0);
        if (!w.solver->prepare(motion.at(0.0), rest.data()))
            throw std::invalid_argument("the mass matrix of " + model.key().name() + " is not positive definite");
        Eigen::MatrixXd W = F;  // column-major: the solver takes columns
        w.solver->solve(W.data(), K);
        // Folding pays while W's nonzeros cost no more than the forces' own terms plus a dense solve. W keeps
        // the block structure of M and F (the axial and transverse blocks of the prescribed M), so a sparse W
        // is stored by rows.
        const long nnz = static_cast<long>((W.array() != 0.0).count());
        if (nnz <= nonzeros(F) + static_cast<long>(n_) * n_) {
            w.m.resize(K);
            if (2 * nnz >= static_cast<long>(n_) * K) {  // by rows only when that skips most of W
                if (model.has_forces_folded()) w.W_rows = W;
                else w.W = std::move(W);
            } else {
                w.W_start.push_back(0);
                for (int i = 0; i < n_; ++i) {
                    for (int k = 0; k < K; ++k)
                        if (W(i, k) != 0.0) {
                            w.W_column.push_back(k);
                            w.W_value.push_back(W(i, k));
                        }
                    w.W_start.push_back(static_cast<int>(w.W_value.size()));
                }
            }
        }
    }
    const std::string pattern = model.mass_pattern();
    const bool hub_only_varies = pattern[0] == 'v' && pattern.find('v', 1) == std::string::npos;
    if (axial_ == Axial::dynamic && !model.mass_is_constant() && hub_only_varies && K > 0 && n_ > 1) {
        Work::RowMatrix F(n_, K), M(n_, n_);
        model.forces_matrix(F.data());
        const std::vector<double> rest(static_cast<std::size_t>(n_), 0.0);
        model.mass(motion.at(0.0), rest.data(), M.data());
        const int r = n_ - 1;
        const Eigen::MatrixXd C = M.bottomRightCorner(r, r).selfadjointView<Eigen::Upper>();
        const Eigen::VectorXd b = M.row(0).tail(r).transpose();  // the upper triangle holds the coupling
        const Eigen::LLT<Eigen::MatrixXd> llt(C);
        if (llt.info() != Eigen::Success)
            throw std::invalid_argument("the mass matrix of " + model.key().name() + " is not positive definite");
        Eigen::MatrixXd W = llt.solve(Eigen::MatrixXd(F.bottomRows(r)));
        // As for a constant M: folding pays while W costs no more than the forces' terms plus a dense solve.
        if (static_cast<long>((W.array() != 0.0).count()) <= nonzeros(F) + static_cast<long>(n_) * n_) {
            w.hub_c = llt.solve(b);
            w.hub_g = F.row(0) - b.transpose() * W;
            w.hub_s0 = b.dot(w.hub_c);
            w.hub_W = std::move(W);
            w.hub_M.resize(n_, n_);
            w.m.resize(K);
        }
    }
    if (axial_ == Axial::quasi_static) {
        w.q.assign(static_cast<std::size_t>(n_), 0.0);
        w.qd.assign(static_cast<std::size_t>(n_), 0.0);
        w.Q.resize(n_);
        w.A = Eigen::VectorXd::Zero(key.nx);
    }
    sys_ = {gsl_rhs, gsl_jacobian, static_cast<std::size_t>(size()), this};
}

FirstOrderSystem::~FirstOrderSystem() = default;

const HubInput& FirstOrderSystem::drive_at(double t)
{
    // Multistep and implicit steppers evaluate several times at one t (predictor, corrector, Jacobian): the
    // drive's sines are computed once per distinct t.
    if (t != drive_t_) {
        drive_ = motion_.at(t);
        drive_t_ = t;
    }
    return drive_;
}

std::string FirstOrderSystem::linear_algebra() const
{
    const Work& w = *work_;
    if (axial_ == Axial::quasi_static)
        return "quasi-static axial coordinates (A by Newton on the axial rows), dense Cholesky of M without them";
    if (w.hub_folded())
        return "the hub's row by its Schur complement, the constant beam block's inverse folded into the forces "
               "once (" + std::to_string(n_ - 1) + " x " + std::to_string(w.m.size()) + ")";
    if (w.folded())
        return "M^-1 folded into the forces once (" + std::to_string(n_) + " x " + std::to_string(w.m.size()) +
               (w.W_rows.size() > 0 ? ", dense, by the generated kernel"
                : w.W.size() > 0  ? ", dense"
                                  : ", " + std::to_string(w.W_value.size()) + " nonzeros") +
               ")";
    return w.solver->describe();
}

int FirstOrderSystem::rhs(double t, const double* y, double* dydt)
{
    ++evaluations_;
    if (axial_ == Axial::quasi_static) return quasi_static_rhs(t, y, dydt);
    Work& w = *work_;
    const HubInput u = drive_at(t);
    const double* q = y;
    const double* qd = y + n_;
    if (w.W_rows.size() > 0) {
        model_.forces_folded(w.W_rows.data(), u, q, qd, w.qdd.data());
    } else if (w.folded()) {
        model_.forces_terms(u, q, qd, w.m.data());
        if (w.W.size() > 0) {
            multiply(w.W, w.m, w.qdd);
        } else {
            for (int i = 0; i < n_; ++i) {
                double sum = 0.0;
                for (int e = w.W_start[static_cast<std::size_t>(i)]; e < w.W_start[static_cast<std::size_t>(i) + 1]; ++e)
                    sum += w.W_value[static_cast<std::size_t>(e)] * w.m[w.W_column[static_cast<std::size_t>(e)]];
                w.qdd[i] = sum;
            }
        }
    } else if (w.hub_folded()) {
        model_.forces_terms(u, q, qd, w.m.data());
        model_.mass_varying(u, q, w.hub_M.data());
        const double schur = w.hub_M(0, 0) - w.hub_s0;  // > 0 exactly when M is positive definite (C is)
        if (!(schur > 0.0)) return indefinite_mass_at(q);
        const double theta_ddot = w.hub_g.dot(w.m) / schur;
        w.qdd[0] = theta_ddot;
        w.qdd.tail(n_ - 1).noalias() = w.hub_W * w.m - w.hub_c * theta_ddot;
    } else {
        if (!w.solver->prepare(u, q)) return indefinite_mass_at(q);
        model_.forces(u, q, qd, w.qdd.data());
        w.solver->solve(w.qdd.data());
    }
    return store_derivative(qd, w.qdd.data(), n_, dydt);
}

int FirstOrderSystem::indefinite_mass_at(const double* q)
{
    indefinite_mass_tip_ = model_.tip(q).uy;
    return GSL_EBADFUNC;
}

int FirstOrderSystem::jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    ++jacobian_evaluations_;
    const bool exact = model_.has_jacobian() && axial_ == Axial::dynamic;
    return exact ? exact_jacobian(t, y, dfdy, dfdt) : finite_difference_jacobian(t, y, dfdy, dfdt);
}

bool FirstOrderSystem::solve_axial(const HubInput& u, const double* y, double* q, double* qd)
{
    Work& w = *work_;
    const VariantKey& key = model_.key();
    const int r = static_cast<int>(kept_.size()), a = key.first_a(), nx = key.nx;
    for (int i = 0; i < r; ++i) {
        q[kept_[static_cast<std::size_t>(i)]] = y[i];
        qd[kept_[static_cast<std::size_t>(i)]] = y[r + i];
    }
    for (int k = 0; k < nx; ++k) {
        q[a + k] = w.A[k];
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
        model_.forces(ua, q, qd, w.Q.data());
        if (model_.has_jacobian()) {
            model_.force_derivatives(ua, q, qd, w.dQdq.data(), w.dQdqd.data(), w.dQdu.data());
            J = w.dQdq.block(a, a, nx, nx);
        } else {
            for (int k = 0; k < nx; ++k) {
                const double h = 1e-6 * std::max(std::abs(q[a + k]), 1e-3);
                q[a + k] += h;
                Eigen::VectorXd Qh(n_);
                model_.forces(ua, q, qd, Qh.data());
                q[a + k] -= h;
                J.col(k) = (Qh.segment(a, nx) - w.Q.segment(a, nx)) / h;
            }
        }
        const Eigen::VectorXd step = J.partialPivLu().solve(-w.Q.segment(a, nx));
        if (!step.allFinite()) return false;
        w.A += step;
        for (int k = 0; k < nx; ++k) q[a + k] = w.A[k];
        // Converged at 1e-12 relative, or once the steps stop shrinking at round-off (a few ulps of A times
        // the condition of the axial stiffness).
        const double size = step.lpNorm<Eigen::Infinity>(), scale = w.A.lpNorm<Eigen::Infinity>();
        const bool stalled = iteration > 0 && size >= 0.5 * previous && size <= 1e-8 * scale;
        previous = size;
        if (size <= 1e-12 * scale || size == 0.0 || stalled) {
            model_.forces(u, q, qd, w.Q.data());
            return true;
        }
    }
    return false;
}

void FirstOrderSystem::full_state(double t, const double* y, double* q, double* qd)
{
    if (axial_ == Axial::dynamic) {
        std::copy(y, y + n_, q);
        std::copy(y + n_, y + 2 * n_, qd);
        return;
    }
    solve_axial(drive_at(t), y, q, qd);
}

int FirstOrderSystem::quasi_static_rhs(double t, const double* y, double* dydt)
{
    // The rows of theta and B with A_ddot = 0: M_rr qdd_r = Q_r (docs/model.md section 9).
    Work& w = *work_;
    const HubInput& u = drive_at(t);
    if (!solve_axial(u, y, w.q.data(), w.qd.data())) return GSL_EBADFUNC;
    const int r = static_cast<int>(kept_.size());
    if (!w.reduced_factored) {
        Eigen::MatrixXd M(n_, n_), Mr(r, r);
        model_.mass(u, w.q.data(), M.data());
        for (int i = 0; i < r; ++i)
            for (int j = 0; j < r; ++j) Mr(i, j) = M(kept_[static_cast<std::size_t>(i)], kept_[static_cast<std::size_t>(j)]);
        w.reduced_llt.compute(Mr);
        if (w.reduced_llt.info() != Eigen::Success) return indefinite_mass_at(w.q.data());
        w.reduced_factored = model_.mass_is_constant();
    }
    Eigen::VectorXd Qr(r);
    for (int i = 0; i < r; ++i) Qr[i] = w.Q[kept_[static_cast<std::size_t>(i)]];
    const Eigen::VectorXd qdd = w.reduced_llt.solve(Qr);
    return store_derivative(y + r, qdd.data(), r, dydt);
}

int FirstOrderSystem::exact_jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    // y = (q, qd), f = (qd, qdd) with M(q) qdd = Q(t, q, qd) (docs/model.md section 5.1). Differentiating
    // M qdd = Q: M dqdd/dq = dQ/dq - (dM/dq) qdd, M dqdd/dqd = dQ/dqd, M dqdd/dt = dQ/du du/dt (M depends on
    // neither u nor qd; the generator checks). So dfdy = [[0, I], [M^-1 (dQ/dq - (dM/dq) qdd), M^-1 dQ/dqd]].
    Work& w = *work_;
    const HubInput u = drive_at(t);
    const double* q = y;
    const double* qd = y + n_;
    if (!w.solver->prepare(u, q)) return indefinite_mass_at(q);
    model_.forces(u, q, qd, w.qdd.data());
    w.solver->solve(w.qdd.data());
    model_.force_derivatives(u, q, qd, w.dQdq.data(), w.dQdqd.data(), w.dQdu.data());
    if (!model_.mass_is_constant()) {
        model_.mass_q_product(u, q, w.qdd.data(), w.dMv.data());
        w.dQdq -= w.dMv;
    }
    Eigen::MatrixXd lower_q = w.dQdq, lower_qd = w.dQdqd;  // column-major copies, solved in place
    w.solver->solve(lower_q.data(), n_);
    w.solver->solve(lower_qd.data(), n_);
    const std::array<double, drive_value_count> du = motion_.rate(t).packed();
    const Eigen::VectorXd dudt = Eigen::Map<const Eigen::VectorXd>(du.data(), static_cast<Eigen::Index>(du.size()));
    Eigen::VectorXd lower_t = w.dQdu * dudt;
    w.solver->solve(lower_t.data());
    const int m = size();
    for (int i = 0; i < n_; ++i) {
        for (int j = 0; j < n_; ++j) {
            dfdy[i * m + j] = 0.0;
            dfdy[i * m + n_ + j] = i == j ? 1.0 : 0.0;
            dfdy[(n_ + i) * m + j] = lower_q(i, j);
            dfdy[(n_ + i) * m + n_ + j] = lower_qd(i, j);
        }
        dfdt[i] = 0.0;
        dfdt[n_ + i] = lower_t[i];
    }
    for (int i = 0; i < m * m; ++i)
        if (!std::isfinite(dfdy[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

int FirstOrderSystem::finite_difference_jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    Work& w = *work_;
    const int m = size();
    w.y_plus.assign(y, y + m);
    w.y_minus.assign(y, y + m);
    w.f_plus.resize(m);
    w.f_minus.resize(m);
    const double scale = std::cbrt(std::numeric_limits<double>::epsilon());
    for (int j = 0; j < m; ++j) {
        const double h = scale * std::max(std::abs(y[j]), 1e-3);
        w.y_plus[j] = y[j] + h;
        w.y_minus[j] = y[j] - h;
        if (int s = rhs(t, w.y_plus.data(), w.f_plus.data()); s != GSL_SUCCESS) return s;
        if (int s = rhs(t, w.y_minus.data(), w.f_minus.data()); s != GSL_SUCCESS) return s;
        for (int i = 0; i < m; ++i) dfdy[i * m + j] = (w.f_plus[i] - w.f_minus[i]) / (2.0 * h);
        w.y_plus[j] = w.y_minus[j] = y[j];
    }
    const double ht = scale * std::max(std::abs(t), 1.0);
    if (int s = rhs(t + ht, y, w.f_plus.data()); s != GSL_SUCCESS) return s;
    if (int s = rhs(t - ht, y, w.f_minus.data()); s != GSL_SUCCESS) return s;
    for (int i = 0; i < m; ++i) dfdt[i] = (w.f_plus[i] - w.f_minus[i]) / (2.0 * ht);
    return GSL_SUCCESS;
}

}  // namespace hubbeam
