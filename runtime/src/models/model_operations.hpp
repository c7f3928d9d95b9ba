// What is computed from a model alone (below dynamics and analysis): force Jacobians, M as a matrix, the Rayleigh
// damping matrix, the tip-deflection row.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// M(q), both triangles, as an Eigen matrix.
Eigen::MatrixXd mass_at(const Model& model, const HubInput& u, const std::vector<double>& q);

/// dM/dtheta at a prescribed angle u.theta where M holds its sine and cosine (a moving hub's, affinely):
/// M(theta + pi/2) - (M(theta) + M(theta + pi)) / 2.
Eigen::MatrixXd mass_theta_derivative(const Model& model, const HubInput& u, const double* q);

/// dQ/dq (nq x nq), dQ/dqd (nq x nq) and dQ/du (nq x 3, u indexed by DriveValue) at (u, q, qd): the model's exact
/// derivatives (Model::jacobian). Throws std::logic_error for a model without them.
struct ForceJacobians {
    Eigen::MatrixXd q, qd, u;
};
ForceJacobians force_jacobians(const Model& model, const HubInput& u, const std::vector<double>& q,
                               const std::vector<double>& qd);
/// dQ/dq alone, the same way.
Eigen::MatrixXd force_q_jacobian(const Model& model, const HubInput& u, const std::vector<double>& q,
                                 const std::vector<double>& qd);

/// The damping matrix: Rayleigh's alpha M_ee + beta K_e of the model's elastic coordinates (nq x nq; the hub angle's
/// row and column, not damped, zero), with M_ee and K_e those of the undeformed beam at rest (docs/model.md section
/// 11.4), a moving hub's support and the modal damping (section 11.5, added_damping): the dissipated energy's rate
/// qd^T C qd, independent of the generated damping forces.
Eigen::MatrixXd damping_matrix(const Model& model, const Parameters& parameters);

/// d value(L) / dq_c for each of the coordinates c (indices into q), at q, value a tip displacement linear in the
/// coordinates (u_y, u_z, phi: Tip::uy, Tip::uz, Tip::phi), so that central differences at unit offsets are exact.
/// The tip rows of the state space's C and the row of a controller's tip feedback.
Eigen::VectorXd tip_row(const Model& model, const std::vector<double>& q, const std::vector<int>& coordinates,
                        double Tip::* value);


/// The coordinates that keep their inertia and are states of the first-order system, in order: all of a model's
/// (its layout: a rotor's holds every blade), or with quasi-static axial coordinates all but A (which then follows
/// its equilibrium). The one definition for the integrator, the stiffness estimates and the linearization.
inline std::vector<int> kept_coordinates(const CoordinateLayout& layout, Axial axial)
{
    std::vector<int> kept;
    for (const CoordinateField& f : layout.fields)
        if (axial == Axial::dynamic || f.kind != FieldKind::axial)
            for (int i = f.first; i < f.end(); ++i) kept.push_back(i);
    return kept;
}

}  // namespace hubbeam
