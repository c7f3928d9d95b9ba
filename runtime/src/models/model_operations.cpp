// What is computed from a model alone, below the dynamics that integrate it and the analyses that linearize it:
// the force Jacobians (the model's exact derivatives), M as a matrix, the damping matrix and the
// tip-deflection row.
#include "models/model_operations.hpp"

#include "models/modal_damping.hpp"

#include <cmath>
#include <stdexcept>

namespace hubbeam {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

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
    // Every model of the library has them (generated kernels, the assembled blocks' derivatives, a rotor's blades'):
    // only a test's stand-in lacks them, and the implicit steppers alone difference its forces.
    const ExactJacobian* exact = model.jacobian();
    if (exact == nullptr) throw std::logic_error("force_jacobians: the model has no exact derivatives");
    const int n = model.nq();
    RowMatrix dq(n, n), dqd(n, n), du(n, static_cast<Eigen::Index>(drive_value_count));
    exact->force_derivatives(u, q.data(), qd.data(), dq.data(), dqd.data(), du.data());
    return {dq, dqd, du};
}

Eigen::MatrixXd force_q_jacobian(const Model& model, const HubInput& u, const std::vector<double>& q,
                                 const std::vector<double>& qd)
{
    return force_jacobians(model, u, q, qd).q;
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
