// Forward sensitivities integrated beside the state (sensitivity.hpp).
#include "simulation/sensitivity.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <gsl/gsl_errno.h>
#include <stdexcept>

#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include "linalg/factorizations.hpp"
#include "models/model_operations.hpp"

namespace hubbeam {

/// One parameter p_j: a physical one (Param) or a control gain. The system integrates sigma_j = pbar_j s_j with pbar_j
/// = |p_j| (1 where p_j = 0): in the state's units, so that the run's tolerances control it as they control the state
/// (as CVODES scales by its pbar).
struct SensitivitySystem::Parameter {
    std::string name;
    bool gain = false;
    Param param = Param::L;
    std::size_t gain_index = 0;
    double scale = 1.0;
    // Where the model has no generated derivatives: models at p_j -+ h, differenced.
    std::unique_ptr<Model> down, up;
    double h = 0.0;
    // With Rayleigh damping: d(damping_matrix)/dp_j, for the dissipated energy's rate qd^T C qd (empty without).
    Eigen::MatrixXd dC;
};

struct SensitivitySystem::Work {
    using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMatrix J, M, dM, other;
    Eigen::MatrixXd R;               // the forcing r_j of each parameter, a column each (nq x count)
    std::vector<char> forced;        // whether parameter j has a forcing at this state (a saturated gain has none)
    std::vector<double> work_rates;  // the hub's work's rate's derivative by gain j
    Eigen::VectorXd dfdt, dQ, other_Q, y_plus, y_minus, f_plus, f_minus;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    // The physical parameters' derivatives of M and Q at the right-hand side's state, from one call of the model's
    // derivatives_p (where it has them): the parameters, each one's place among them (-1: a gain), and the results.
    std::vector<Param> derived;
    std::vector<int> derived_at;
    std::vector<double> dMs, dQs;
};

namespace {

/// The index of a gain's name in gain_names.
std::size_t gain_index(const std::string& name)
{
    return static_cast<std::size_t>(std::find(gain_names.begin(), gain_names.end(), name) - gain_names.begin());
}

}  // namespace

SensitivitySystem::SensitivitySystem(const Model& model, const Scene& scene)
    : FirstOrderSystem(model, scene.motion, scene.axial, scene.controller(), &scene.parameters, scene.wants({"ki"})),
      model_(model),
      scene_(scene),
      controlled_(scene.solver.sensitivity_error_control == SensitivityErrorControl::on),
      work_(std::make_unique<Work>())
{
    if (scene.control && scene.control->law)
        throw std::invalid_argument(
            "--sensitivities: expected a scene whose torque is its [control]'s law or its "
            "motion, got a torque law given as code (its derivatives are unknown)");
    if (scene.axial != Axial::dynamic)
        throw std::invalid_argument("--sensitivities: expected model.axial \"dynamic\", got \"quasi-static\"");
    const std::vector<double> packed = scene.parameters.packed();
    for (const std::string& name : scene.output.sensitivities) {
        auto p = std::make_unique<Parameter>();
        p->name = name;
        if (const std::size_t g = gain_index(name); g < gain_names.size()) {
            p->gain = true;
            p->gain_index = g;
            const Control& c = *scene.control;
            const double values[] = {c.kp, c.kd, c.ki, c.k_tip};
            p->scale = values[g] != 0.0 ? std::abs(values[g]) : 1.0;
        } else {
            const auto at = std::find(param_names.begin(), param_names.end(), name);
            if (at == param_names.end()) throw std::invalid_argument("--sensitivities: unknown parameter " + name);
            p->param = static_cast<Param>(at - param_names.begin());
            const double v = packed[index(p->param)];
            p->scale = v != 0.0 ? std::abs(v) : 1.0;
            const bool generated = model.parameter_derivatives() != nullptr, damped = dissipated_index() >= 0;
            if (!generated || damped) {
                // Models at p_j -+ h, h = 1e-6 of the value (an error of 1e-12 relative to the curvature's, round-off
                // of 1e-10): differenced for df/dp where there are no generated derivatives (the assembled path,
                // order full's quadrature sums), and for the damping matrix's derivative (C is linear in alpha and
                // beta, smooth in the others; once per run).
                p->h = 1e-6 * p->scale;
                Parameters down = scene.parameters, up = scene.parameters;
                value(down, p->param) -= p->h;
                value(up, p->param) += p->h;
                std::unique_ptr<Model> model_down = make_model(model.key(), down, scene.source);
                std::unique_ptr<Model> model_up = make_model(model.key(), up, scene.source);
                if (damped) p->dC = (damping_matrix(*model_up, up) - damping_matrix(*model_down, down)) / (2.0 * p->h);
                if (!generated) {
                    p->down = std::move(model_down);
                    p->up = std::move(model_up);
                }
            }
        }
        parameters_.push_back(std::move(p));
    }
    const int n = state_size(), nq = model.nq();
    work_->J.resize(n, n);
    work_->dfdt.resize(n);
    work_->M.resize(nq, nq);
    work_->dM.resize(nq, nq);
    work_->other.resize(nq, nq);
    work_->dQ.resize(nq);
    work_->other_Q.resize(nq);
    for (Eigen::VectorXd* v : {&work_->y_plus, &work_->y_minus, &work_->f_plus, &work_->f_minus}) v->resize(n);
    work_->R.resize(nq, count());
    work_->forced.resize(static_cast<std::size_t>(count()));
    work_->work_rates.resize(static_cast<std::size_t>(count()));
    for (const auto& p : parameters_) {
        work_->derived_at.push_back(p->gain ? -1 : static_cast<int>(work_->derived.size()));
        if (!p->gain) work_->derived.push_back(p->param);
    }
    work_->dMs.resize(work_->derived.size() * static_cast<std::size_t>(nq) * nq);
    work_->dQs.resize(work_->derived.size() * static_cast<std::size_t>(nq));
    set_dimension(size());
}

SensitivitySystem::~SensitivitySystem() = default;

double SensitivitySystem::scale(int j) const
{
    return parameters_[static_cast<std::size_t>(j)]->scale;
}

bool SensitivitySystem::forcing(int j, const double* y, const double* qdd_at, const HubInput& u,
                                const HubInput& reference, double* r_at, double& work_rate) const
{
    const Parameter& p = *parameters_[static_cast<std::size_t>(j)];
    Work& w = *work_;
    const int nq = model_.nq();
    const double* q = y;
    const double* qd = y + nq;
    Eigen::Map<Eigen::VectorXd> r(r_at, nq);
    const Eigen::Map<const Eigen::VectorXd> qdd(qdd_at, nq);
    work_rate = 0.0;
    if (p.gain) {
        const Control& c = *control();
        const Tip tip = model_.tip(q);
        const HubState s{q[0], qd[0], tip.uy, model_.tip(qd).uy};
        const double z = integral_index() >= 0 ? y[integral_index()] : 0.0;
        const double unclipped = c.unclipped(s, z, reference);
        if (std::abs(unclipped) > c.tau_max) return false;  // saturated: the torque does not move with the gain
        const double dtau[] = {-(s.theta - reference.theta), -(s.theta_dot - reference.theta_dot), -z, -s.tip_uy};
        r.setZero();
        r[0] = dtau[p.gain_index];  // Q = tau e_theta + ...
        // The hub's work, z' = tau theta_dot, moves with the gain too.
        if (work_index() >= 0) work_rate = p.scale * s.theta_dot * dtau[p.gain_index];
    } else if (model_.parameter_derivatives() != nullptr) {
        const int at = w.derived_at[static_cast<std::size_t>(j)];
        const Eigen::Map<const Work::RowMatrix> dM(w.dMs.data() + static_cast<std::ptrdiff_t>(at) * nq * nq, nq, nq);
        const Eigen::Map<const Eigen::VectorXd> dQ(w.dQs.data() + static_cast<std::ptrdiff_t>(at) * nq, nq);
        r = dQ - dM * qdd;
    } else {
        p.up->mass(u, q, w.dM.data());
        p.down->mass(u, q, w.other.data());
        p.up->forces(u, q, qd, w.dQ.data());
        p.down->forces(u, q, qd, w.other_Q.data());
        r = ((w.dQ - w.other_Q) - (w.dM - w.other) * qdd) / (2.0 * p.h);
    }
    return true;
}

int SensitivitySystem::product_by_differences(double t, const double* y, int j, double* out_at)
{
    Work& w = *work_;
    const int n = state_size();
    const Eigen::Map<const Eigen::VectorXd> sigma(y + n * (1 + j), n);
    Eigen::Map<Eigen::VectorXd> out(out_at, n);
    const double size = sigma.lpNorm<Eigen::Infinity>();
    if (size == 0.0) {
        out.setZero();
        return GSL_SUCCESS;
    }
    double y_size = 1.0;
    for (int i = 0; i < n; ++i) y_size = std::max(y_size, std::abs(y[i]));
    // A step of eps^(1/3) of y's size balances the difference's truncation and round-off.
    const double e = 6e-6 * y_size / size;
    w.y_plus = Eigen::Map<const Eigen::VectorXd>(y, n) + e * sigma;
    w.y_minus = Eigen::Map<const Eigen::VectorXd>(y, n) - e * sigma;
    if (const int s = FirstOrderSystem::rhs(t, w.y_plus.data(), w.f_plus.data()); s != GSL_SUCCESS) return s;
    if (const int s = FirstOrderSystem::rhs(t, w.y_minus.data(), w.f_minus.data()); s != GSL_SUCCESS) return s;
    out = (w.f_plus - w.f_minus) / (2.0 * e);
    return GSL_SUCCESS;
}

int SensitivitySystem::state_and_forcings(double t, const double* y, double* dydt)
{
    if (const int s = FirstOrderSystem::rhs(t, y, dydt); s != GSL_SUCCESS) return s;
    Work& w = *work_;
    const int nq = model_.nq(), k = count();
    // The model's input at this state, as the state's own equations had it.
    const HubInput reference = scene_.motion.at(t);
    const HubInput u = input_at(t, y);
    // sigma_j' = J sigma_j + (0, M^-1 r_j, ...) times p_j's scale, r_j = dQ/dp_j - dM/dp_j qdd (forcing).
    if (const ParameterDerivatives* d = model_.parameter_derivatives(); d != nullptr && !w.derived.empty())
        d->derivatives_p(w.derived.data(), static_cast<int>(w.derived.size()), nq, u, y, y + nq, w.dMs.data(),
                         w.dQs.data());
    for (int j = 0; j < k; ++j)
        w.forced[static_cast<std::size_t>(j)] =
            forcing(j, y, dydt + nq, u, reference, w.R.col(j).data(), w.work_rates[static_cast<std::size_t>(j)]);
    // A gain's forcing writes nothing while the torque saturates: its column is zeroed, not scaled by zero, for what
    // it held may be anything (at the first right-hand side the heap's bytes: NaN times zero stopped a run at t = 0).
    if (has_exact_jacobian())
        for (int j = 0; j < k; ++j) {
            if (w.forced[static_cast<std::size_t>(j)]) w.R.col(j) *= scale(j);
            else w.R.col(j).setZero();
        }
    return GSL_SUCCESS;
}

int SensitivitySystem::finish_rates(const double* y, double* dydt) const
{
    const Work& w = *work_;
    const int n = state_size(), nq = model_.nq();
    for (int j = 0; j < count(); ++j) {
        const Parameter& p = *parameters_[static_cast<std::size_t>(j)];
        double* out = dydt + n * (1 + j);
        if (!w.forced[static_cast<std::size_t>(j)]) continue;
        if (p.gain && work_index() >= 0) out[work_index()] += w.work_rates[static_cast<std::size_t>(j)];
        if (p.dC.size() > 0) {
            // the dissipated energy's rate qd^T C qd moves with C's parameters
            const Eigen::Map<const Eigen::VectorXd> rates(y + nq, nq);
            out[dissipated_index()] += p.scale * rates.dot(p.dC * rates);
        }
    }
    for (int i = 0; i < size(); ++i)
        if (!std::isfinite(dydt[i])) return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

int SensitivitySystem::rhs(double t, const double* y, double* dydt)
{
    if (const int s = state_and_forcings(t, y, dydt); s != GSL_SUCCESS) return s;
    Work& w = *work_;
    const int n = state_size(), nq = model_.nq(), k = count();
    // J sigma_j: exact products from one linearization of the forces, with the forcing's solves, where the model
    // has derivative kernels (jacobian_product); else by the Jacobian when forming it costs less than two
    // evaluations of f per parameter, or by central differences of f along sigma_j (as CVODES does by default),
    // accurate to about 1e-10 of f: far below the tolerances.
    if (has_exact_jacobian()) {
        if (const int s = jacobian_product(t, y, k, y + n, w.R.data(), dydt + n); s != GSL_SUCCESS) return s;
    } else {
        const bool formed = 2 * k >= n;
        if (formed)
            if (const int s = FirstOrderSystem::jacobian(t, y, w.J.data(), w.dfdt.data()); s != GSL_SUCCESS) return s;
        model_.mass(input_at(t, y), y, w.M.data());
        w.lu.compute(w.M);
        for (int j = 0; j < k; ++j) {
            Eigen::Map<Eigen::VectorXd> out(dydt + n * (1 + j), n);
            if (formed)
                out.noalias() = w.J * Eigen::Map<const Eigen::VectorXd>(y + n * (1 + j), n);
            else if (const int s = product_by_differences(t, y, j, out.data()); s != GSL_SUCCESS)
                return s;
            if (w.forced[static_cast<std::size_t>(j)]) out.segment(nq, nq) += scale(j) * w.lu.solve(w.R.col(j));
        }
    }
    return finish_rates(y, dydt);
}

int SensitivitySystem::blocks_forcing(double t, const double* y, double* dydt)
{
    if (!has_exact_jacobian()) return FirstOrderSystem::blocks_forcing(t, y, dydt);
    if (const int s = state_and_forcings(t, y, dydt); s != GSL_SUCCESS) return s;
    Work& w = *work_;
    const int n = state_size(), nq = model_.nq(), k = count();
    if (const int s = mass_solve(t, y, k, w.R.data()); s != GSL_SUCCESS) return s;
    for (int j = 0; j < k; ++j) {
        double* out = dydt + n * (1 + j);
        std::fill_n(out, n, 0.0);
        std::copy_n(w.R.col(j).data(), nq, out + nq);
    }
    return finish_rates(y, dydt);
}

int SensitivitySystem::jacobian(double t, const double* y, double* dfdy, double* dfdt)
{
    const int n = state_size(), m = size();
    Work& w = *work_;
    if (const int s = FirstOrderSystem::jacobian(t, y, w.J.data(), w.dfdt.data()); s != GSL_SUCCESS) return s;
    std::fill_n(dfdy, static_cast<std::size_t>(m) * m, 0.0);
    std::fill_n(dfdt, m, 0.0);
    for (int b = 0; b <= count(); ++b)
        for (int i = 0; i < n; ++i)
            std::copy_n(w.J.data() + static_cast<std::ptrdiff_t>(i) * n, n,
                        dfdy + static_cast<std::ptrdiff_t>(b * n + i) * m + b * n);
    std::copy_n(w.dfdt.data(), n, dfdt);
    // The blocks below the diagonal, d(J sigma_j + df/dp_j)/dy, by central differences of the sensitivity rows over
    // the state: they hold the parameter's derivative of the stiffness (E's, L's), as stiff as the state's own J,
    // and an iteration without them diverges unless the steps resolve the stiff modes.
    if (count() > 0) {
        std::vector<double> ya(y, y + m), fp(static_cast<std::size_t>(m)), fm(fp);
        for (int i = 0; i < n; ++i) {
            const double h = 1e-6 * std::max(std::abs(y[i]), 1e-3);
            ya[static_cast<std::size_t>(i)] = y[i] + h;
            if (const int s = rhs(t, ya.data(), fp.data()); s != GSL_SUCCESS) return s;
            ya[static_cast<std::size_t>(i)] = y[i] - h;
            if (const int s = rhs(t, ya.data(), fm.data()); s != GSL_SUCCESS) return s;
            ya[static_cast<std::size_t>(i)] = y[i];
            for (int r = n; r < m; ++r)
                dfdy[static_cast<std::ptrdiff_t>(r) * m + i] =
                    (fp[static_cast<std::size_t>(r)] - fm[static_cast<std::size_t>(r)]) / (2.0 * h);
        }
    }
    return GSL_SUCCESS;
}

namespace {

/// A tip's displacements in tip_values' order.
std::array<double, std::size(tip_values)> values_of(const Tip& t)
{
    std::array<double, std::size(tip_values)> v{};
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = t.*tip_values[k].member;
    return v;
}

}  // namespace

void SensitivitySystem::outputs(double t, const double* y, double* out)
{
    (void)t;
    const int n = state_size(), nq = model_.nq();
    const bool torque = model_.key().drive == Drive::torque;
    const int stride = static_cast<int>(sensitivity_outputs_of(model_.key()).size());
    std::vector<double> plus(static_cast<std::size_t>(nq)), minus(plus);
    for (int j = 0; j < count(); ++j) {
        const Parameter& p = *parameters_[static_cast<std::size_t>(j)];
        const double* sigma = y + n * (1 + j);
        double* o = out + j * stride;
        o[0] = torque ? sigma[0] / p.scale : 0.0;
        o[1] = torque ? sigma[nq] / p.scale : 0.0;
        // The tip is at most quadratic in q: a central difference along sigma is exact at any step; a unit step
        // keeps its round-off at that of the tip itself.
        double big = 0.0;
        for (int i = 0; i < nq; ++i) big = std::max(big, std::abs(sigma[i]));
        std::array<double, std::size(tip_values)> d{};  // the tip's, in tip_values' order
        if (big > 0.0) {
            for (int i = 0; i < nq; ++i) {
                plus[static_cast<std::size_t>(i)] = y[i] + sigma[i] / big;
                minus[static_cast<std::size_t>(i)] = y[i] - sigma[i] / big;
            }
            const auto a = values_of(model_.tip(plus.data())), b = values_of(model_.tip(minus.data()));
            for (std::size_t k = 0; k < d.size(); ++k) d[k] = (a[k] - b[k]) / 2.0 * big / p.scale;
        }
        if (!p.gain) {  // the tip's own dependence on the parameter (a slope coordinate's scale)
            const ParameterDerivatives* pd = model_.parameter_derivatives();
            const auto a = values_of(pd ? pd->tip_p(p.param, y) : p.up->tip(y));
            const auto b = values_of(pd ? Tip{} : p.down->tip(y));
            const double step = pd ? 1.0 : 2.0 * p.h;
            for (std::size_t k = 0; k < d.size(); ++k) d[k] += (a[k] - b[k]) / step;
        }
        // In sensitivity_outputs_of's order: the tip's values the variant has.
        int next = static_cast<int>(std::size(sensitivity_outputs));
        for (std::size_t k = 0; k < d.size(); ++k)
            if (has_tip_value(model_.key(), tip_values[k])) o[next++] = d[k];
    }
}

}  // namespace hubbeam
