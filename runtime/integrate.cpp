// FirstOrderSystem: mass solve per evaluation (or one factorization for a constant M) and GSL glue.
#include "integrate.hpp"

#include <array>
#include <cmath>
#include <limits>

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
    Eigen::MatrixXd M;
    Eigen::VectorXd Q, qdd;
    Eigen::LLT<Eigen::MatrixXd> llt;
    bool factored_once = false;
    std::vector<double> y_plus, y_minus, f_plus, f_minus;
    // Exact Jacobian: row-major like the kernels (RowMajor maps them as written).
    using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMatrix dQdq, dQdqd, dQdu, dMv;
};

FirstOrderSystem::FirstOrderSystem(const Model& model, const Motion& motion)
    : model_(model), motion_(motion), n_(model.nq()), work_(std::make_unique<Work>())
{
    work_->M.resize(n_, n_);
    work_->Q.resize(n_);
    work_->qdd.resize(n_);
    work_->dQdq.resize(n_, n_);
    work_->dQdqd.resize(n_, n_);
    work_->dQdu.resize(n_, static_cast<Eigen::Index>(drive_value_count));
    work_->dMv.resize(n_, n_);
    sys_ = {gsl_rhs, gsl_jacobian, static_cast<std::size_t>(2 * n_), this};
}

FirstOrderSystem::~FirstOrderSystem() = default;

int FirstOrderSystem::rhs(double t, const double* y, double* dydt)
{
    ++evaluations_;
    Work& w = *work_;
    const HubInput u = motion_.at(t);
    const double* q = y;
    const double* qd = y + n_;
    if (int s = factor_mass(u, q); s != GSL_SUCCESS) return s;
    model_.forces(u, q, qd, w.Q.data());
    w.qdd = w.llt.solve(w.Q);
    for (int i = 0; i < n_; ++i) {
        dydt[i] = qd[i];
        dydt[n_ + i] = w.qdd[i];
        if (!std::isfinite(dydt[n_ + i])) return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

int FirstOrderSystem::factor_mass(const HubInput& u, const double* q)
{
    Work& w = *work_;
    if (w.factored_once) return GSL_SUCCESS;
    // Eigen is column-major and the kernel writes row-major: M is symmetric, so the transpose is M.
    model_.mass(u, q, w.M.data());
    w.llt.compute(w.M);
    if (w.llt.info() != Eigen::Success) return GSL_EBADFUNC;
    w.factored_once = model_.mass_is_constant();
    return GSL_SUCCESS;
}

int FirstOrderSystem::jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    ++jacobian_evaluations_;
    return model_.has_jacobian() ? exact_jacobian(t, y, dfdy, dfdt) : finite_difference_jacobian(t, y, dfdy, dfdt);
}

int FirstOrderSystem::exact_jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    // y = (q, qd), f = (qd, qdd) with M(q) qdd = Q(t, q, qd) (docs/model.md section 5.1). Differentiating
    // M qdd = Q: M dqdd/dq = dQ/dq - (dM/dq) qdd, M dqdd/dqd = dQ/dqd, M dqdd/dt = dQ/du du/dt (M depends on
    // neither u nor qd; the generator checks). So dfdy = [[0, I], [M^-1 (dQ/dq - (dM/dq) qdd), M^-1 dQ/dqd]].
    Work& w = *work_;
    const HubInput u = motion_.at(t);
    const double* q = y;
    const double* qd = y + n_;
    if (int s = factor_mass(u, q); s != GSL_SUCCESS) return s;
    model_.forces(u, q, qd, w.Q.data());
    w.qdd = w.llt.solve(w.Q);
    model_.force_derivatives(u, q, qd, w.dQdq.data(), w.dQdqd.data(), w.dQdu.data());
    if (!model_.mass_is_constant()) {
        model_.mass_q_product(u, q, w.qdd.data(), w.dMv.data());
        w.dQdq -= w.dMv;
    }
    const Eigen::MatrixXd lower_q = w.llt.solve(Eigen::MatrixXd(w.dQdq));
    const Eigen::MatrixXd lower_qd = w.llt.solve(Eigen::MatrixXd(w.dQdqd));
    const std::array<double, drive_value_count> du = motion_.rate(t).packed();
    const Eigen::VectorXd dudt = Eigen::Map<const Eigen::VectorXd>(du.data(), static_cast<Eigen::Index>(du.size()));
    const Eigen::VectorXd lower_t = w.llt.solve(w.dQdu * dudt);
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
