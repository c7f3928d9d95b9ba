// docs/model.md sections 5 and 11 assembled numerically: coefficient matrices by quadrature (a taper as a weight
// inside them), a tip body as point values of the shape functions at x = L, then M(q) and Q(q, qd) of Lagrange's
// equations for orders first and zero, with gravity and Rayleigh damping, in torque form q = (theta, A, B) or
// prescribed form q = (A, B). A beam that leaves the plane runs on section 12.3's forms (assembled_forms.cpp).
#include "models/assembled/assembled.hpp"

#include <algorithm>
#include <cmath>
#include <hubbeam/fields.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/assembled/assembled_terms.hpp"
#include "profile.hpp"

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

/// Shape functions and their xi-derivatives at the quadrature nodes (one row per node).
struct NodeValues {
    MatrixXd X, X1, Y, Y1, Y2;
};

NodeValues node_values(const FieldBasis& axial, const FieldBasis& transverse, const QuadratureRule& rule)
{
    const int nn = static_cast<int>(rule.nodes.size()), nx = axial.size(), ny = transverse.size();
    NodeValues v{MatrixXd(nn, nx), MatrixXd(nn, nx), MatrixXd(nn, ny), MatrixXd(nn, ny), MatrixXd(nn, ny)};
    for (int r = 0; r < nn; ++r) {
        const double xi = rule.nodes[r];
        for (int i = 0; i < nx; ++i) {
            const Jet<double> f = axial.at(i, xi);
            v.X(r, i) = f.v;
            v.X1(r, i) = f.d1;
        }
        for (int i = 0; i < ny; ++i) {
            const Jet<double> f = transverse.at(i, xi);
            v.Y(r, i) = f.v;
            v.Y1(r, i) = f.d1;
            v.Y2(r, i) = f.d2;
        }
    }
    return v;
}

/// The beam's section at the nodes (docs/model.md section 11): m(x) = m s(xi), ES(x) = ES e(xi), EI(x) = EI i(xi),
/// and the weights of C and D with the order of integration exchanged: H(x) is weighed by int_x^L m dt = m L above
/// and by int_x^L m t dt = m L^2 above_x / 2.
struct SectionAtNodes {
    Eigen::ArrayXd s, i, e, above, above_x;
    double r1 = 0.0;                                 // a taper's tip_ratio - 1 (0 for a uniform beam or a profile)
    double first_moment = 0.0, second_moment = 0.0;  // a profile's int_0^1 m(xi) (a + L xi)^n dxi, n = 1, 2
};

/// A uniform or tapered section: s = 1 + (tip_ratio - 1) xi, i = s (width taper) or s^3 (depth taper); s = i = 1 for
/// a uniform beam, whatever tip_ratio says.
SectionAtNodes taper_at_nodes(const VariantKey& key, const Parameters& p, const Eigen::ArrayXd& xi)
{
    SectionAtNodes c;
    const double r1 = key.extras.taper == Taper::uniform ? 0.0 : p.tip_ratio - 1.0;
    c.r1 = r1;
    c.s = 1.0 + r1 * xi;
    c.i = key.extras.taper == Taper::depth ? Eigen::ArrayXd(c.s.cube()) : c.s;
    c.e = c.s;  // ES(x) / ES
    c.above = (1.0 - xi) + 0.5 * r1 * (1.0 - xi * xi);
    c.above_x = (1.0 - xi * xi) + (2.0 / 3.0) * r1 * (1.0 - xi * xi * xi);
    return c;
}

/// Section 11.2's profile: the table's distributions at the nodes (the reference values are 1), the tails
/// int_xi^1 m(t) t^n dt by 3-point Gauss on each station interval (exact: m is linear there) and the moments.
void profile_at_nodes(const std::vector<double>& stations, const Parameters& p, double cb, const Eigen::ArrayXd& xi,
                      SectionAtNodes& c)
{
    const auto value = [&](ProfileValue j, double x) { return profile_value(stations, p.profile, j, x); };
    const Eigen::Index nn = xi.size();
    for (Eigen::Index r = 0; r < nn; ++r) {
        c.s(r) = value(ProfileValue::m, xi(r));
        c.i(r) = value(ProfileValue::EI, xi(r));
        c.e(r) = value(ProfileValue::ES, xi(r));
    }
    const MassTail tail0(stations, p.profile, 0), tail1(stations, p.profile, 1), tail2(stations, p.profile, 2);
    for (Eigen::Index r = 0; r < nn; ++r) {
        c.above(r) = tail0(xi(r));
        c.above_x(r) = 2.0 * tail1(xi(r));
    }
    // (a + cb L xi)^n = sum of xi powers (cb: a precone's cosine, section 12): the moments of m over [0, 1].
    const double a = p.a, L = cb * p.L, t0 = tail0(0.0), t1 = tail1(0.0), t2 = tail2(0.0);
    c.first_moment = a * t0 + L * t1;
    c.second_moment = a * a * t0 + 2.0 * a * L * t1 + L * L * t2;
}

/// The hub's integrals of the beam's mass: J_ob = int_0^L m(x) R^2 dx and S_ob = int_0^L m(x) R dx (R = a + x cb),
/// from section's taper or profile (m: the reference mass per length, 1 with a profile).
void hub_moments(BeamMatrices& b, bool profile, bool cone, double m, double L, double a, double cb,
                 const SectionAtNodes& section)
{
    const double r1 = section.r1, first_moment = section.first_moment, second_moment = section.second_moment;
    // In closed form for the taper (with a precone's R = a + x cb).
    b.J_ob = profile ? L * second_moment
             : cone  ? m * L *
                          (a * a * (1.0 + 0.5 * r1) + a * cb * L * (1.0 + 2.0 * r1 / 3.0) +
                           cb * cb * L * L * (1.0 / 3.0 + 0.25 * r1))
                    : m * ((std::pow(a + L, 3) - std::pow(a, 3)) / 3.0 +
                           r1 * L * (a * a / 2.0 + 2.0 * a * L / 3.0 + L * L / 4.0));
    b.S_ob = profile ? L * first_moment : m * (a * L + cb * L * L / 2.0 + r1 * L * (a / 2.0 + cb * L / 3.0));
}

/// The shape functions at the tip, for the tip's displacements and slope: Phi_x(L), Phi_y(L) and Phi_y'(L).
void tip_shape_values(BeamMatrices& b, const FieldBasis& axial, const FieldBasis& transverse, int nx, int ny, double L)
{
    b.Phi_x_L.resize(nx);
    b.Phi_y_L.resize(ny);
    b.Phi_y1_L.resize(ny);
    for (int k = 0; k < nx; ++k) b.Phi_x_L(k) = axial.at(k, 1.0).v;
    for (int k = 0; k < ny; ++k) {
        const Jet<double> f = transverse.at(k, 1.0);
        b.Phi_y_L(k) = f.v;
        b.Phi_y1_L(k) = f.d1 / L;
    }
}

}  // namespace

BeamMatrices assemble_matrices(const VariantKey& key, const Parameters& p)
{
    if (const std::string problem = key.dof_problem(); !problem.empty()) throw std::invalid_argument(problem);
    const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis();
    const int nx = key.nx, ny = key.ny;
    // Exact for the polynomial bases with a taper too: max(degree) + 2 Gauss points per piece integrate degree
    // 2 max(degree) + 3, and no integrand below exceeds the product of two pieces times a cubic in xi (the depth
    // taper's i(xi) times two second derivatives; the weights of D and G); AMM's rule is converged to round-off.
    // A profile's stations are cuts too: its values are linear on each interval between them.
    const std::vector<double> stations = p.stations;
    const QuadratureRule rule = product_rule(axial, transverse, stations);
    const int nn = static_cast<int>(rule.nodes.size());
    const auto [X, X1, Y, Y1, Y2] = node_values(axial, transverse, rule);

    // docs/model.md section 5's integrals in xi: x = L xi, dx = L dxi, Phi' = (1/L) dPhi/dxi, Phi'' = (1/L^2)
    // d2Phi/dxi2.
    const bool profile = key.extras.profile();
    // With a profile (section 11.2) the reference values are 1 and the ratios below are its distributions.
    const double L = p.L, a = p.a, m = profile ? 1.0 : p.rho * p.S, EI = profile ? 1.0 : p.E * p.I,
                 ES = profile ? 1.0 : p.E * p.S;
    const Eigen::ArrayXd xi = Eigen::Map<const Eigen::ArrayXd>(rule.nodes.data(), nn);
    const VectorXd w = Eigen::Map<const VectorXd>(rule.weights.data(), nn);
    // A precone turns the beam out of the plane: a point's arm about the spin axis is R = a + x cb (section 12).
    const double cb = key.extras.cone ? std::cos(p.precone) : 1.0;
    SectionAtNodes section = taper_at_nodes(key, p, xi);
    if (profile) profile_at_nodes(stations, p, cb, xi, section);
    const auto& [s, i, e, above, above_x, r1, first_moment, second_moment] = section;
    const VectorXd w_s = (w.array() * s).matrix();                              // m(x) dx / (m L)
    const VectorXd w_e = (w.array() * e).matrix();                              // ES(x) dx / (ES L)
    const VectorXd w_i = (w.array() * i).matrix();                              // EI(x) dx / (EI L)
    const VectorXd w_arm = (m * L * w_s.array() * (a + cb * L * xi)).matrix();  // m(x) R dx
    const VectorXd w_C = (m * w.array() * above).matrix();                      // m L above dx / L^2
    const VectorXd w_D = (0.5 * m * L * w.array() * above_x).matrix();          // m L^2 above_x / 2 dx / L^2

    BeamMatrices b;
    b.cb = cb;
    b.sb = key.extras.cone ? std::sin(p.precone) : 0.0;
    hub_moments(b, profile, key.extras.cone, m, L, a, cb, section);
    b.mass = m * L * w_s.sum();
    b.S_x = (X.transpose() * w_arm).transpose();
    b.S_y = (Y.transpose() * w_arm).transpose();
    b.M1 = m * L * weighted_gram(X, w_s);
    b.M2 = m * L * weighted_gram(Y, w_s);
    b.M3 = m * L * weighted_product(X, w_s, Y);
    b.K1 = ES / L * weighted_gram(X1, w_e);
    b.K2 = EI / (L * L * L) * weighted_gram(Y2, w_i);
    b.C = weighted_gram(Y1, w_C);
    b.D = weighted_gram(Y1, w_D);
    b.G = a * b.C + cb * b.D;

    b.P_x = m * L * (X.transpose() * w_s).transpose();
    b.P_y = m * L * (Y.transpose() * w_s).transpose();
    tip_shape_values(b, axial, transverse, nx, ny, L);
    b.H_L = weighted_gram(Y1, w) / L;
    if (key.out_of_plane()) {
        // Section 12.3: the flapwise and twist fields, and the in-plane bending about the chord turned by the pitch.
        b.o = assemble_out_of_plane(key, p);
        b.K2 = b.o.K_yy;
    }
    return b;
}

namespace {

/// docs/model.md sections 5 and 11's M and Q from constant matrices: section 5's beam matrices with the tip body
/// added (its translation to S_x, S_y, M1, M2, M3, G, its rotation to J_o, S_y and the B-rate mass M2r), the weight's
/// W_o, W_x, W_y, W_H and the damping matrices. Order zero drops G and W_H (no foreshortening). Its exact Jacobian is
/// the derivative of each block of Q and M, written from the same matrices (never from the generator's kernels).
class AssembledModel final : public Model, ExactJacobian {
public:
    AssembledModel(const VariantKey& key, const Parameters& p)
        : Model(key, p),
          fields_(key, p),
          a_(coordinates().first(FieldKind::axial)),
          b_(coordinates().first(FieldKind::inplane)),
          nx_(coordinates().count(FieldKind::axial)),
          ny_(coordinates().count(FieldKind::inplane))
    {
        const BeamMatrices c = assemble_matrices(key, p);
        // The beam with the terms the variant carries (runtime/src/models/assembled/terms/); a term it does not carry
        // contributes nothing, whatever its parameter says (as in the generator).
        m_ = model_matrices({key, p, c});
        M2_G_ = key.order == Order::zero ? m_.M2 : MatrixXd(m_.M2 - m_.G);
        K1_ = c.K1;
        K2_ = c.K2;
        S_x_T_ = m_.S_x.transpose();
        S_y_T_ = m_.S_y.transpose();

        if (key.drive == Drive::prescribed) {  // paper eq. 57: M = blockdiag(M1, M2r), constant
            M_prescribed_ = RowMajorMatrix::Zero(nq(), nq());
            M_prescribed_.block(a_, a_, nx_, nx_) = m_.M1;
            M_prescribed_.block(b_, b_, ny_, ny_) = m_.M2r;
        }
    }

    const char* source() const override { return "assembled"; }
    bool mass_is_constant() const override { return key().drive == Drive::prescribed; }

    /// Zeros of M1 and M2 (the bands of FEM and BSIM, AMM's orthogonality) are exact: the shape functions
    /// vanish identically outside their support.
    std::string mass_pattern() const override { return assembled_mass_pattern(*this); }

    void mass(const HubInput&, const double* q, double* M) const override
    {
        const int n = nq();
        if (key().drive == Drive::prescribed) {
            std::copy(M_prescribed_.data(), M_prescribed_.data() + n * n, M);
            return;
        }
        const ConstVector A(q + a_, nx_), B(q + b_, ny_);
        Eigen::Map<RowMajorMatrix> Mm(M, n, n);
        Mm.setZero();
        Mm(0, 0) = M11(A, B);
        // Row 0: M12 = -(M3 B)^T, M13 = S_y + A^T M3; column 0 is its transpose (M21, M31).
        Mm.row(0).segment(a_, nx_).noalias() = -B.transpose() * m_.M3.transpose();
        Mm.row(0).segment(b_, ny_).noalias() = A.transpose() * m_.M3;
        Mm.row(0).segment(b_, ny_) += m_.S_y;
        Mm.col(0).tail(n - 1) = Mm.row(0).tail(n - 1).transpose();
        Mm.block(a_, a_, nx_, nx_) = m_.M1;
        Mm.block(b_, b_, ny_, ny_) = m_.M2r;
    }

    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double theta_dot = torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + a_, nx_), B(q + b_, ny_), A_dot(qd + a_, nx_), B_dot(qd + b_, ny_);
        Vector Q_A(Q + a_, nx_), Q_B(Q + b_, ny_);
        const double w2 = theta_dot * theta_dot, w = 2.0 * theta_dot;

        // Q_A = theta_dot^2 (S_x^T + M1 A) + 2 theta_dot M3 B_dot - K1 A
        Q_A.noalias() = w2 * (m_.M1 * A);
        Q_A += w2 * S_x_T_;
        Q_A.noalias() += w * (m_.M3 * B_dot);
        Q_A.noalias() -= K1_ * A;
        // Q_B = theta_dot^2 (M2 - G) B - 2 theta_dot M3^T A_dot - K2 B
        Q_B.noalias() = w2 * (M2_G_ * B);
        Q_B.noalias() -= w * (m_.M3.transpose() * A_dot);
        Q_B.noalias() -= K2_ * B;

        if (torque) {
            // Q_theta = tau - 2 theta_dot (S_x A_dot + A^T M1 A_dot + B^T (M2 - G) B_dot)
            Q[0] = u.tau - w * (m_.S_x.dot(A_dot) + A.dot(m_.M1.lazyProduct(A_dot)) + B.dot(M2_G_.lazyProduct(B_dot)));
        } else {
            // Paper eq. 57: the known theta_ddot moves to the right: Q_A - M21 theta_ddot, Q_B - M31 theta_ddot.
            Q_A.noalias() += u.theta_ddot * (m_.M3 * B);
            Q_B.noalias() -= u.theta_ddot * (m_.M3.transpose() * A);
            Q_B -= u.theta_ddot * S_y_T_;
        }

        if (m_.g != 0.0) {
            // -dU_g/dq (section 11.3): Q_A -= g sin W_x^T, Q_B += g (sin W_H B - cos W_y^T),
            // Q_theta -= g (cos (W_o + W_x A - 1/2 B^T W_H B) - sin W_y B).
            const double theta = torque ? q[0] : u.theta, gs = m_.g * std::sin(theta), gc = m_.g * std::cos(theta);
            Q_A -= gs * m_.W_x.transpose();
            Q_B.noalias() += gs * (m_.W_H * B);
            Q_B -= gc * m_.W_y.transpose();
            if (torque) Q[0] -= gc * (m_.W_o + m_.W_x.dot(A) - 0.5 * B.dot(m_.W_H.lazyProduct(B))) - gs * m_.W_y.dot(B);
        }
        if (m_.damped) {
            // -dD/dqd (section 11.4): Rayleigh damping of the elastic rates; the hub's rate is not damped.
            Q_A.noalias() -= m_.D_A * A_dot;
            Q_B.noalias() -= m_.D_B * B_dot;
        }
    }

    /// dQ/dtheta of the prescribed form with gravity: U_g is the only place theta enters.
    void forces_theta(const HubInput& u, const double* q, const double*, double* dQdtheta) const override
    {
        std::fill_n(dQdtheta, nq(), 0.0);
        if (m_.g == 0.0 || key().drive == Drive::torque) return;
        const ConstVector B(q + b_, ny_);
        Vector dA(dQdtheta + a_, nx_), dB(dQdtheta + b_, ny_);
        const double gs = m_.g * std::sin(u.theta), gc = m_.g * std::cos(u.theta);
        dA = -gc * m_.W_x.transpose();
        dB.noalias() = gc * (m_.W_H * B);
        dB += gs * m_.W_y.transpose();
    }

    const ExactJacobian* jacobian() const override { return this; }

    /// The derivatives of eqs. 54 to 56 (with 57's theta_ddot terms, the weight and the damping) block by block.
    void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                           double* dQdu) const override
    {
        const int n = nq();
        Eigen::Map<RowMajorMatrix> Jq(dQdq, n, n), Jqd(dQdqd, n, n), Ju(dQdu, n, drive_value_count);
        Jq.setZero();
        Jqd.setZero();
        Ju.setZero();
        const bool torque = key().drive == Drive::torque;
        const double theta_dot = torque ? qd[0] : u.theta_dot, w2 = theta_dot * theta_dot, w = 2.0 * theta_dot;
        const ConstVector A(q + a_, nx_), B(q + b_, ny_), A_dot(qd + a_, nx_), B_dot(qd + b_, ny_);
        // dQ_A/dA, dQ_B/dB and the Coriolis couplings dQ_A/dB_dot = 2 theta_dot M3, dQ_B/dA_dot = -2 theta_dot M3^T.
        Jq.block(a_, a_, nx_, nx_) = w2 * m_.M1 - K1_;
        Jq.block(b_, b_, ny_, ny_) = w2 * M2_G_ - K2_;
        Jqd.block(a_, b_, nx_, ny_) = w * m_.M3;
        Jqd.block(b_, a_, ny_, nx_) = -w * m_.M3.transpose();
        // dQ_A/dtheta_dot and dQ_B/dtheta_dot: a column of dQ/dqd under torque, of dQ/du under a prescribed drive.
        auto by_rate = torque ? Jqd.col(0) : Ju.col(drive_column(DriveValue::theta_dot));
        by_rate.segment(a_, nx_) = w * (S_x_T_ + m_.M1 * A) + 2.0 * (m_.M3 * B_dot);
        by_rate.segment(b_, ny_) = w * (M2_G_ * B) - 2.0 * (m_.M3.transpose() * A_dot);
        if (torque) {
            hub_row_derivatives(theta_dot, A, B, A_dot, B_dot, Jq, Jqd);
            Ju(0, drive_column(DriveValue::tau)) = 1.0;
        } else {
            // Eq. 57's theta_ddot M3 B in Q_A and -theta_ddot (S_y^T + M3^T A) in Q_B.
            Jq.block(a_, b_, nx_, ny_) += u.theta_ddot * m_.M3;
            Jq.block(b_, a_, ny_, nx_) -= u.theta_ddot * m_.M3.transpose();
            auto by_acceleration = Ju.col(drive_column(DriveValue::theta_ddot));
            by_acceleration.segment(a_, nx_) = m_.M3 * B;
            by_acceleration.segment(b_, ny_) = -(S_y_T_ + m_.M3.transpose() * A);
        }
        if (m_.g != 0.0) weight_derivatives(torque ? q[0] : u.theta, torque, A, B, Jq);
        if (m_.damped) {
            Jqd.block(a_, a_, nx_, nx_) -= m_.D_A;
            Jqd.block(b_, b_, ny_, ny_) -= m_.D_B;
        }
    }

    /// dM/dq v under torque, where M11, M12 = -(M3 B)^T and M13 = S_y + A^T M3 (eqs. 49 to 51) hold A and B; zero
    /// under a prescribed drive.
    void mass_q_product(const HubInput&, const double* q, const double* v, double* dMv) const override
    {
        const int n = nq();
        Eigen::Map<RowMajorMatrix> D(dMv, n, n);
        D.setZero();
        if (key().drive != Drive::torque) return;
        const ConstVector A(q + a_, nx_), B(q + b_, ny_), v_A(v + a_, nx_), v_B(v + b_, ny_);
        // Row 0: v_0 dM11/dq + v_A dM12/dq + v_B dM13/dq (dM11/dA = 2 (S_x + A^T M1), dM11/dB = 2 B^T (M2 - G)).
        D.row(0).segment(a_, nx_) = (2.0 * v[0] * (S_x_T_ + m_.M1 * A) + m_.M3 * v_B).transpose();
        D.row(0).segment(b_, ny_) = (2.0 * v[0] * (M2_G_ * B) - m_.M3.transpose() * v_A).transpose();
        // Rows A and B: their column 0, M21 = -M3 B and M31 = S_y^T + M3^T A, times v_0.
        D.block(a_, b_, nx_, ny_) = -v[0] * m_.M3;
        D.block(b_, a_, ny_, nx_) = v[0] * m_.M3.transpose();
    }

    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        const bool torque = key().drive == Drive::torque;
        const double theta_dot = torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + a_, nx_), B(q + b_, ny_), A_dot(qd + a_, nx_), B_dot(qd + b_, ny_);

        // T of docs/model.md section 5 (with section 11's tip body), by degree in the flexible rates.
        const double flexible = 0.5 * A_dot.dot(m_.M1.lazyProduct(A_dot)) + 0.5 * B_dot.dot(m_.M2r.lazyProduct(B_dot));
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
        e.U = 0.5 * A.dot(K1_.lazyProduct(A)) + 0.5 * B.dot(K2_.lazyProduct(B));
        if (m_.g != 0.0) {
            const double theta = torque ? q[0] : u.theta;
            e.U += m_.g * std::sin(theta) * (m_.W_o + m_.W_x.dot(A) - 0.5 * B.dot(m_.W_H.lazyProduct(B))) +
                   m_.g * std::cos(theta) * m_.W_y.dot(B);
        }
        return e;
    }

    Tip tip(const double* q) const override { return fields_.tip(nx_ > 0 ? q + a_ : nullptr, q + b_); }

    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        const double theta_dot = key().drive == Drive::torque ? qd[0] : u.theta_dot;
        const ConstVector A(q + a_, nx_), B(q + b_, ny_), A_dot(qd + a_, nx_), B_dot(qd + b_, ny_);
        return M11(A, B) * theta_dot + gyroscopic(A, B, A_dot, B_dot);  // dT/dtheta_dot
    }

private:
    using Block = Eigen::Map<RowMajorMatrix>;

    /// The hub row's derivatives (eq. 54): Q_theta = tau - 2 theta_dot (S_x A_dot + A^T M1 A_dot + B^T (M2 - G) B_dot).
    void hub_row_derivatives(double theta_dot, const ConstVector& A, const ConstVector& B, const ConstVector& A_dot,
                             const ConstVector& B_dot, Block& Jq, Block& Jqd) const
    {
        const double w = 2.0 * theta_dot;
        const VectorXd M1_A_dot = m_.M1 * A_dot, M2_G_B_dot = M2_G_ * B_dot;
        Jq.row(0).segment(a_, nx_) = -w * M1_A_dot.transpose();
        Jq.row(0).segment(b_, ny_) = -w * M2_G_B_dot.transpose();
        Jqd(0, 0) = -2.0 * (m_.S_x.dot(A_dot) + A.dot(M1_A_dot) + B.dot(M2_G_B_dot));
        Jqd.row(0).segment(a_, nx_) = -w * (S_x_T_ + m_.M1 * A).transpose();
        Jqd.row(0).segment(b_, ny_) = -w * (M2_G_ * B).transpose();
    }

    /// The weight's share of dQ/dq (section 11.3): -d2U_g/dq2, with the hub angle among q under torque.
    void weight_derivatives(double theta, bool torque, const ConstVector& A, const ConstVector& B, Block& Jq) const
    {
        const double gs = m_.g * std::sin(theta), gc = m_.g * std::cos(theta);
        Jq.block(b_, b_, ny_, ny_) += gs * m_.W_H;
        if (!torque) return;
        // dQ_A/dtheta, dQ_B/dtheta and, U_g's Hessian being symmetric, dQ_theta/dA, dQ_theta/dB the same.
        const VectorXd by_A = -gc * m_.W_x.transpose(), by_B = gc * (m_.W_H * B) + gs * m_.W_y.transpose();
        Jq.col(0).segment(a_, nx_) = by_A;
        Jq.col(0).segment(b_, ny_) = by_B;
        Jq.row(0).segment(a_, nx_) += by_A.transpose();
        Jq.row(0).segment(b_, ny_) += by_B.transpose();
        Jq(0, 0) = gs * (m_.W_o + m_.W_x.dot(A) - 0.5 * B.dot(m_.W_H * B)) + gc * m_.W_y.dot(B);
    }

    /// M11 = J_o + 2 S_x A + A^T M1 A + B^T (M2 - G) B, J_o = J_oh + J_ob (+ the tip's m_tip (a+L)^2 + J_tip).
    double M11(const ConstVector& A, const ConstVector& B) const
    {
        return m_.J_o + 2.0 * m_.S_x.dot(A) + A.dot(m_.M1.lazyProduct(A)) + B.dot(M2_G_.lazyProduct(B));
    }

    /// The factor of theta_dot in T linear in the rates: (S_y + A^T M3) B_dot - B^T M3^T A_dot.
    double gyroscopic(const ConstVector& A, const ConstVector& B, const ConstVector& A_dot,
                      const ConstVector& B_dot) const
    {
        return m_.S_y.dot(B_dot) + A.dot(m_.M3.lazyProduct(B_dot)) - A_dot.dot(m_.M3.lazyProduct(B));
    }

    BeamFields fields_;
    int a_, b_;  // where A and B begin in q (coordinates())
    int nx_, ny_;
    // Section 5.2's matrices of the beam with the terms the variant carries (tip body, weight, damping: section 11),
    // as the terms' twins assembled them.
    ModelMatrices m_;
    MatrixXd K1_, K2_;
    MatrixXd M2_G_;                // M2 - G (first order) or M2 (zero order)
    VectorXd S_x_T_, S_y_T_;       // S_x^T, S_y^T as columns
    RowMajorMatrix M_prescribed_;  // blockdiag(M1, M2r) for the prescribed form
};

}  // namespace

std::string assembled_mass_pattern(const Model& model)
{
    const int n = model.nq();
    RowMajorMatrix M(n, n);
    model.mass(HubInput{}, std::vector<double>(static_cast<std::size_t>(n), 0.0).data(), M.data());
    const bool torque = model.key().drive == Drive::torque;
    std::string pattern;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) pattern += torque && (i == 0 || j == 0) ? 'v' : M(i, j) == 0.0 ? '0' : 'c';
    return pattern;
}

std::unique_ptr<Model> make_assembled_model(const VariantKey& key, const Parameters& p)
{
    if (key.order == Order::full)
        throw std::invalid_argument("full order has no hand-assembled form; it needs a generated variant");
    if ((key.extras.offsets || key.extras.tip_body) && key.extras.cone)
        throw std::invalid_argument(
            "section offsets and the tip body in the blade's axes (tip.inertia_flap, "
            "tip.inertia_twist, tip.offset) have no hand-assembled form with a precone; they "
            "need a generated variant");
    // Out of the plane, section 12.3's forms: the precone's projections and the coupled bending have no place in
    // section 5.2's blocks; nor have a moving hub's translation and a blade's section offsets, in the plane or out.
    if (key.out_of_plane() || key.extras.hub || key.extras.offsets) {
        return make_quadratic_form_model(key, p);
    }
    return std::make_unique<AssembledModel>(key, p);
}

}  // namespace hubbeam
