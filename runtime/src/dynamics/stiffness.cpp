// Stiffness from the generalized eigenvalues of the stiffness and mass matrices at rest.
#include "dynamics/stiffness.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "linalg/eigen_solvers.hpp"
#include "linalg/factorizations.hpp"
#include "models/model_operations.hpp"

namespace hubbeam {

namespace {

/// -dQ/dq at (u, q, qd) (exact by differences too for the linear restoring forces about the straight beam, where it
/// is used).
Eigen::MatrixXd stiffness(const Model& model, const HubInput& u, const std::vector<double>& q,
                          const std::vector<double>& qd)
{
    return -force_q_jacobian(model, u, q, qd);
}

/// M at rest (symmetric: row- or column-major alike).
Eigen::MatrixXd mass_at_rest(const Model& model)
{
    const std::vector<double> zero(static_cast<std::size_t>(model.nq()), 0.0);
    Eigen::MatrixXd M(model.nq(), model.nq());
    model.mass(HubInput{}, zero.data(), M.data());
    return M;
}

/// omega^2 of K x = omega^2 M x at rest, no spin, ascending, with K = -dQ/dq symmetrized, the integrated
/// coordinates only (with quasi-static axial coordinates their rows and columns are left out); empty when M is not
/// positive definite.
Eigen::VectorXd squared_frequencies(const Model& model, Axial axial)
{
    const std::vector<double> zero(static_cast<std::size_t>(model.nq()), 0.0);
    const std::vector<int> kept = kept_coordinates(model.coordinates(), axial);
    const Eigen::MatrixXd K = stiffness(model, HubInput{}, zero, zero)(kept, kept);
    const Eigen::MatrixXd M = mass_at_rest(model)(kept, kept);
    const SymmetricPairs solver = symmetric_pairs(0.5 * (K + K.transpose()), M, false);
    if (!solver.converged) return {};
    return solver.values;
}

/// The highest frequency of squared frequencies w2 (squared_frequencies): infinite where M is not positive definite.
double highest_of(const Eigen::VectorXd& w2)
{
    if (w2.size() == 0) return INFINITY;  // M not positive definite: treat as stiff
    return std::sqrt(std::max(0.0, w2.maxCoeff()));
}

/// The lowest positive frequency of squared frequencies w2. The hub angle under torque is a rigid mode (zero
/// frequency): the lowest vibration is the first above it.
double lowest_of(const Eigen::VectorXd& w2)
{
    for (const double v : w2)
        if (v > 1e-9 * w2.maxCoeff()) return std::sqrt(v);
    return 0.0;
}

}  // namespace

double highest_frequency(const Model& model, Axial axial)
{
    return highest_of(squared_frequencies(model, axial));
}

namespace {

/// RatesAtRest::omega_max of a model whose highest frequency is omega.
double highest_rate(const Model& model, Axial axial, double omega)
{
    const int n = model.nq();
    const std::vector<double> zero(static_cast<std::size_t>(n), 0.0);
    const HubInput rest;
    const ForceJacobians J = force_jacobians(model, rest, zero, zero);
    if (J.qd.isZero(0.0)) return omega;  // undamped: the rates are the frequencies
    // Damped: the eigenvalues of the first-order system x' = [[0, I], [M^-1 dQ/dq, M^-1 dQ/dqd]] x at rest, kept
    // coordinates only. Stiffness-proportional damping turns the stiff axial modes into fast real decays of rate
    // about beta omega^2, which bound an explicit step as a frequency does.
    const std::vector<int> kept = kept_coordinates(model.coordinates(), axial);
    const auto m = static_cast<Eigen::Index>(kept.size());
    const Eigen::MatrixXd Mk = mass_at_rest(model)(kept, kept), Kq = J.q(kept, kept), Kqd = J.qd(kept, kept);
    const Eigen::LDLT<Eigen::MatrixXd> solve(Mk);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    A.topRightCorner(m, m).setIdentity();
    A.bottomLeftCorner(m, m) = solve.solve(Kq);
    A.bottomRightCorner(m, m) = solve.solve(Kqd);
    const EigenPairs eig = eigen_pairs(A, false);
    if (!eig.converged) return INFINITY;
    return std::max(omega, eig.values.cwiseAbs().maxCoeff());
}

}  // namespace

RatesAtRest rates_at_rest(const Model& model, Axial axial)
{
    const Eigen::VectorXd w2 = squared_frequencies(model, axial);  // once for both
    return {highest_rate(model, axial, highest_of(w2)), lowest_of(w2)};
}

namespace {

/// -dQ/dq at rest, spinning steadily at omega, symmetrized, the beam's rows alone: the cyclic hub angle and a moving
/// hub's translation (a free-floating hub has no stiffness) left out.
Eigen::MatrixXd spinning_stiffness(const Model& model, double omega)
{
    const int n = model.nq(), first = model.coordinates().first_beam();
    HubInput u;
    std::vector<double> q(static_cast<std::size_t>(n), 0.0), qd(q);
    if (model.key().drive == Drive::torque)
        qd[0] = omega;
    else
        u.theta_dot = omega;
    const int m = n - first;
    const Eigen::MatrixXd K = stiffness(model, u, q, qd).bottomRightCorner(m, m);
    return 0.5 * (K + K.transpose());
}

bool positive_definite(const Eigen::MatrixXd& K)
{
    return Eigen::LLT<Eigen::MatrixXd>(K).info() == Eigen::Success;
}

}  // namespace

double critical_spin(const Model& model)
{
    constexpr double hi = 1000.0;
    const Eigen::MatrixXd K0 = spinning_stiffness(model, 0.0), Khi = spinning_stiffness(model, hi);
    if (positive_definite(Khi)) return INFINITY;
    if (!positive_definite(K0)) return 0.0;
    // At rest the forces are quadratic in the velocities (the kinetic energy is), and the elastic ones are still:
    // K(omega) = K0 + omega^2 D. It stops being positive definite where 1 + omega^2 mu = 0 for the most negative mu
    // of D x = mu K0 x: one eigenproblem in place of a bisection's sixty factorizations. Checked at the bound, so
    // that a term whose forces at rest depended on the rate otherwise would fail its tests here.
    const Eigen::MatrixXd D = spinning_stiffness(model, 1.0) - K0;
    const double scale = std::max(K0.cwiseAbs().maxCoeff(), Khi.cwiseAbs().maxCoeff());
    const SymmetricPairs solver = symmetric_pairs(D, K0, false);
    const double mu = solver.converged ? solver.values.minCoeff() : 0.0;
    if ((K0 + hi * hi * D - Khi).cwiseAbs().maxCoeff() > 1e-9 * scale || !(mu < 0.0))
        throw std::logic_error(model.key().name() + ": the stiffness at rest is not quadratic in the hub's rate");
    return std::min(hi, std::sqrt(-1.0 / mu));
}

bool needs_pilot(const Model& model, double rtol)
{
    // Where M's condition number passes 1e10 the round-off in the accelerations (1e-6 of them) rings in the undamped
    // stiff modes and grows through the run, which the start does not show: BIM at Ny = 16 under torque (cond(M)
    // 2e12) took 3.5 times its pilot's extrapolated steps. There the rule, which assumes the stiff modes resolved,
    // is the safer prediction. The meshes the pilot serves stay far below (FEM and BSIM at Ny = 32: 1e8 to 4e8).
    constexpr double condition_limit = 1e10;
    return model.key().drive == Drive::torque && rtol >= gauss4_tightest_rtol &&
           mass_condition(model) < condition_limit;
}

PilotPlan pilot_plan(const StepperCosts& c, double t_end)
{
    // Half the lowest period covers the phases of the motion accuracy follows; a thirtieth of the run keeps the
    // pilot's cost within a few per cent of the run's. gauss4's first steps grow from h0: a few dozen steps more.
    const double t = std::min(t_end, std::max(t_end / 30.0, c.omega_1 > 0.0 ? std::numbers::pi / c.omega_1 : 0.0));
    const double break_even = c.rk8pd / c.gauss4_step * (t / t_end);
    return {t, static_cast<long>(std::min(break_even, 1e12)) + 30};
}

double pilot_extrapolated_steps(const Pilot& pilot, double t_end)
{
    const double second_half = static_cast<double>(pilot.steps - pilot.steps_to_half);
    return static_cast<double>(pilot.steps) + second_half / (0.5 * pilot.t) * (t_end - pilot.t);
}

bool pilot_lost(const Pilot& pilot, const StepperCosts& c, double t_end)
{
    if (c.gauss4 < c.rk8pd) return false;
    constexpr double thinning = 0.7;
    const auto first_half = static_cast<double>(pilot.steps_to_half);
    const auto second_half = static_cast<double>(pilot.steps - pilot.steps_to_half);
    return !(second_half < thinning * first_half && pilot.steps <= pilot_plan(c, t_end).budget);
}

StepperCosts predicted_costs(const Model& model, Axial axial, double rtol, double t_end, int auxiliary,
                             const Pilot* pilot, const RatesAtRest* rates)
{
    StepperCosts c;
    const RatesAtRest r = rates != nullptr ? *rates : rates_at_rest(model, axial);
    c.omega_max = r.omega_max;
    c.omega_1 = r.omega_1;
    const double m = 2.0 * static_cast<double>(kept_coordinates(model.coordinates(), axial).size());
    // Steps: rk8pd's the more of accuracy (order 8: h omega_1 = 0.077 at rtol 1e-8, the paper's spin-up with AMM at
    // Ny = 4) and stability (h omega_max = 3.1: stability_step_factor). gauss4's what accuracy needs (order 4:
    // h omega_1 = 0.073 at rtol 1e-8, same scene), twice that for the stiff modes its step doubling sees excited
    // under a prescribed rotation, which starts and ends smoothly (AMM 1 to 1.9 times, BSIM and FEM 1.8, the four
    // methods at Ny 4 to 16, Nx 0 and Ny, rtol 1e-8). A hub torque excites the highest bending modes of FEM, BIM and
    // BSIM, modes of the discretization, and gauss4 must then resolve them as an explicit step must (at Nx = 0 it
    // took 0.3 to 1.6 times rk8pd's steps); AMM's are the cantilever's own modes, whose response to the hub falls off
    // fast (Ny = 16: 3984 steps against rk8pd's 19194), and the axial modes, which the torque reaches only through
    // the centrifugal coupling, stay quiet in every method. That rule is only the fallback: a run under a hub torque
    // measures gauss4's steps with a pilot (needs_pilot), for whether gauss4 must resolve the excited modes depends on
    // how much the torque excites them (FEM Ny = 32: 35,000 steps where the rule predicted rk8pd's 124,000).
    const double scale = rtol / 1e-8;
    const double accuracy8 = t_end * c.omega_1 / (0.077 * std::pow(scale, 1.0 / 8.0));
    const double stability8 = t_end * c.omega_max / stability_step_factor("rk8pd");
    c.steps_rk8pd = std::max(accuracy8, stability8);
    c.stability_bound = stability8 > accuracy8;
    c.steps_gauss4 = 2.0 * t_end * c.omega_1 / (0.073 * std::pow(scale, 1.0 / 5.0));
    if (pilot != nullptr) {
        c.steps_gauss4 = pilot->failed || pilot->t <= 0.0
                             ? INFINITY
                             : pilot_extrapolated_steps(*pilot, t_end) * std::pow(pilot->rtol / rtol, 0.2);
    } else if (model.key().drive == Drive::torque && model.key().method != Method::amm) {
        c.steps_gauss4 = std::max(
            c.steps_gauss4, t_end * highest_frequency(model, Axial::quasi_static) / stability_step_factor("rk8pd"));
    }
    // Cost per step in flops, with a right-hand side of about 4 m^2 (the folded or dense products over m states):
    // rk8pd's 13 evaluations; gauss4's about 15 evaluations and 10 solves with its factored Newton matrices, and
    // every fourth step their two factorizations (2 x 2/3 n^3), n = m where the Newton systems condense to the
    // velocities (no auxiliary states), else 2m (measured on the paper's spin-up: 14.7 evaluations, a Jacobian
    // every 5.3 steps; since gauss4 keeps its step sizes, the spin-up refactors every few dozen steps, a torque run on
    // a fine mesh still every five or so: the model keeps the conservative every fourth, which the grids of
    // docs/performance.md were measured with).
    // gauss4 also pays a step's bookkeeping of three stage solves (dynamic-size vector operations, the interpolation
    // of starting values, the convergence tests): about 25,000 flops' time, measured as its time per step against
    // rk8pd's at Ny = 8 and 16 with Nx = 0 on the spin-up (3 to 4.5 times rk8pd's, where the flops alone said 1.7).
    constexpr double gauss4_step_overhead = 25000.0;
    // Order full's right-hand side pays the foreshortening's squares: expanded, of order Ny^4 terms (about order
    // first's cost at Ny = 4); from Ny = 8 summed at some 4 Ny + 16 Gauss points, 18 to 40 times order first's at
    // Ny = 8 (rk8pd's runs of the spin-up at Nx = 0, the four methods), taken as 25.
    const int ny = model.coordinates().count(FieldKind::inplane);
    const double full = model.key().order != Order::full ? 1.0 : ny >= 8 ? 25.0 : std::max(1.0, std::pow(ny / 4.0, 4));
    const double rhs = 4.0 * m * m * full;
    const double n = auxiliary == 0 ? m : 2.0 * (m + auxiliary);
    c.rk8pd = c.steps_rk8pd * 13.0 * rhs;
    // A pilot that factored banded Newton matrices (gauss4's mass form) prices its solves and factorizations.
    const bool banded = pilot != nullptr && pilot->band_factor_flops > 0.0;
    const double solve = banded ? pilot->band_solve_flops : 2.0 * n * n;
    const double factor = banded ? pilot->band_factor_flops : 2.0 / 3.0 * n * n * n;
    c.gauss4_step = 15.0 * rhs + 10.0 * solve + 2.0 * factor / 4.0 + gauss4_step_overhead;
    c.gauss4 = c.steps_gauss4 * c.gauss4_step;
    return c;
}

StepperChoice automatic_stepper(const Model& model, Axial axial, double rtol, double t_end, int auxiliary,
                                const Pilot* pilot, const RatesAtRest* rates)
{
    const StepperCosts c = predicted_costs(model, axial, rtol, t_end, auxiliary, pilot, rates);
    // Below rtol 1e-10 gauss4's step doubling compares results that agree to round-off, amplified by cond(M) under a
    // hub torque (2.5e5 for the paper's FEM beam with axial coordinates: its steps collapse at rtol 1e-11): rk8pd,
    // whatever it costs.
    const bool implicit = c.gauss4 < c.rk8pd && rtol >= gauss4_tightest_rtol;
    std::string pilot_note;
    if (pilot != nullptr) {
        char text[120];
        if (pilot->failed)
            std::snprintf(text, sizeof text, ": its pilot failed at t = %.3g s", pilot->t);
        else
            std::snprintf(text, sizeof text, ", from %ld in a pilot to t = %.3g s, %ld in its second half",
                          pilot->steps, pilot->t, pilot->steps - pilot->steps_to_half);
        pilot_note = text;
    }
    char why[440];
    if (c.gauss4 < c.rk8pd && !implicit) {
        std::snprintf(why, sizeof why,
                      "automatic: rtol %g is below gauss4's %g, where its error estimate meets "
                      "round-off",
                      rtol, gauss4_tightest_rtol);
        return {"rk8pd", why};
    }
    std::snprintf(
        why, sizeof why,
        "automatic: predicted %.2g flops against %.2g for %s (rk8pd about %.0f steps, %s; gauss4 about %.0f%s; "
        "highest rate %.0f 1/s, lowest frequency %.3g rad/s)",
        implicit ? c.gauss4 : c.rk8pd, implicit ? c.rk8pd : c.gauss4, implicit ? "rk8pd" : "gauss4", c.steps_rk8pd,
        c.stability_bound ? "bound by stability" : "bound by accuracy", c.steps_gauss4, pilot_note.c_str(), c.omega_max,
        c.omega_1);
    return {implicit ? gauss_stepper : "rk8pd", why};
}

double mass_condition(const Model& model)
{
    const SymmetricPairs eig = symmetric_pairs(mass_at_rest(model), false);
    const double lo = eig.values.minCoeff(), hi = eig.values.maxCoeff();
    return lo > 0.0 ? hi / lo : INFINITY;
}

double stability_step_factor(const std::string& stepper)
{
    static const std::map<std::string, double> factors = {{"rk2", 1.1},   {"rk4", 2.5},   {"rkf45", 0.42},
                                                          {"rkck", 0.47}, {"rk8pd", 3.1}, {"msadams", 0.21}};
    const auto it = factors.find(stepper);
    return it == factors.end() ? INFINITY : it->second;
}

}  // namespace hubbeam
