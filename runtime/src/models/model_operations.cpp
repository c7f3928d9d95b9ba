// What is computed from a model alone, below the dynamics that integrate it and the analyses that linearize it:
// the force Jacobians (exact kernels or central differences), M as a matrix, the damping matrix and the
// tip-deflection row.
#include "models/model_operations.hpp"

#include "models/modal_damping.hpp"

#include <algorithm>
#include <cmath>

namespace hubbeam {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Central-difference step for a value of size x: about the cube root of machine epsilon, relative.
double step_for(double x) { return 6e-6 * std::max(1.0, std::abs(x)); }

/// The one drive value of u that index names.
double& drive_value(HubInput& u, int index)
{
    switch (static_cast<DriveValue>(index)) {
    case DriveValue::tau: return u.tau;
    case DriveValue::theta_dot: return u.theta_dot;
    default: return u.theta_ddot;
    }
}

/// count columns of dQ/dz by central differences: evaluate(k, h, Q) writes Q with the k-th of z moved by h, whose
/// value is value(k).
template <class Value, class Evaluate>
Eigen::MatrixXd differences(const Model& model, int count, const Value& value, const Evaluate& evaluate)
{
    const int n = model.nq();
    Eigen::MatrixXd out(n, count);
    std::vector<double> plus(static_cast<std::size_t>(n)), minus(plus);
    for (int k = 0; k < count; ++k) {
        const double h = step_for(value(k));
        evaluate(k, h, plus.data());
        evaluate(k, -h, minus.data());
        for (int i = 0; i < n; ++i)
            out(i, k) = (plus[static_cast<std::size_t>(i)] - minus[static_cast<std::size_t>(i)]) / (2 * h);
    }
    return out;
}

/// dQ/dq by central differences.
Eigen::MatrixXd q_differences(const Model& model, const HubInput& u, const std::vector<double>& q,
                              const std::vector<double>& qd)
{
    return differences(model, model.nq(), [&](int k) { return q[static_cast<std::size_t>(k)]; },
                       [&](int k, double h, double* Q) {
                           std::vector<double> qh = q;
                           qh[static_cast<std::size_t>(k)] += h;
                           model.forces(u, qh.data(), qd.data(), Q);
                       });
}

}  // namespace

Eigen::MatrixXd mass_at(const Model& model, const HubInput& u, const std::vector<double>& q)
{
    const int n = model.nq();
    RowMatrix M(n, n);
    model.mass(u, q.data(), M.data());
    return M;
}

Eigen::MatrixXd mass_theta_derivative(const Model& model, const HubInput& u, const double* q)
{
    const std::vector<double> at(q, q + model.nq());
    HubInput turned = u;
    const auto mass_turned = [&](double by) {
        turned.theta = u.theta + by;
        return mass_at(model, turned, at);
    };
    return mass_turned(0.5 * M_PI) - 0.5 * (mass_at(model, u, at) + mass_turned(M_PI));
}

ForceJacobians force_jacobians(const Model& model, const HubInput& u, const std::vector<double>& q,
                               const std::vector<double>& qd)
{
    const int n = model.nq();
    const auto drives = static_cast<Eigen::Index>(drive_value_count);
    if (const ExactJacobian* exact = model.jacobian()) {
        RowMatrix dq(n, n), dqd(n, n), du(n, drives);
        exact->force_derivatives(u, q.data(), qd.data(), dq.data(), dqd.data(), du.data());
        return {dq, dqd, du};
    }
    return {q_differences(model, u, q, qd),
            differences(model, n, [&](int k) { return qd[static_cast<std::size_t>(k)]; },
                        [&](int k, double h, double* Q) {
                            std::vector<double> qdh = qd;
                            qdh[static_cast<std::size_t>(k)] += h;
                            model.forces(u, q.data(), qdh.data(), Q);
                        }),
            differences(model, static_cast<int>(drives), [&](int j) { return u.packed()[static_cast<std::size_t>(j)]; },
                        [&](int j, double h, double* Q) {
                            HubInput uh = u;
                            drive_value(uh, j) += h;
                            model.forces(uh, q.data(), qd.data(), Q);
                        })};
}

Eigen::MatrixXd force_q_jacobian(const Model& model, const HubInput& u, const std::vector<double>& q,
                                 const std::vector<double>& qd)
{
    return model.jacobian() != nullptr ? force_jacobians(model, u, q, qd).q : q_differences(model, u, q, qd);
}

Eigen::MatrixXd damping_matrix(const Model& model, const Parameters& parameters)
{
    const HubInput rest;
    const std::vector<double> zero(static_cast<std::size_t>(model.nq()), 0.0);
    const Eigen::MatrixXd M = mass_at(model, rest, zero);
    const Eigen::MatrixXd K = -force_q_jacobian(model, rest, zero, zero);
    Eigen::MatrixXd C = parameters.alpha * M + parameters.beta * 0.5 * (K + K.transpose());
    // The hub angle, a coordinate under torque, is not damped; a moving hub's translation only by its support.
    for (const CoordinateField& f : model.coordinates().fields)
        if (!f.basis) {
            C.middleRows(f.first, f.count).setZero();
            C.middleCols(f.first, f.count).setZero();
            if (f.kind == FieldKind::hub_x) C(f.first, f.first) = parameters.c_x;
            if (f.kind == FieldKind::hub_y) C(f.first, f.first) = parameters.c_y;
        }
    if (const Eigen::MatrixXd modal = added_damping(model); modal.size() > 0) C += modal;
    return C;
}

Eigen::VectorXd tip_row(const Model& model, const std::vector<double>& q, const std::vector<int>& coordinates,
                        double Tip::* value)
{
    Eigen::VectorXd row(static_cast<Eigen::Index>(coordinates.size()));
    std::vector<double> plus = q, minus = q;
    for (std::size_t i = 0; i < coordinates.size(); ++i) {
        const auto c = static_cast<std::size_t>(coordinates[i]);
        plus[c] += 1.0;
        minus[c] -= 1.0;
        row[static_cast<Eigen::Index>(i)] = 0.5 * (model.tip(plus.data()).*value - model.tip(minus.data()).*value);
        plus[c] = minus[c] = q[c];
    }
    return row;
}

}  // namespace hubbeam
