// The hand-assembled model of docs/model.md section 12.3: Lagrange's equations of T, U and D written as quadratic forms
// in the elastic coordinates (quadratic_forms.hpp), in torque form q = (theta, q_e) or prescribed form q = q_e. The
// assembled path's model for a beam that leaves the plane.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/assembled.hpp"
#include "models/quadratic_forms.hpp"

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Section 12.3's equations from the forms: with w = theta_dot, h = s + N^T q_e (the rates' coupling to the hub) and
/// M11 = J + 2 b^T q_e + q_e^T K_w q_e,
///   M = [[M11, h^T], [h, M]] (torque) or M (prescribed)
///   Q_theta = tau - 2 w (b + K_w q_e)^T qd_e - dU_g/dtheta
///   Q_e = w^2 (b + K_w q_e) + 2 w N qd_e - K q_e - dU_g/dq_e - Dm qd_e (- theta_ddot h, prescribed)
class QuadraticFormModel final : public Model {
public:
    QuadraticFormModel(const VariantKey& key, const Parameters& p)
        : Model(key, p), e_(coordinates().first_elastic()), ne_(nq() - e_)
    {
        const BeamMatrices c = assemble_matrices(key, p);
        f_ = quadratic_forms(key, c, model_matrices({key, p, c}));
        tip_ = {c.Phi_x_L, c.Phi_y_L, c.o.Phi_z_L, c.o.Phi_t_L, c.H_L, c.o.H_z_L};
    }

    const char* source() const override { return "assembled"; }
    bool mass_is_constant() const override { return key().drive == Drive::prescribed; }

    /// Zeros of M are exact (shape functions vanish outside their support, fields with no mass coupling).
    std::string mass_pattern() const override { return assembled_mass_pattern(*this); }

    void mass(const HubInput&, const double* q, double* M) const override
    {
        Eigen::Map<RowMajorMatrix> Mm(M, nq(), nq());
        Mm.bottomRightCorner(ne_, ne_) = f_.M;
        if (key().drive == Drive::prescribed) return;
        const VectorXd qe = elastic(q);
        Mm(0, 0) = M11(qe);
        const VectorXd h = coupling(qe);
        Mm.col(0).tail(ne_) = h;
        Mm.row(0).tail(ne_) = h.transpose();
    }

    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const VectorXd spin = f_.b + f_.K_w * qe;  // half of dM11/dq_e
        VectorXd Qe = w * w * spin + 2.0 * w * (f_.N * qde) - f_.K * qe;
        if (torque)
            Q[0] = u.tau - 2.0 * w * spin.dot(qde);
        else
            Qe -= u.theta_ddot * coupling(qe);  // the known hub acceleration's share of d/dt dT/dqd_e
        if (weighed()) {
            const double theta = torque ? q[0] : u.theta, gs = f_.g * std::sin(theta), gc = f_.g * std::cos(theta);
            Qe -= gs * f_.V_i.gradient(qe) + gc * f_.V_j.gradient(qe) + f_.g_axis * f_.V_k.gradient(qe);
            if (torque) Q[0] -= gc * f_.V_i.at(qe) - gs * f_.V_j.at(qe);  // V_k does not turn with theta
        }
        if (f_.damped) Qe -= f_.Dm * qde;
        Eigen::Map<VectorXd>(Q + e_, ne_) = Qe;
    }

    /// dQ/dtheta of the prescribed form: only U_g's in-plane part turns with theta.
    void forces_theta(const HubInput& u, const double* q, const double*, double* dQdtheta) const override
    {
        Eigen::Map<VectorXd> d(dQdtheta, nq());
        d.setZero();
        if (f_.g == 0.0 || key().drive == Drive::torque) return;
        const VectorXd qe = elastic(q);
        d.tail(ne_) = -f_.g * std::cos(u.theta) * f_.V_i.gradient(qe) + f_.g * std::sin(u.theta) * f_.V_j.gradient(qe);
    }

    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const double flexible = 0.5 * qde.dot(f_.M * qde), gyroscopic = w * (f_.s.dot(qde) + qe.dot(f_.N * qde)),
                     spin = 0.5 * w * w * M11(qe);
        Energy e;
        if (torque)
            e.T2 = flexible + gyroscopic + spin;  // theta_dot is a rate too
        else
            e = {flexible, gyroscopic, spin, 0.0};
        e.U = 0.5 * qe.dot(f_.K * qe);
        if (weighed()) {
            const double theta = torque ? q[0] : u.theta;
            e.U +=
                f_.g * (std::sin(theta) * f_.V_i.at(qe) + std::cos(theta) * f_.V_j.at(qe)) + f_.g_axis * f_.V_k.at(qe);
        }
        return e;
    }

    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        const double w = key().drive == Drive::torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        return M11(qe) * w + coupling(qe).dot(qde);  // dT/dtheta_dot
    }

    Tip tip(const double* q) const override;

private:
    /// The shape functions at the tip and H(L), H_z(L): u = Phi(L) q, u_x = u_x1 - 1/2 (B^T H B + Z^T H_z Z).
    struct TipRows {
        Eigen::RowVectorXd x, y, z, t;
        MatrixXd H_y, H_z;
    };

    /// The elastic part of q or qd.
    VectorXd elastic(const double* v) const { return Eigen::Map<const VectorXd>(v + e_, ne_); }
    /// M11 = J + 2 b^T q_e + q_e^T K_w q_e: the hub's inertia with the beam as it stands.
    double M11(const VectorXd& qe) const { return f_.J + 2.0 * f_.b.dot(qe) + qe.dot(f_.K_w * qe); }
    /// h = s + N^T q_e = d2T/dtheta_dot dqd_e: the hub row of M.
    VectorXd coupling(const VectorXd& qe) const { return f_.s + f_.N.transpose() * qe; }
    /// Whether U holds a weight (gravity in the plane or along the axis).
    bool weighed() const { return f_.g != 0.0 || f_.g_axis != 0.0; }

    int e_, ne_;  // where q_e begins in q, and its size
    QuadraticForms f_;
    TipRows tip_;
};

Tip QuadraticFormModel::tip(const double* q) const
{
    const CoordinateLayout& l = coordinates();
    const auto field = [&](FieldKind k) {
        const CoordinateField* f = l.find(k);
        return f ? Eigen::Map<const VectorXd>(q + f->first, f->count) : Eigen::Map<const VectorXd>(q, 0);
    };
    const auto A = field(FieldKind::axial), B = field(FieldKind::inplane), Z = field(FieldKind::flap),
               P = field(FieldKind::twist);
    Tip t;
    t.ux1 = tip_.x.dot(A);
    t.uy = tip_.y.dot(B);
    t.uz = tip_.z.size() > 0 ? tip_.z.dot(Z) : 0.0;
    t.phi = tip_.t.size() > 0 ? tip_.t.dot(P) : 0.0;
    t.ux = t.ux1;
    if (key().order != Order::zero) {
        t.ux -= 0.5 * B.dot(tip_.H_y * B);
        if (Z.size() > 0) t.ux -= 0.5 * Z.dot(tip_.H_z * Z);
    }
    return t;
}

}  // namespace

std::unique_ptr<Model> make_quadratic_form_model(const VariantKey& key, const Parameters& p)
{
    if (key.order == Order::full)
        throw std::invalid_argument("full order has no hand-assembled form; it needs a generated variant");
    return std::make_unique<QuadraticFormModel>(key, p);
}

}  // namespace hubbeam
