// The hand-assembled path's quadratic forms over the elastic coordinates (docs/model.md section 12.3), and the blocks
// by which the beam and each term place their matrices in them.
#pragma once

#include <Eigen/Dense>

#include "coordinates.hpp"
#include "variant.hpp"

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
///   T = 1/2 qd_e^T M qd_e + w (s^T qd_e + q_e^T (N + P) qd_e) + 1/2 w^2 (J + 2 b^T q_e + q_e^T K_w q_e)
///   U = 1/2 q_e^T K q_e + g (sin(theta) V_i + cos(theta) V_j) + g_axis V_k
///   D = 1/2 qd_e^T Dm qd_e,  Dm = alpha M + beta K
/// M, K_w, K, Dm and P are symmetric, N is skew (q^T N q = 0: the Coriolis terms do no work). w q^T P qd = w d/dt
/// (1/2 q^T P q) acts only while w changes (section offsets' terms, 12.5; zero without them).
struct QuadraticForms {
    Eigen::MatrixXd M, N, P, K_w, K, Dm;
    Eigen::VectorXd s, b;
    double J = 0.0;
    AxisWeight V_i, V_j, V_k;
    double g = 0.0, g_axis = 0.0;
    bool damped = false;

    /// Adds a term's forms b (of the same coordinates, from zero_forms) to these, b's damping only where these damp.
    void add(const QuadraticForms& b);
};

/// The blocks of a form over q_e by the coordinates' fields (coordinate_layout, counted from the first coordinate
/// after the hub's): f(M, A, B) is M's block of the axial rows and in-plane columns, f(v, B) v's in-plane segment;
/// a field the variant lacks has an empty block.
class FieldBlocks {
public:
    explicit FieldBlocks(const VariantKey& key) : layout_(coordinate_layout(key)), beam_(layout_.first_beam()) {}

    int size() const { return layout_.size() - beam_; }
    int count(FieldKind k) const { return layout_.count(k); }
    auto operator()(Eigen::MatrixXd& m, FieldKind rows, FieldKind columns) const
    {
        return m.block(first(rows), first(columns), count(rows), count(columns));
    }
    auto operator()(Eigen::VectorXd& v, FieldKind rows) const { return v.segment(first(rows), count(rows)); }
    /// Adds v to m's block (rows, columns) and its transpose to (columns, rows): one term of a symmetric form.
    void add_both(Eigen::MatrixXd& m, FieldKind rows, FieldKind columns, const Eigen::MatrixXd& v) const
    {
        (*this)(m, rows, columns) += v;
        (*this)(m, columns, rows) += v.transpose();
    }

private:
    int first(FieldKind k) const
    {
        const CoordinateField* f = layout_.find(k);
        return f ? f->first - beam_ : 0;
    }

    CoordinateLayout layout_;
    int beam_;  // after the hub's coordinates (its angle, a moving hub's x_h, y_h)
};

/// Forms of n coordinates, all zero (no weight, no damping).
QuadraticForms zero_forms(int n);

/// The fields by the letters of docs/model.md section 12.3.
namespace fields {
constexpr FieldKind A = FieldKind::axial, B = FieldKind::inplane, Z = FieldKind::flap, P = FieldKind::twist;
}

}  // namespace hubbeam
