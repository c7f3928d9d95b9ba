// FirstOrderSystem: the right-hand side by the strategy acceleration.hpp chooses for the model, exact or
// finite-difference Jacobians, and GSL glue.
#include "dynamics/integrate.hpp"

#include "dynamics/acceleration.hpp"
#include "dynamics/mass_solver.hpp"
#include "models/modal_damping.hpp"
#include "models/model_operations.hpp"
#include "terms.hpp"

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

void interpolate_state(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                       double t, int size, double* y, int auxiliary)
{
    const double h = t1 - t0, s = (t - t0) / h, s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    // Quintic Hermite basis on [0, 1] (value, first and second derivative at 0, then at 1) and its derivative.
    const double h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, h1 = s - 6 * s3 + 8 * s4 - 3 * s5,
                 h2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), h3 = 10 * s3 - 15 * s4 + 6 * s5,
                 h4 = -4 * s3 + 7 * s4 - 3 * s5, h5 = 0.5 * (s3 - 2 * s4 + s5);
    const double d0 = -30 * s2 + 60 * s3 - 30 * s4, d1 = 1 - 18 * s2 + 32 * s3 - 15 * s4,
                 d2 = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4), d3 = 30 * s2 - 60 * s3 + 30 * s4,
                 d4 = -12 * s2 + 28 * s3 - 15 * s4, d5 = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
    const int k = (size - auxiliary) / 2;
    for (int i = 0; i < k; ++i) {
        const double p0 = y0[i], v0 = y0[k + i], a0 = f0[k + i], p1 = y1[i], v1 = y1[k + i], a1 = f1[k + i];
        y[i] = h0 * p0 + h * (h1 * v0 + h4 * v1) + h * h * (h2 * a0 + h5 * a1) + h3 * p1;
        y[k + i] = (d0 * p0 + d3 * p1) / h + d1 * v0 + d4 * v1 + h * (d2 * a0 + d5 * a1);
    }
    // Cubic Hermite basis (value and rate at 0, then at 1) for the auxiliary states.
    const double c0 = 1 - 3 * s2 + 2 * s3, c1 = s - 2 * s2 + s3, c2 = 3 * s2 - 2 * s3, c3 = -s2 + s3;
    for (int i = 2 * k; i < size; ++i) y[i] = c0 * y0[i] + c2 * y1[i] + h * (c1 * f0[i] + c3 * f1[i]);
}

double interpolation_error(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                           const double* y_mid, const double* f_mid, int size, double atol, double rtol, int auxiliary)
{
    const double h = t1 - t0;
    // Second derivatives in s of the quintic Hermite basis at s = 1/2 (those of the end values vanish there).
    const double b0 = 0.0, b1 = -1.5, b2 = -0.25, b3 = 0.0, b4 = 1.5, b5 = -0.25;
    const int k = (size - auxiliary) / 2;
    double worst = 0.0;
    for (int i = 0; i < k; ++i) {
        const double acc = (b0 * y0[i] + b3 * y1[i]) / (h * h) + (b1 * y0[k + i] + b4 * y1[k + i]) / h +
                           (b2 * f0[k + i] + b5 * f1[k + i]);
        const double error = std::abs(acc - f_mid[k + i]) * h * h / 24.0;
        worst = std::max(worst, error / (atol + rtol * std::abs(y_mid[i])));
    }
    for (int i = 2 * k; i < size; ++i) {
        // The rates at both ends and the middle against the step's increment of z (Simpson's rule): a rate that
        // varies too much over the step for its three values to integrate it shows here, and the step limit that
        // keeps this within the tolerance keeps the cubic's values near it.
        const double simpson = y0[i] + h / 6.0 * (f0[i] + 4.0 * f_mid[i] + f1[i]);
        const double error = std::abs(simpson - y1[i]);
        worst = std::max(worst, error / (atol + rtol * std::abs(y_mid[i])));
    }
    return worst;
}

std::vector<std::string> stepper_names()
{
    std::vector<std::string> names;
    for (const StepperInfo& s : steppers) names.emplace_back(s.name);
    names.emplace_back(gauss_stepper);
    names.emplace_back(cvode_stepper);
    return names;
}

bool is_stepper(const std::string& name)
{
    const std::vector<std::string> names = stepper_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

const gsl_odeiv2_step_type* step_type(const std::string& name)
{
    for (const StepperInfo& s : steppers)
        if (name == s.name) return *s.type;
    return nullptr;
}

namespace {

/// A controller's torque's derivatives by the state (q, qd, the integral z) and by t.
struct TorqueDerivatives {
    Eigen::VectorXd dq, dqd;
    double dz = 0.0, dt = 0.0;
};

}  // namespace

struct FirstOrderSystem::Work {
    using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    std::unique_ptr<RightHandSide> rhs;
    // The exact Jacobian's own solves of M, and its buffers: row-major like the kernels (RowMajor maps them as
    // written).
    std::unique_ptr<MassSolver> solver;
    Eigen::VectorXd qdd;
    RowMatrix dQdq, dQdqd, dQdu, dMv;
    std::vector<double> y_plus, y_minus, f_plus, f_minus;
    // A control's tip feedback: u_y(L) = tip_row . (kept coordinates); the dissipation matrix alpha M_ee + beta K_e
    // over the kept coordinates (zero in the hub's row and column), and a product with it.
    Eigen::VectorXd tip_row;
    Eigen::MatrixXd dissipation;
    Eigen::VectorXd product;
    // jacobian_product's: the auxiliary states' rows of dfdy as exact_jacobian writes them (zero elsewhere), and a
    // product's acceleration rows, a column per vector.
    RowMatrix auxiliary_rows;
    std::vector<double> auxiliary_dfdt;
    Eigen::MatrixXd directions;
    // exact_jacobian's lower blocks M^-1 (dQ/dq - (dM/dq) qdd) and M^-1 dQ/dqd, and M^-1 dQ/dtau, M^-1 dQ/dt and
    // dQ/dtheta.
    Eigen::MatrixXd lower_q, lower_qd;
    Eigen::VectorXd lower_tau, lower_t, dQdtheta;
    // A control's torque derivatives, and their products with jacobian_product's vectors: kept, for a right-hand
    // side's worth of work must not allocate.
    TorqueDerivatives dtau;
    Eigen::RowVectorXd dtau_v;
};

Auxiliary Auxiliary::of(const VariantKey& key, bool damped, const Control* control, const Parameters* parameters,
                         bool integral)
{
    Auxiliary a;
    a.integral = control != nullptr && !control->law && (control->ki != 0.0 || integral);
    a.dissipated = damped && parameters != nullptr;
    a.work = key.drive == Drive::torque && (control != nullptr || a.dissipated);
    return a;
}

FirstOrderSystem::FirstOrderSystem(const Model& model, const Motion& motion, Axial axial, const Control* control,
                                   const Parameters* parameters, bool integral)
    : model_(model), motion_(motion), n_(model.nq()), axial_(axial), control_(control), work_(std::make_unique<Work>())
{
    const VariantKey& key = model.key();
    if (control_ != nullptr && key.drive != Drive::torque)
        throw std::invalid_argument("a controlled hub needs a torque variant, not " + key.name());
    kept_ = kept_coordinates(model.coordinates(), axial_);
    aux_ = Auxiliary::of(key, dissipates(model), control_, parameters, integral);
    const int k = static_cast<int>(kept_.size());
    int next = 2 * k;
    if (aux_.integral) integral_ = next++;
    if (aux_.dissipated) dissipated_ = next++;
    if (aux_.work) work_at_ = next++;
    Work& w = *work_;
    const std::vector<double> zero(static_cast<std::size_t>(n_), 0.0);
    if (control_ != nullptr) {
        w.tip_row = tip_row(model, zero, kept_, &Tip::uy);  // u_y(L) is linear in the kept coordinates
    }
    if (aux_.dissipated) {
        const Eigen::MatrixXd C = damping_matrix(model, *parameters);
        w.dissipation.resize(k, k);
        for (int i = 0; i < k; ++i)
            for (int j = 0; j < k; ++j)
                w.dissipation(i, j) = C(kept_[static_cast<std::size_t>(i)], kept_[static_cast<std::size_t>(j)]);
        w.product.resize(k);
    }
    w.rhs = make_right_hand_side(model, motion, axial);
    w.solver = MassSolver::make(model);
    w.qdd.resize(n_);
    w.dQdq.resize(n_, n_);
    w.dQdqd.resize(n_, n_);
    w.dQdu.resize(n_, static_cast<Eigen::Index>(drive_value_count));
    w.dMv.resize(n_, n_);
    sys_ = {gsl_rhs, gsl_jacobian, static_cast<std::size_t>(state_size()), this};
}

FirstOrderSystem::~FirstOrderSystem() = default;

const HubInput& FirstOrderSystem::drive_at(double t)
{
    // Multistep and implicit steppers evaluate several times at one t (predictor, corrector, Jacobian), and gauss4's
    // Newton iterations alternate between its two stages' times: the drive's sines are computed once per such t.
    if (t == drive_t_[0]) return drive_[0];
    if (t == drive_t_[1]) return drive_[1];
    const int e = drive_older_;
    drive_older_ = 1 - e;
    drive_[e] = motion_.at(t);
    drive_t_[e] = t;
    return drive_[e];
}

std::string FirstOrderSystem::linear_algebra() const
{
    return work_->rhs->describe();
}

double FirstOrderSystem::indefinite_mass_tip() const
{
    return work_->rhs->indefinite_mass_tip();
}

int FirstOrderSystem::rhs(double t, const double* y, double* dydt)
{
    ++evaluations_;
    if (control_ == nullptr && aux_.count() == 0) return work_->rhs->derivative(drive_at(t), y, dydt);
    return extended_rhs(t, y, dydt);
}

void FirstOrderSystem::full_acceleration(double t, const double* y, double* qdd)
{
    const std::size_t k = kept_.size();
    std::vector<double> dydt(static_cast<std::size_t>(state_size()));
    const bool ok = FirstOrderSystem::rhs(t, y, dydt.data()) == GSL_SUCCESS;
    std::fill_n(qdd, model_.nq(), ok ? 0.0 : std::numeric_limits<double>::quiet_NaN());
    for (std::size_t j = 0; ok && j < k; ++j) qdd[kept_[j]] = dydt[k + j];
}

HubState FirstOrderSystem::hub_state(const double* y) const
{
    const auto k = static_cast<Eigen::Index>(kept_.size());
    const Eigen::VectorXd& c = work_->tip_row;
    HubState s;
    s.theta = y[0];
    s.theta_dot = y[k];
    s.tip_uy = c.dot(Eigen::Map<const Eigen::VectorXd>(y, k));
    s.tip_uy_dot = c.dot(Eigen::Map<const Eigen::VectorXd>(y + k, k));
    return s;
}

double FirstOrderSystem::torque(double t, const double* y)
{
    saturated_ = false;
    if (control_ == nullptr) return model_.key().drive == Drive::torque ? drive_at(t).tau : 0.0;
    const HubState s = hub_state(y);
    if (control_->law) return control_->law(t, s);
    const double tau = control_->unclipped(s, integral_ >= 0 ? y[integral_] : 0.0, drive_at(t));
    if (std::abs(tau) <= control_->tau_max || std::isnan(tau)) return tau;
    saturated_ = true;
    return std::copysign(control_->tau_max, tau);
}

bool FirstOrderSystem::saturated(double t, const double* y)
{
    torque(t, y);
    return saturated_;
}

HubInput FirstOrderSystem::input_at(double t, const double* y)
{
    if (control_ == nullptr) return drive_at(t);
    HubInput u;  // a torque variant reads tau alone (and its angle from q), the control's law of the state
    u.tau = torque(t, y);
    return u;
}

int FirstOrderSystem::extended_rhs(double t, const double* y, double* dydt)
{
    Work& w = *work_;
    const int k = static_cast<int>(kept_.size());
    const HubInput u = input_at(t, y);
    if (control_ != nullptr && !std::isfinite(u.tau)) return GSL_EBADFUNC;
    if (const int status = w.rhs->derivative(u, y, dydt); status != GSL_SUCCESS) return status;
    if (integral_ >= 0) dydt[integral_] = y[0] - drive_at(t).theta;
    if (dissipated_ >= 0) {
        const Eigen::Map<const Eigen::VectorXd> qd(y + k, k);
        w.product.noalias() = w.dissipation * qd;
        dydt[dissipated_] = qd.dot(w.product);
    }
    if (work_at_ >= 0) dydt[work_at_] = u.tau * y[k];
    return GSL_SUCCESS;
}

int FirstOrderSystem::jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    ++jacobian_evaluations_;
    if (has_exact_jacobian()) return exact_jacobian(*model_.jacobian(), t, y, dfdy, dfdt);
    return finite_difference_jacobian(t, y, dfdy, dfdt);
}

void FirstOrderSystem::full_state(double t, const double* y, double* q, double* qd)
{
    work_->rhs->full_state(drive_at(t), y, q, qd);
}

namespace {

/// The torque's derivatives of the PD(I) law unsaturated at reference (tip_row: its tip feedback's row); zero without
/// a control or where it saturates (a law given as code is differenced by finite_difference_jacobian instead).
const TorqueDerivatives& torque_derivatives(const Control* control, bool saturated, const Eigen::VectorXd& tip_row,
                                            const HubInput& reference, int n, TorqueDerivatives& d)
{
    d.dq.setZero(n);
    d.dqd.setZero(n);
    d.dz = d.dt = 0.0;
    if (control != nullptr && !saturated) {
        d.dq = -control->k_tip * tip_row;
        d.dq[0] -= control->kp;
        d.dqd[0] = -control->kd;
        d.dz = -control->ki;
        d.dt = control->kp * reference.theta_dot + control->kd * reference.theta_ddot;
    }
    return d;
}

/// The first-order Jacobian's rows of the state (q, qd), row-major in m columns: dfdy = [[0, I], [lower_q, lower_qd]]
/// and dfdt = (0, lower_t); with an integral state at column integral, its column b dtau/dz in the lower rows.
void write_state_rows(const Eigen::MatrixXd& lower_q, const Eigen::MatrixXd& lower_qd, const Eigen::VectorXd& lower_t,
                      const Eigen::VectorXd& b, double dtau_dz, int integral, int n, int m, double* dfdy, double* dfdt)
{
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            dfdy[i * m + j] = 0.0;
            dfdy[i * m + n + j] = i == j ? 1.0 : 0.0;
            dfdy[(n + i) * m + j] = lower_q(i, j);
            dfdy[(n + i) * m + n + j] = lower_qd(i, j);
        }
        dfdt[i] = 0.0;
        dfdt[n + i] = lower_t[i];
        if (integral >= 0) dfdy[(n + i) * m + integral] = b[i] * dtau_dz;
    }
}

/// Where a system's auxiliary states sit in y (-1: not carried).
struct AuxiliaryAt {
    int integral, dissipated, work;
};

/// The auxiliary states' rows of the Jacobian (their rates' derivatives), row-major in m columns: the controller's
/// integral, the dissipated energy (dissipation: C) and the hub's work, at qd under the torque tau.
void write_auxiliary_rows(const AuxiliaryAt& at, int n, int m, const Eigen::MatrixXd& dissipation, const double* qd,
                          double tau, double theta_dot_ref, double tau_rate, const TorqueDerivatives& dtau,
                          double* dfdy, double* dfdt)
{
    if (at.integral >= 0) {  // z' = theta - theta_ref(t)
        dfdy[at.integral * m + 0] = 1.0;
        dfdt[at.integral] = -theta_dot_ref;
    }
    if (at.dissipated >= 0) {  // z' = qd^T C qd
        const Eigen::VectorXd g = 2.0 * (dissipation * Eigen::Map<const Eigen::VectorXd>(qd, n));
        for (int j = 0; j < n; ++j) dfdy[at.dissipated * m + n + j] = g[j];
    }
    if (at.work >= 0) {  // z' = tau theta_dot
        const double theta_dot = qd[0];
        for (int j = 0; j < n; ++j) {
            dfdy[at.work * m + j] = theta_dot * dtau.dq[j];
            dfdy[at.work * m + n + j] = theta_dot * dtau.dqd[j];
        }
        dfdy[at.work * m + n] += tau;
        if (at.integral >= 0) dfdy[at.work * m + at.integral] = theta_dot * dtau.dz;
        dfdt[at.work] = theta_dot * tau_rate;  // the law's dtau/dt under a control
    }
}

}  // namespace

int FirstOrderSystem::exact_jacobian(const ExactJacobian& exact, double t, const double* y, double* dfdy, double* dfdt)
{
    // y = (q, qd), f = (qd, qdd) with M(q) qdd = Q(t, q, qd) (docs/model.md section 5.1). Differentiating
    // M qdd = Q: M dqdd/dq = dQ/dq - (dM/dq) qdd, M dqdd/dqd = dQ/dqd, M dqdd/dt = dQ/du du/dt (M depends on
    // neither u nor qd; the generator checks). So dfdy = [[0, I], [M^-1 (dQ/dq - (dM/dq) qdd), M^-1 dQ/dqd]].
    // A control's torque depends on the state: dQ/dtau dtau/dy joins each block (zero where it saturates), and the
    // auxiliary states' rows are their rates' derivatives.
    Work& w = *work_;
    const HubInput reference = drive_at(t);
    const HubInput u = input_at(t, y);
    const double* q = y;
    const double* qd = y + n_;
    if (const int s = force_linearization(exact, u, y); s != GSL_SUCCESS) return s;
    // In the Work, so that a Jacobian allocates nothing (gauss4 forms two per stage solve for sensitivities).
    Eigen::MatrixXd &lower_q = w.lower_q, &lower_qd = w.lower_qd;  // column-major copies, solved in place
    lower_q = w.dQdq;
    lower_qd = w.dQdqd;
    w.solver->solve(lower_q.data(), n_);
    w.solver->solve(lower_qd.data(), n_);
    const TorqueDerivatives& dtau = torque_derivatives(control_, saturated_, w.tip_row, reference, n_, w.dtau);
    Eigen::VectorXd& b = w.lower_tau;  // M^-1 dQ/dtau
    b.setZero(n_);
    if (control_ != nullptr) {
        b = w.dQdu.col(static_cast<Eigen::Index>(index(DriveValue::tau)));
        w.solver->solve(b.data());
        lower_q += b * dtau.dq.transpose();
        lower_qd += b * dtau.dqd.transpose();
    }
    std::array<double, drive_value_count> du = motion_.rate(t).packed();
    if (control_ != nullptr) du = {dtau.dt, 0.0, 0.0};
    const Eigen::Map<const Eigen::VectorXd> dudt(du.data(), static_cast<Eigen::Index>(du.size()));
    Eigen::VectorXd& lower_t = w.lower_t;
    lower_t.noalias() = w.dQdu * dudt;
    if (reads_driven_angle(model_.key())) {
        w.dQdtheta.resize(n_);  // the angle is an input too: (dQ/dtheta - dM/dtheta qdd) theta_dot
        model_.forces_theta(u, q, qd, w.dQdtheta.data());
        if (mass_reads_angle(model_.key())) {  // M turns with the angle (allocates: a rare variant's Jacobian)
            Eigen::VectorXd qdd(n_);
            model_.forces(u, q, qd, qdd.data());
            w.solver->solve(qdd.data());
            w.dQdtheta -= mass_theta_derivative(model_, u, q) * qdd;
        }
        lower_t += u.theta_dot * w.dQdtheta;
    }
    w.solver->solve(lower_t.data());
    const int m = state_size();
    if (aux_.count() > 0) {
        std::fill_n(dfdy, m * m, 0.0);
        std::fill_n(dfdt, m, 0.0);
    }
    write_state_rows(lower_q, lower_qd, lower_t, b, dtau.dz, integral_, n_, m, dfdy, dfdt);
    write_auxiliary_rows({integral_, dissipated_, work_at_}, n_, m, w.dissipation, qd, u.tau, reference.theta_dot,
                         du[index(DriveValue::tau)], dtau, dfdy, dfdt);
    for (int i = 0; i < m * m; ++i)
        if (!std::isfinite(dfdy[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

bool FirstOrderSystem::has_exact_jacobian() const
{
    return model_.jacobian() != nullptr && axial_ == Axial::dynamic && !(control_ != nullptr && control_->law);
}

int FirstOrderSystem::jacobian_product(double t, const double* y, int k, const double* v, const double* g, double* out)
{
    const ExactJacobian* exact = model_.jacobian();
    // The lower rows: M^-1 (g + K v_q + C v_qd + dQ/dtau (dtau/dy . v)), K and C as mass_form_jacobian's, the
    // products exact_jacobian's matrices would give, at one solve per vector instead of 2n + 1 per Jacobian.
    Work& w = *work_;
    const HubInput reference = drive_at(t);
    const HubInput u = input_at(t, y);
    if (const int s = force_linearization(*exact, u, y); s != GSL_SUCCESS) return s;
    const TorqueDerivatives& dtau = torque_derivatives(control_, saturated_, w.tip_row, reference, n_, w.dtau);
    const int m = state_size();
    if (aux_.count() > 0) {
        if (w.auxiliary_rows.rows() != m) {
            w.auxiliary_rows = Work::RowMatrix::Zero(m, m);
            w.auxiliary_dfdt.assign(static_cast<std::size_t>(m), 0.0);
        }
        // Their rows by y only: the time derivatives, written to a scratch, are not part of J v.
        write_auxiliary_rows({integral_, dissipated_, work_at_}, n_, m, w.dissipation, y + n_, u.tau,
                             reference.theta_dot, 0.0, dtau, w.auxiliary_rows.data(), w.auxiliary_dfdt.data());
    }
    // All k at once, as matrix products: the vectors' positions and rates are strided columns of v.
    using Strided = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
    const Strided vq(v, n_, k, Eigen::OuterStride<>(m)), vqd(v + n_, n_, k, Eigen::OuterStride<>(m));
    w.directions = Eigen::Map<const Eigen::MatrixXd>(g, n_, k);
    w.directions.noalias() += w.dQdq * vq;
    w.directions.noalias() += w.dQdqd * vqd;
    if (control_ != nullptr) {
        Eigen::RowVectorXd& dtau_v = w.dtau_v;
        dtau_v.noalias() = dtau.dq.transpose() * vq;
        dtau_v.noalias() += dtau.dqd.transpose() * vqd;
        if (integral_ >= 0) dtau_v += dtau.dz * Strided(v + integral_, 1, k, Eigen::OuterStride<>(m));
        w.directions.noalias() += w.dQdu.col(static_cast<Eigen::Index>(index(DriveValue::tau))) * dtau_v;
    }
    w.solver->solve(w.directions.data(), k);
    Eigen::Map<Eigen::MatrixXd> product(out, m, k);
    product.topRows(n_) = vqd;
    product.middleRows(n_, n_) = w.directions;
    if (m > 2 * n_)
        product.bottomRows(m - 2 * n_).noalias() =
            w.auxiliary_rows.bottomRows(m - 2 * n_) * Eigen::Map<const Eigen::MatrixXd>(v, m, k);
    return GSL_SUCCESS;
}

int FirstOrderSystem::blocks_forcing(double t, const double* y, double* dydt)
{
    std::vector<double> zeroed(static_cast<std::size_t>(size()), 0.0);
    std::copy_n(y, state_size(), zeroed.begin());
    return rhs(t, zeroed.data(), dydt);
}

int FirstOrderSystem::mass_solve(double t, const double* y, int k, double* columns)
{
    Work& w = *work_;
    if (!w.solver->prepare(input_at(t, y), y)) return w.rhs->indefinite_mass_at(y);
    w.solver->solve(columns, k);
    return GSL_SUCCESS;
}

int FirstOrderSystem::force_linearization(const ExactJacobian& exact, const HubInput& u, const double* y)
{
    Work& w = *work_;
    const double* q = y;
    const double* qd = y + n_;
    if (!w.solver->prepare(u, q)) return w.rhs->indefinite_mass_at(q);
    model_.forces(u, q, qd, w.qdd.data());
    w.solver->solve(w.qdd.data());
    exact.force_derivatives(u, q, qd, w.dQdq.data(), w.dQdqd.data(), w.dQdu.data());
    if (!model_.mass_is_constant()) {
        exact.mass_q_product(u, q, w.qdd.data(), w.dMv.data());
        w.dQdq -= w.dMv;
    }
    return GSL_SUCCESS;
}

bool FirstOrderSystem::has_mass_form() const
{
    return has_exact_jacobian() && integral_ < 0;
}

bool FirstOrderSystem::auxiliary_are_quadratures() const
{
    return integral_ < 0;
}

int FirstOrderSystem::mass_form_jacobian(double t, const double* y, double* M, double* K, double* C)
{
    ++jacobian_evaluations_;
    Work& w = *work_;
    const HubInput u = input_at(t, y);
    if (const int s = force_linearization(*model_.jacobian(), u, y); s != GSL_SUCCESS) return s;
    model_.mass(u, y, M);
    const auto size = static_cast<std::ptrdiff_t>(n_) * n_;
    std::copy_n(w.dQdq.data(), size, K);
    std::copy_n(w.dQdqd.data(), size, C);
    if (control_ != nullptr && !saturated_) {
        // The law's torque moves with the state: dQ/dtau dtau/dq joins K and dQ/dtau dtau/dqd joins C (as in
        // exact_jacobian, before M^-1). dQ/dtau is the hub's column, dtau/dq the hub angle and the tip coordinates: the
        // hub's row, which the band LU borders, gains them.
        const TorqueDerivatives& dtau = torque_derivatives(control_, saturated_, w.tip_row, drive_at(t), n_, w.dtau);
        const auto tau = static_cast<Eigen::Index>(index(DriveValue::tau));
        for (int i = 0; i < n_; ++i) {
            const double b = w.dQdu(i, tau);
            if (b == 0.0) continue;
            for (int j = 0; j < n_; ++j) {
                K[static_cast<std::ptrdiff_t>(i) * n_ + j] += b * dtau.dq[j];
                C[static_cast<std::ptrdiff_t>(i) * n_ + j] += b * dtau.dqd[j];
            }
        }
    }
    for (std::ptrdiff_t i = 0; i < size; ++i)
        if (!std::isfinite(K[i]) || !std::isfinite(C[i]) || !std::isfinite(M[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

int FirstOrderSystem::finite_difference_jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    Work& w = *work_;
    const int m = state_size();
    w.y_plus.assign(y, y + m);
    w.y_minus.assign(y, y + m);
    w.f_plus.resize(m);
    w.f_minus.resize(m);
    const double scale = std::cbrt(std::numeric_limits<double>::epsilon());
    for (int j = 0; j < m; ++j) {
        const double h = scale * std::max(std::abs(y[j]), 1e-3);
        w.y_plus[j] = y[j] + h;
        w.y_minus[j] = y[j] - h;
        if (int s = FirstOrderSystem::rhs(t, w.y_plus.data(), w.f_plus.data()); s != GSL_SUCCESS) return s;
        if (int s = FirstOrderSystem::rhs(t, w.y_minus.data(), w.f_minus.data()); s != GSL_SUCCESS) return s;
        for (int i = 0; i < m; ++i) dfdy[i * m + j] = (w.f_plus[i] - w.f_minus[i]) / (2.0 * h);
        w.y_plus[j] = w.y_minus[j] = y[j];
    }
    const double ht = scale * std::max(std::abs(t), 1.0);
    if (int s = FirstOrderSystem::rhs(t + ht, y, w.f_plus.data()); s != GSL_SUCCESS) return s;
    if (int s = FirstOrderSystem::rhs(t - ht, y, w.f_minus.data()); s != GSL_SUCCESS) return s;
    for (int i = 0; i < m; ++i) dfdt[i] = (w.f_plus[i] - w.f_minus[i]) / (2.0 * ht);
    return GSL_SUCCESS;
}

}  // namespace hubbeam
