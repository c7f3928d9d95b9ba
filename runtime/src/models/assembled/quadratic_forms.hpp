// docs/model.md section 12.3: the energies of orders zero and first as quadratic forms in the elastic coordinates, the
// hand-assembled path's form for a beam that leaves the plane, placed block by block from the terms' matrices.
#pragma once

#include <Eigen/Dense>

#include "models/assembled/assembled_terms.hpp"

namespace hubbeam {

/// A weight's potential along one hub-frame axis n (i, j or k), per unit g: V_n = int m p_n dx (+ m_tip p_n(L)) =
/// o + w^T q_e - 1/2 q_e^T H q_e.
struct AxisWeight {
    double o = 0.0;
    Eigen::VectorXd w;
    Eigen::MatrixXd H;

    /// V_n at q_e.
    double at(const Eigen::VectorXd& q) const { return o + w.dot(q) - 0.5 * q.dot(H * q); }
    /// dV_n/dq_e = w - H q_e.
    Eigen::VectorXd gradient(const Eigen::VectorXd& q) const { return w - H * q; }
};

/// Section 12.3's forms over q_e, the coordinates after the hub angle in coordinate_layout's order (A, B, Z, P), and
/// the hub's rate w = theta_dot:
///   T = 1/2 qd_e^T M qd_e + w (s^T qd_e + q_e^T N qd_e) + 1/2 w^2 (J + 2 b^T q_e + q_e^T K_w q_e)
///   U = 1/2 q_e^T K q_e + g (sin(theta) V_i + cos(theta) V_j) + g_axis V_k
///   D = 1/2 qd_e^T Dm qd_e,  Dm = alpha M + beta K
/// M, K_w, K and Dm are symmetric, N is skew (q^T N q = 0: the Coriolis terms do no work).
struct QuadraticForms {
    Eigen::MatrixXd M, N, K_w, K, Dm;
    Eigen::VectorXd s, b;
    double J = 0.0;
    AxisWeight V_i, V_j, V_k;
    double g = 0.0, g_axis = 0.0;
    bool damped = false;
};

/// The forms of a variant from the beam's matrices c and the model's m (c's with the terms it carries added).
QuadraticForms quadratic_forms(const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m);

}  // namespace hubbeam
