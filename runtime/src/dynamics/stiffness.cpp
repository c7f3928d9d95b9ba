// Stiffness from the generalized eigenvalues of the stiffness and mass matrices at rest.
#include "stiffness.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "linearize.hpp"

namespace hubbeam {

namespace {

/// -dQ/dq at (u, q, qd) (exact by differences too for the linear restoring forces about the straight beam, where it
/// is used).
Eigen::MatrixXd stiffness(const Model& model, const HubInput& u, const std::vector<double>& q, const std::vector<double>& qd)
{
    return -force_q_jacobian(model, u, q, qd);
}

}  // namespace

double highest_frequency(const Model& model, Axial axial)
{
    const int n = model.nq();
    const VariantKey& key = model.key();
    const HubInput rest;
    const std::vector<double> zero(static_cast<std::size_t>(n), 0.0);
    Eigen::MatrixXd M(n, n);
    model.mass(rest, zero.data(), M.data());  // symmetric, so row- or column-major alike
    const Eigen::MatrixXd K = stiffness(model, rest, zero, zero);
    // The integrated coordinates only.
    const std::vector<int> kept = kept_coordinates(key, axial);
    const auto m = static_cast<Eigen::Index>(kept.size());
    Eigen::MatrixXd Mk(m, m), Kk(m, m);
    for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < m; ++j) {
            Mk(i, j) = M(kept[static_cast<std::size_t>(i)], kept[static_cast<std::size_t>(j)]);
            Kk(i, j) = 0.5 * (K(kept[static_cast<std::size_t>(i)], kept[static_cast<std::size_t>(j)]) +
                              K(kept[static_cast<std::size_t>(j)], kept[static_cast<std::size_t>(i)]));
        }
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(Kk, Mk, Eigen::EigenvaluesOnly);
    if (solver.info() != Eigen::Success) return INFINITY;  // M not positive definite: treat as stiff
    return std::sqrt(std::max(0.0, solver.eigenvalues().maxCoeff()));
}

double highest_rate(const Model& model, Axial axial)
{
    const double omega = highest_frequency(model, axial);
    const int n = model.nq();
    const std::vector<double> zero(static_cast<std::size_t>(n), 0.0);
    const HubInput rest;
    const ForceJacobians J = force_jacobians(model, rest, zero, zero);
    if (J.qd.isZero(0.0)) return omega;  // undamped: the rates are the frequencies
    // Damped: the eigenvalues of the first-order system x' = [[0, I], [M^-1 dQ/dq, M^-1 dQ/dqd]] x at rest, kept
    // coordinates only. Stiffness-proportional damping turns the stiff axial modes into fast real decays of rate
    // about beta omega^2, which bound an explicit step as a frequency does.
    const std::vector<int> kept = kept_coordinates(model.key(), axial);
    const auto m = static_cast<Eigen::Index>(kept.size());
    Eigen::MatrixXd M(n, n), Mk(m, m), Kq(m, m), Kqd(m, m);
    model.mass(rest, zero.data(), M.data());
    for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < m; ++j) {
            const auto a = static_cast<Eigen::Index>(kept[static_cast<std::size_t>(i)]);
            const auto b = static_cast<Eigen::Index>(kept[static_cast<std::size_t>(j)]);
            Mk(i, j) = M(a, b);
            Kq(i, j) = J.q(a, b);
            Kqd(i, j) = J.qd(a, b);
        }
    const Eigen::LDLT<Eigen::MatrixXd> solve(Mk);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    A.topRightCorner(m, m).setIdentity();
    A.bottomLeftCorner(m, m) = solve.solve(Kq);
    A.bottomRightCorner(m, m) = solve.solve(Kqd);
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(A, false);
    if (eig.info() != Eigen::Success) return INFINITY;
    return std::max(omega, eig.eigenvalues().cwiseAbs().maxCoeff());
}

namespace {

/// Whether -dQ/dq at rest, spinning steadily at omega, is positive definite (the cyclic hub angle left out).
bool stable_at(const Model& model, double omega)
{
    const int n = model.nq(), first = model.key().first_a();
    HubInput u;
    std::vector<double> q(static_cast<std::size_t>(n), 0.0), qd(q);
    if (model.key().drive == Drive::torque) qd[0] = omega;
    else u.theta_dot = omega;
    const int m = n - first;
    const Eigen::MatrixXd K = stiffness(model, u, q, qd).bottomRightCorner(m, m);
    const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (K + K.transpose()));
    return llt.info() == Eigen::Success;
}

}  // namespace

double critical_spin(const Model& model)
{
    double lo = 0.0, hi = 1000.0;
    if (stable_at(model, hi)) return INFINITY;
    if (!stable_at(model, lo)) return 0.0;
    for (int i = 0; i < 60 && hi - lo > 1e-9 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (stable_at(model, mid) ? lo : hi) = mid;
    }
    return lo;
}

StepperChoice automatic_stepper(const Model& model, Axial axial)
{
    const double omega = highest_rate(model, axial);
    const bool damped = omega != highest_frequency(model, axial);
    // Damped equations are judged by their largest rate |lambda|, which a damped decay may set.
    const char* what = damped ? "largest rate |lambda| of the damped equations" : "highest frequency";
    const char* unit = damped ? "1/s" : "rad/s";
    char why[220];
    if (omega > stiff_frequency && model.mass_is_constant()) {
        std::snprintf(why, sizeof why, "automatic: stiff, %s %.0f %s > %.0f %s, constant M", what, omega, unit,
                      stiff_frequency, unit);
        return {"rk4imp", why};
    }
    if (omega > stiff_frequency) {
        std::snprintf(why, sizeof why,
                      "automatic: stiff, %s %.0f %s > %.0f %s, but M varies: an implicit step costs more than the "
                      "explicit steps it saves",
                      what, omega, unit, stiff_frequency, unit);
        return {"rk8pd", why};
    }
    std::snprintf(why, sizeof why, "automatic: not stiff, %s %.0f %s <= %.0f %s", what, omega, unit, stiff_frequency, unit);
    return {"rk8pd", why};
}

double mass_condition(const Model& model)
{
    const int n = model.nq();
    const std::vector<double> zero(static_cast<std::size_t>(n), 0.0);
    Eigen::MatrixXd M(n, n);
    model.mass(HubInput{}, zero.data(), M.data());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M, Eigen::EigenvaluesOnly);
    const double lo = eig.eigenvalues().minCoeff(), hi = eig.eigenvalues().maxCoeff();
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
