// The hand-assembled model of docs/model.md section 12.3: Lagrange's equations of T, U and D written as quadratic forms
// in the elastic coordinates (quadratic_forms.hpp), in torque form q = (theta, q_e) or prescribed form q = q_e. The
// assembled path's model for a beam that leaves the plane.
#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/assembled/assembled.hpp"
#include "models/assembled/quadratic_forms.hpp"

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Section 12.3's equations from the forms: with w = theta_dot, h = s + (N^T + P) q_e (the rates' coupling to the hub)
/// and M11 = J + 2 b^T q_e + q_e^T K_w q_e,
///   M = [[M11, h^T], [h, M]] (torque) or M (prescribed)
///   Q_theta = tau - 2 w (b + K_w q_e)^T qd_e - qd_e^T P qd_e - dU_g/dtheta
///   Q_e = w^2 (b + K_w q_e) + 2 w N qd_e - K q_e - dU_g/dq_e - Dm qd_e (- theta_ddot h, prescribed)
/// and their exact derivatives, each a form's matrix or its product with the state (never the generator's kernels).
class QuadraticFormModel final : public Model, ExactJacobian {
public:
    QuadraticFormModel(const VariantKey& key, const Parameters& p)
        : Model(key, p), e_(coordinates().first_beam()), ne_(nq() - e_)
    {
        const BeamMatrices c = assemble_matrices(key, p);
        f_ = quadratic_forms(key, c, model_matrices({key, p, c}));
        tip_ = {c.Phi_x_L, c.Phi_y_L, c.o.Phi_z_L, c.o.Phi_t_L, c.H_L, c.o.H_z_L};
        if (key.extras.hub) {
            hub_ = std::make_unique<HubForms>();
            hub_->x = coordinates().first(FieldKind::hub_x);
            hub_->mass = p.m_hub + c.mass + (key.extras.tip ? p.m_tip : 0.0);
            hub_->P = f_.V_i.o;
            hub_->c_i = f_.V_i.w;
            hub_->c_j = f_.V_j.w;
            hub_->k = {p.k_x, p.k_y};
            hub_->c = {p.c_x, p.c_y};
        }
    }

    const char* source() const override { return "assembled"; }
    bool mass_is_constant() const override { return key().drive == Drive::prescribed && !hub_; }

    /// Zeros of M are exact (shape functions vanish outside their support, fields with no mass coupling); a moving
    /// hub's rows turn with the hub angle.
    std::string mass_pattern() const override
    {
        std::string pattern = assembled_mass_pattern(*this);
        if (hub_)
            for (int i = 0; i < nq(); ++i)
                for (int j : {hub_->x, hub_->x + 1}) {
                    pattern[static_cast<std::size_t>(i * nq() + j)] = 'v';
                    pattern[static_cast<std::size_t>(j * nq() + i)] = 'v';
                }
        return pattern;
    }

    void mass(const HubInput& u, const double* q, double* M) const override
    {
        Eigen::Map<RowMajorMatrix> Mm(M, nq(), nq());
        Mm.setZero();
        Mm.bottomRightCorner(ne_, ne_) = f_.M;
        const VectorXd qe = elastic(q);
        if (key().drive == Drive::torque) {
            Mm(0, 0) = M11(qe);
            const VectorXd h = coupling(qe);
            Mm.col(0).tail(ne_) = h;
            Mm.row(0).tail(ne_) = h.transpose();
        }
        if (!hub_) return;
        const double theta = angle(u, q), C = std::cos(theta), S = std::sin(theta);
        const int x = hub_->x, y = x + 1;
        Mm(x, x) = Mm(y, y) = hub_->mass;
        const VectorXd rx = C * hub_->c_i - S * hub_->c_j, ry = S * hub_->c_i + C * hub_->c_j;
        Mm.row(x).tail(ne_) = rx.transpose();
        Mm.col(x).tail(ne_) = rx;
        Mm.row(y).tail(ne_) = ry.transpose();
        Mm.col(y).tail(ne_) = ry;
        if (key().drive == Drive::torque) {
            const auto [mx, my] = hub_angle_coupling(C, S, qe);
            Mm(x, 0) = Mm(0, x) = mx;
            Mm(y, 0) = Mm(0, y) = my;
        }
    }

    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const VectorXd spin = f_.b + f_.K_w * qe;  // half of dM11/dq_e
        VectorXd Qe = w * w * spin + 2.0 * w * (f_.N * qde) - f_.K * qe;
        if (torque)
            Q[0] = u.tau - 2.0 * w * spin.dot(qde) - qde.dot(f_.P * qde);
        else
            Qe -= u.theta_ddot * coupling(qe);  // the known hub acceleration's share of d/dt dT/dqd_e
        if (weighed()) {
            const double theta = torque ? q[0] : u.theta, gs = f_.g * std::sin(theta), gc = f_.g * std::cos(theta);
            Qe -= gs * f_.V_i.gradient(qe) + gc * f_.V_j.gradient(qe) + f_.g_axis * f_.V_k.gradient(qe);
            if (torque) Q[0] -= gc * f_.V_i.at(qe) - gs * f_.V_j.at(qe);  // V_k does not turn with theta
        }
        if (f_.damped) Qe -= f_.Dm * qde;
        Eigen::Map<VectorXd>(Q + e_, ne_) = Qe;
        if (!hub_) return;
        const int x = hub_->x, y = x + 1;
        const double theta = angle(u, q);
        const auto [fx, fy] = hub_turning_forces(std::cos(theta), std::sin(theta), u, q, qd);
        Q[x] = fx - hub_->k[0] * q[x] - hub_->c[0] * qd[x];
        Q[y] = fy - hub_->k[1] * q[y] - hub_->c[1] * qd[y] - f_.g * hub_->mass;
    }

    /// dQ/dtheta of the prescribed form: U_g's in-plane part and a moving hub's forces turn with theta.
    void forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const override
    {
        Eigen::Map<VectorXd> d(dQdtheta, nq());
        d.setZero();
        if (key().drive == Drive::torque) return;
        const VectorXd qe = elastic(q);
        if (f_.g != 0.0)
            d.tail(ne_) = -f_.g * std::cos(u.theta) * f_.V_i.gradient(qe) + f_.g * std::sin(u.theta) * f_.V_j.gradient(qe);
        if (!hub_) return;
        // The hub's turning forces are linear in (cos theta, sin theta): their derivative is their value at
        // (-sin theta, cos theta).
        const auto [fx, fy] = hub_turning_forces(-std::sin(u.theta), std::cos(u.theta), u, q, qd);
        d[hub_->x] = fx;
        d[hub_->x + 1] = fy;
    }

    const ExactJacobian* jacobian() const override { return this; }

    /// The derivatives of Q's forms above, term by term; a moving hub's rows by hub_derivatives.
    void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                           double* dQdu) const override
    {
        const int n = nq();
        Block Jq(dQdq, n, n), Jqd(dQdqd, n, n), Ju(dQdu, n, drive_value_count);
        Jq.setZero();
        Jqd.setZero();
        Ju.setZero();
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const VectorXd spin = f_.b + f_.K_w * qe;
        auto Jq_e = Jq.bottomRightCorner(ne_, ne_), Jqd_e = Jqd.bottomRightCorner(ne_, ne_);
        Jq_e = w * w * f_.K_w - f_.K;
        Jqd_e = 2.0 * w * f_.N;
        if (f_.damped) Jqd_e -= f_.Dm;
        // dQ_e/dw: a column of dQ/dqd under torque, of dQ/du under a prescribed drive.
        auto by_rate = torque ? Jqd.col(0) : Ju.col(drive_column(DriveValue::theta_dot));
        by_rate.tail(ne_) = 2.0 * w * spin + 2.0 * (f_.N * qde);
        if (torque) {
            // Q_theta = tau - 2 w spin^T qd_e - qd_e^T P qd_e, spin = b + K_w q_e.
            Jq.row(0).tail(ne_) = -2.0 * w * (f_.K_w * qde).transpose();
            Jqd.row(0).tail(ne_) = -2.0 * (w * spin + f_.P * qde).transpose();
            Jqd(0, 0) = -2.0 * spin.dot(qde);
            Ju(0, drive_column(DriveValue::tau)) = 1.0;
        } else {
            // -theta_ddot h, h = s + (N^T + P) q_e.
            Jq_e -= u.theta_ddot * (f_.N.transpose() + f_.P);
            Ju.col(drive_column(DriveValue::theta_ddot)).tail(ne_) = -coupling(qe);
        }
        if (weighed()) weight_derivatives(angle(u, q), qe, Jq);
        if (hub_) hub_derivatives(u, q, qd, Jq, Jqd, Ju);
    }

    /// dM/dq v: under torque M11 = J + 2 b^T q_e + q_e^T K_w q_e and h = s + (N^T + P) q_e hold q_e, and a moving hub's
    /// couplings the hub angle; zero under a prescribed drive (M turns with the drive's angle, not with q).
    void mass_q_product(const HubInput&, const double* q, const double* v, double* dMv) const override
    {
        const int n = nq();
        Block D(dMv, n, n);
        D.setZero();
        if (key().drive != Drive::torque) return;
        const VectorXd qe = elastic(q), ve = elastic(v);
        // Row 0: v_0 dM11/dq_e + v_e^T dh/dq_e (dh_i/dq_e,k = N_ki + P_ik); rows e: column 0's h times v_0.
        D.row(0).tail(ne_) = (2.0 * v[0] * (f_.b + f_.K_w * qe) + (f_.N + f_.P) * ve).transpose();
        D.bottomRightCorner(ne_, ne_) = v[0] * (f_.N.transpose() + f_.P);
        if (hub_) hub_mass_q_product(q, v, D);
    }

    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const double flexible = 0.5 * qde.dot(f_.M * qde),
                     gyroscopic = w * (f_.s.dot(qde) + qe.dot((f_.N + f_.P) * qde)), spin = 0.5 * w * w * M11(qe);
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
        if (hub_) add_hub_energy(u, q, qd, e);
        return e;
    }

    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        const double w = key().drive == Drive::torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        double h = M11(qe) * w + coupling(qe).dot(qde);  // dT/dtheta_dot
        if (hub_) {
            const auto [v_i, v_j] = hub_velocity(angle(u, q), qd);
            h += -v_i * hub_->c_j.dot(qe) + v_j * (hub_->P + hub_->c_i.dot(qe));
        }
        return h;
    }

    Tip tip(const double* q) const override;

private:
    /// A moving hub (docs/model.md section 13.1) on the forms: the translating mass (hub, beam and tip body), and
    /// the rotor's first moments along the blade's axes, int m p_i dx = P + c_i^T q_e and int m p_j dx = c_j^T q_e
    /// to first order (the weights' V_i, V_j, tip included). With the hub's velocity in the blade's frame
    /// v_i = C x_dot + S y_dot, v_j = -S x_dot + C y_dot (C, S: cos and sin theta) and w = theta_dot, order first's
    /// kinetic energy gains 1/2 M_t (x_dot^2 + y_dot^2) + v_i a + v_j b, a = c_i^T qd_e - w c_j^T q_e,
    /// b = c_j^T qd_e + w (P + c_i^T q_e).
    struct HubForms {
        int x = 0;  // x_h's index in q; y_h follows
        double mass = 0.0, P = 0.0;
        VectorXd c_i, c_j;
        std::array<double, 2> k{}, c{};
    };

    using Block = Eigen::Map<RowMajorMatrix>;

    /// The weight's share of dQ/dq: -d2U_g/dq2, with the hub angle among q under torque.
    void weight_derivatives(double theta, const VectorXd& qe, Block& Jq) const
    {
        const double gs = f_.g * std::sin(theta), gc = f_.g * std::cos(theta);
        Jq.bottomRightCorner(ne_, ne_) += gs * f_.V_i.H + gc * f_.V_j.H + f_.g_axis * f_.V_k.H;
        if (key().drive != Drive::torque) return;
        // dQ_e/dtheta and, U_g's Hessian being symmetric, dQ_theta/dq_e: V_k does not turn with theta.
        const VectorXd by_angle = -gc * f_.V_i.gradient(qe) + gs * f_.V_j.gradient(qe);
        Jq.col(0).tail(ne_) = by_angle;
        Jq.row(0).tail(ne_) += by_angle.transpose();
        Jq(0, 0) = gs * f_.V_i.at(qe) + gc * f_.V_j.at(qe);
    }

    /// The hub rows' derivatives. Their forces are (f_x, f_y) = (C F_1 + S F_2, S F_1 - C F_2) - the support's, with
    /// F_1 = 2 w c_j^T qd_e + w^2 (P + c_i^T q_e) + a c_j^T q_e and F_2 = 2 w c_i^T qd_e - w^2 c_j^T q_e +
    /// a (P + c_i^T q_e) in the blade's axes (a: a prescribed drive's theta_ddot, hub_turning_forces' M terms).
    void hub_derivatives(const HubInput& u, const double* q, const double* qd, Block& Jq, Block& Jqd, Block& Ju) const
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot, a = torque ? 0.0 : u.theta_ddot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const VectorXd &c_i = hub_->c_i, &c_j = hub_->c_j;
        const double along = hub_->P + c_i.dot(qe), across = c_j.dot(qe);
        // F_1's and F_2's derivatives by q_e, qd_e and w.
        const VectorXd F1_q = w * w * c_i + a * c_j, F2_q = -w * w * c_j + a * c_i;
        const VectorXd F1_qd = 2.0 * w * c_j, F2_qd = 2.0 * w * c_i;
        const double F1_w = 2.0 * c_j.dot(qde) + 2.0 * w * along, F2_w = 2.0 * c_i.dot(qde) - 2.0 * w * across;
        const double theta = angle(u, q), C = std::cos(theta), S = std::sin(theta);
        // Each row's weights of F_1 and F_2 (x: C and S, y: S and -C), and its support.
        const std::array<std::pair<double, double>, 2> turn = {{{C, S}, {S, -C}}};
        for (int r = 0; r < 2; ++r) {
            const int i = hub_->x + r;
            const auto [c1, c2] = turn[static_cast<std::size_t>(r)];
            Jq.row(i).tail(ne_) = (c1 * F1_q + c2 * F2_q).transpose();
            Jqd.row(i).tail(ne_) = (c1 * F1_qd + c2 * F2_qd).transpose();
            (torque ? Jqd(i, 0) : Ju(i, drive_column(DriveValue::theta_dot))) = c1 * F1_w + c2 * F2_w;
            if (!torque) Ju(i, drive_column(DriveValue::theta_ddot)) = c1 * across + c2 * along;
            Jq(i, i) = -hub_->k[static_cast<std::size_t>(r)];
            Jqd(i, i) = -hub_->c[static_cast<std::size_t>(r)];
        }
        if (!torque) return;
        // By the hub angle: the forces are linear in (C, S), so their derivative is their value at (-S, C).
        const auto [fx, fy] = hub_turning_forces(-S, C, u, q, qd);
        Jq(hub_->x, 0) = fx;
        Jq(hub_->x + 1, 0) = fy;
    }

    /// A moving hub's part of dM/dq v under torque: its couplings to the hub angle (m_x, m_y of hub_angle_coupling)
    /// hold q_e and theta, and to the beam (r_x = C c_i - S c_j, r_y = S c_i + C c_j) theta.
    void hub_mass_q_product(const double* q, const double* v, Block& D) const
    {
        const VectorXd qe = elastic(q), ve = elastic(v);
        const VectorXd &c_i = hub_->c_i, &c_j = hub_->c_j;
        const double C = std::cos(q[0]), S = std::sin(q[0]), along = hub_->P + c_i.dot(qe), across = c_j.dot(qe);
        const int x = hub_->x, y = x + 1;
        // m_x = -C c_j^T q_e - S (P + c_i^T q_e), m_y = -S c_j^T q_e + C (P + c_i^T q_e): by q_e and by theta.
        const VectorXd mx_q = -C * c_j - S * c_i, my_q = -S * c_j + C * c_i;
        const double mx_theta = S * across - C * along, my_theta = -C * across - S * along;
        // r_x and r_y by theta.
        const VectorXd rx_theta = -S * c_i - C * c_j, ry_theta = C * c_i - S * c_j;
        D(0, 0) = v[x] * mx_theta + v[y] * my_theta;
        D.row(0).tail(ne_) += (v[x] * mx_q + v[y] * my_q).transpose();
        D(x, 0) = v[0] * mx_theta + rx_theta.dot(ve);
        D(y, 0) = v[0] * my_theta + ry_theta.dot(ve);
        D.row(x).tail(ne_) = v[0] * mx_q.transpose();
        D.row(y).tail(ne_) = v[0] * my_q.transpose();
        D.col(0).tail(ne_) += v[x] * rx_theta + v[y] * ry_theta;
    }

    double angle(const HubInput& u, const double* q) const { return key().drive == Drive::torque ? q[0] : u.theta; }
    /// (v_i, v_j): the hub's velocity in the blade's frame.
    std::pair<double, double> hub_velocity(double theta, const double* qd) const
    {
        const double C = std::cos(theta), S = std::sin(theta), xd = qd[hub_->x], yd = qd[hub_->x + 1];
        return {C * xd + S * yd, -S * xd + C * yd};
    }
    /// M's entries of (x_h, theta) and (y_h, theta): d2T / dx_dot dtheta_dot and d2T / dy_dot dtheta_dot.
    std::pair<double, double> hub_angle_coupling(double C, double S, const VectorXd& qe) const
    {
        const double along = hub_->P + hub_->c_i.dot(qe), across = hub_->c_j.dot(qe);
        return {-C * across - S * along, -S * across + C * along};
    }
    /// The hub rows' forces that turn with the hub (linear in C and S): from d/dt of the momenta p_x = M_t x_dot +
    /// C a - S b and p_y = M_t y_dot + S a + C b, less the accelerations' terms of M; under a prescribed drive its
    /// known theta_ddot's term too. (The beam's and the hub angle's rows gain nothing beyond M's couplings: their
    /// rate terms cancel.)
    std::pair<double, double> hub_turning_forces(double C, double S, const HubInput& u, const double* q,
                                                 const double* qd) const
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const double ci_qd = hub_->c_i.dot(qde), cj_qd = hub_->c_j.dot(qde);
        const double a = ci_qd - w * hub_->c_j.dot(qe), b = cj_qd + w * (hub_->P + hub_->c_i.dot(qe));
        double fx = w * (C * cj_qd + S * ci_qd) + w * (S * a + C * b);
        double fy = w * (S * cj_qd - C * ci_qd) - w * (C * a - S * b);
        if (!torque) {
            const auto [mx, my] = hub_angle_coupling(C, S, qe);
            fx -= u.theta_ddot * mx;
            fy -= u.theta_ddot * my;
        }
        return {fx, fy};
    }
    /// The hub's part of T (by degree in the rates under a prescribed drive) and of U.
    void add_hub_energy(const HubInput& u, const double* q, const double* qd, Energy& e) const
    {
        const bool torque = key().drive == Drive::torque;
        const double w = torque ? qd[0] : u.theta_dot;
        const VectorXd qe = elastic(q), qde = elastic(qd);
        const auto [v_i, v_j] = hub_velocity(angle(u, q), qd);
        const double xd = qd[hub_->x], yd = qd[hub_->x + 1];
        const double quadratic = 0.5 * hub_->mass * (xd * xd + yd * yd) + v_i * hub_->c_i.dot(qde) + v_j * hub_->c_j.dot(qde);
        const double linear = w * (-v_i * hub_->c_j.dot(qe) + v_j * (hub_->P + hub_->c_i.dot(qe)));
        if (torque)
            e.T2 += quadratic + linear;
        else
            e.T2 += quadratic, e.T1 += linear;
        const double x = q[hub_->x], y = q[hub_->x + 1];
        e.U += 0.5 * (hub_->k[0] * x * x + hub_->k[1] * y * y) + f_.g * hub_->mass * y;
    }

    /// The shape functions at the tip and H(L), H_z(L): u = Phi(L) q, u_x = u_x1 - 1/2 (B^T H B + Z^T H_z Z).
    struct TipRows {
        Eigen::RowVectorXd x, y, z, t;
        MatrixXd H_y, H_z;
    };

    /// The elastic part of q or qd.
    VectorXd elastic(const double* v) const { return Eigen::Map<const VectorXd>(v + e_, ne_); }
    /// M11 = J + 2 b^T q_e + q_e^T K_w q_e: the hub's inertia with the beam as it stands.
    double M11(const VectorXd& qe) const { return f_.J + 2.0 * f_.b.dot(qe) + qe.dot(f_.K_w * qe); }
    /// h = s + (N^T + P) q_e = d2T/dtheta_dot dqd_e: the hub row of M.
    VectorXd coupling(const VectorXd& qe) const { return f_.s + f_.N.transpose() * qe + f_.P * qe; }
    /// Whether U holds a weight (gravity in the plane or along the axis).
    bool weighed() const { return f_.g != 0.0 || f_.g_axis != 0.0; }

    int e_, ne_;  // where q_e begins in q (after the hub's coordinates), and its size
    QuadraticForms f_;
    TipRows tip_;
    std::unique_ptr<HubForms> hub_;  // null without a moving hub
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
