// docs/model.md section 5 assembled numerically: coefficient matrices by quadrature, then M(q) and Q(q, qd) of
// Lagrange's equations for orders first and zero, in torque form q = (theta, A, B) or prescribed form q = (A, B).
#include "assembled.hpp"

#include "fields.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace hubbeam {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using ConstVector = Eigen::Map<const VectorXd>;
using Vector = Eigen::Map<VectorXd>;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// P^T diag(w) Q: the quadrature of int p(xi)^T w(xi) q(xi) dxi from values at the nodes (one row per node).
MatrixXd weighted_product(const MatrixXd& P, const VectorXd& w, const MatrixXd& Q)
{
    return P.transpose() * w.asDiagonal() * Q;
}

/// P^T diag(w) P, exactly symmetric.
MatrixXd weighted_gram(const MatrixXd& P, const VectorXd& w)
{
    const MatrixXd R = weighted_product(P, w, P);
    return 0.5 * (R + R.transpose());
}

}  // namespace

BeamMatrices assemble_matrices(const VariantKey& key, const Parameters& p)
{
    if (const std::string problem = key.dof_problem(); !problem.empty()) throw std::invalid_argument(problem);
    const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis();
    const int nx = key.nx, ny = key.ny;
    const QuadratureRule rule = product_rule(axial, transverse);
    const int nn = static_cast<int>(rule.nodes.size());

    // Shape functions and their xi-derivatives at the nodes (one row per node).
    MatrixXd X(nn, nx), X1(nn, nx), Y(nn, ny), Y1(nn, ny), Y2(nn, ny);
    for (int r = 0; r < nn; ++r) {
        const double xi = rule.nodes[r];
        for (int i = 0; i < nx; ++i) {
            const Jet<double> f = axial.at(i, xi);
            X(r, i) = f.v;
            X1(r, i) = f.d1;
        }
        for (int i = 0; i < ny; ++i) {
            const Jet<double> f = transverse.at(i, xi);
            Y(r, i) = f.v;
            Y1(r, i) = f.d1;
            Y2(r, i) = f.d2;
        }
    }

    // docs/model.md section 5's integrals in xi: x = L xi, dx = L dxi, Phi' = (1/L) dPhi/dxi, Phi'' = (1/L^2) d2Phi/dxi2.
    const double L = p.L, a = p.a, m = p.rho * p.S, EI = p.E * p.I, ES = p.E * p.S;
    const Eigen::ArrayXd xi = Eigen::Map<const Eigen::ArrayXd>(rule.nodes.data(), nn);
    const VectorXd w = Eigen::Map<const VectorXd>(rule.weights.data(), nn);
    const VectorXd w_arm = (m * L * w.array() * (a + L * xi)).matrix();         // m (a+x) dx
    const VectorXd w_C = (m * w.array() * (1.0 - xi)).matrix();                  // m (L-x) dx / L^2
    const VectorXd w_D = (0.5 * m * L * w.array() * (1.0 - xi * xi)).matrix();  // m (L^2-x^2)/2 dx / L^2

    BeamMatrices b;
    b.J_ob = m * (std::pow(a + L, 3) - std::pow(a, 3)) / 3.0;  // int_0^L m (a+x)^2 dx in closed form
    b.S_x = (X.transpose() * w_arm).transpose();
    b.S_y = (Y.transpose() * w_arm).transpose();
    b.M1 = m * L * weighted_gram(X, w);
    b.M2 = m * L * weighted_gram(Y, w);
    b.M3 = m * L * weighted_product(X, w, Y);
    b.K1 = ES / L * weighted_gram(X1, w);
    b.K2 = EI / (L * L * L) * weighted_gram(Y2, w);
    b.C = weighted_gram(Y1, w_C);
    b.D = weighted_gram(Y1, w_D);
    b.G = a * b.C + b.D;
    return b;
}

namespace {

/// docs/model.md section 5's M and Q from the constant matrices; `zero` order uses M2 in place of M2 - G.
class AssembledModel final : public Model {
public:
    AssembledModel(const VariantKey& key, const Parameters& p)
        : Model(key), c_(assemble_matrices(key, p)), fields_(key, p), nx_(key.nx), ny_(key.ny), J_o_(p.J_oh + c_.J_ob)
    {
        M2_G_ = key.order == Order::zero ? c_.M2 : MatrixXd(c_.M2 - c_.G);
        S_x_T_ = c_.S_x.transpose();
        S_y_T_ = c_.S_y.transpose();
        if (key.drive == Drive::prescribed) {  // paper eq. 57: M = blockdiag(M1, M2), constant
            M_prescribed_ = RowMajorMatrix::Zero(nx_ + ny_, nx_ + ny_);
            M_prescribed_.topLeftCorner(nx_, nx_) = c_.M1;
            M_prescribed_.bottomRightCorner(ny_, ny_) = c_.M2;
        }
    }

    const char* source() const override { return "assembled"; }
    bool mass_is_constant() const override { return key().drive == Drive::prescribed; }

    /// Zeros of M1 and M2 (the bands of FEM and BSIM, AMM's orthogonality) are exact: the shape functions
    /// vanish identically outside their support. Under torque the hub's row and column depend on q.
    std::string mass_pattern() const override
    {
        const int n = nq();
        RowMajorMatrix M(n, n);
        mass(HubInput{}, std::vector<double>(static_cast<std::size_t>(n), 0.0).data(), M.data());
        const bool torque = key().drive == Drive::torque;
        std::string pattern;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                pattern += torque && (i == 0 || j == 0) ? 'v' : M(i, j) == 0.0 ? '0' : 'c';
        return pattern;
    }

    void mass(const HubInput&, const double* q, double* M) const override
    {
        const int n = nq();
        if (key().drive == Drive::prescribed) {
            std::copy(M_prescribed_.data(), M_prescribed_.data() + n * n, M);
            return;
        }
        const ConstVector A(q + 1, nx_), B(q + 1 + nx_, ny_);
        Eigen::Map<RowMajorMatrix> Mm(M, n, n);
        Mm.setZero();
        Mm(0, 0) = M11(A, B);
        // Row 0: M12 = -(M3 B)^T, M13 = S_y + A^T M3; column 0 is its transpose (M21, M31).
        Mm.row(0).segment(1, nx_).noalias() = -B.transpose() * c_.M3.transpose();
        Mm.row(0).segment(1 + nx_, ny_).noalias() = A.transpose() * c_.M3;
        Mm.row(0).segment(1 + nx_, ny_) += c_.S_y;
        Mm.col(0).tail(n - 1) = Mm.row(0).tail(n - 1).transpose();
        Mm.block(1, 1, nx_, nx_) = c_.M1;
        Mm.block(1 + nx_, 1 + nx_, ny_, ny_) = c_.M2;
    }

    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        const int o = key().first_a();
        const bool torque = key().drive == Drive::torque;
        const double theta_dot = torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + o, nx_), B(q + o + nx_, ny_), A_dot(qd + o, nx_), B_dot(qd + o + nx_, ny_);
        Vector Q_A(Q + o, nx_), Q_B(Q + o + nx_, ny_);
        const double w2 = theta_dot * theta_dot, w = 2.0 * theta_dot;

        // Q_A = theta_dot^2 (S_x^T + M1 A) + 2 theta_dot M3 B_dot - K1 A
        Q_A.noalias() = w2 * (c_.M1 * A);
        Q_A += w2 * S_x_T_;
        Q_A.noalias() += w * (c_.M3 * B_dot);
        Q_A.noalias() -= c_.K1 * A;
        // Q_B = theta_dot^2 (M2 - G) B - 2 theta_dot M3^T A_dot - K2 B
        Q_B.noalias() = w2 * (M2_G_ * B);
        Q_B.noalias() -= w * (c_.M3.transpose() * A_dot);
        Q_B.noalias() -= c_.K2 * B;

        if (torque) {
            // Q_theta = tau - 2 theta_dot (S_x A_dot + A^T M1 A_dot + B^T (M2 - G) B_dot)
            Q[0] = u.tau - w * (c_.S_x.dot(A_dot) + A.dot(c_.M1.lazyProduct(A_dot)) + B.dot(M2_G_.lazyProduct(B_dot)));
        } else {
            // Paper eq. 57: the known theta_ddot moves to the right: Q_A - M21 theta_ddot, Q_B - M31 theta_ddot.
            Q_A.noalias() += u.theta_ddot * (c_.M3 * B);
            Q_B.noalias() -= u.theta_ddot * (c_.M3.transpose() * A);
            Q_B -= u.theta_ddot * S_y_T_;
        }
    }

    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        const int o = key().first_a();
        const bool torque = key().drive == Drive::torque;
        const double theta_dot = torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + o, nx_), B(q + o + nx_, ny_), A_dot(qd + o, nx_), B_dot(qd + o + nx_, ny_);

        // T of docs/model.md section 5, by degree in the flexible rates.
        const double flexible = 0.5 * A_dot.dot(c_.M1.lazyProduct(A_dot)) + 0.5 * B_dot.dot(c_.M2.lazyProduct(B_dot));
        const double coupling = theta_dot * gyroscopic(A, B, A_dot, B_dot);
        const double spin = 0.5 * M11(A, B) * theta_dot * theta_dot;
        Energy e;
        if (torque) {
            e.T2 = flexible + coupling + spin;  // theta_dot is a rate too: all of T is quadratic in qd
        } else {
            e.T2 = flexible;
            e.T1 = coupling;
            e.T0 = spin;
        }
        e.U = 0.5 * A.dot(c_.K1.lazyProduct(A)) + 0.5 * B.dot(c_.K2.lazyProduct(B));
        return e;
    }

    Tip tip(const double* q) const override
    {
        return fields_.tip(nx_ > 0 ? q + key().first_a() : nullptr, q + key().first_b());
    }

    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        const int o = key().first_a();
        const double theta_dot = key().drive == Drive::torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + o, nx_), B(q + o + nx_, ny_), A_dot(qd + o, nx_), B_dot(qd + o + nx_, ny_);
        return M11(A, B) * theta_dot + gyroscopic(A, B, A_dot, B_dot);  // dT/dtheta_dot
    }

private:
    /// M11 = J_oh + J_ob + 2 S_x A + A^T M1 A + B^T (M2 - G) B.
    double M11(const ConstVector& A, const ConstVector& B) const
    {
        return J_o_ + 2.0 * c_.S_x.dot(A) + A.dot(c_.M1.lazyProduct(A)) + B.dot(M2_G_.lazyProduct(B));
    }

    /// The factor of theta_dot in T linear in the rates: (S_y + A^T M3) B_dot - B^T M3^T A_dot.
    double gyroscopic(const ConstVector& A, const ConstVector& B, const ConstVector& A_dot,
                      const ConstVector& B_dot) const
    {
        return c_.S_y.dot(B_dot) + A.dot(c_.M3.lazyProduct(B_dot)) - A_dot.dot(c_.M3.lazyProduct(B));
    }

    BeamMatrices c_;
    BeamFields fields_;
    int nx_, ny_;
    double J_o_;                  // J_oh + J_ob
    MatrixXd M2_G_;               // M2 - G (first order) or M2 (zero order)
    VectorXd S_x_T_, S_y_T_;      // S_x^T, S_y^T as columns
    RowMajorMatrix M_prescribed_;  // blockdiag(M1, M2) for the prescribed form
};

}  // namespace

std::unique_ptr<Model> make_assembled_model(const VariantKey& key, const Parameters& p)
{
    if (key.order == Order::full)
        throw std::invalid_argument("full order has no hand-assembled form; it needs a generated variant");
    if (key.extras.any())
        throw std::invalid_argument("a tip body, gravity, damping or a taper has no hand-assembled form yet; it needs a generated variant");
    return std::make_unique<AssembledModel>(key, p);
}

}  // namespace hubbeam
