// The equations of motion of any order-full variant by a route that shares nothing with the generator's
// expansion: T and U by quadrature of the beam's position r = R(theta) (a + x + u_x, u_y) along the beam, with
// the foreshortening u_x2(x) = -1/2 int_0^x (u_y')^2 as a nested quadrature (the inner rule's sums of slope
// products kept for each outer node), and Lagrange's equations by numerical differentiation that is exact to
// round-off (central differences in the rates, in which T is quadratic; complex steps in the coordinates). A blade's flapwise field and precone (docs/model.md section 12) are
// taken too: r = R(theta) (a + (x + u_x) cb - u_z sb, u_y, (x + u_x) sb + u_z cb), u_z' in u_x2 beside u_y'; a twist
// field, a pitch or a pre-twist (whose terms no order changes) are not.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <stdexcept>
#include <vector>

#include "basis/basis.hpp"
#include "coordinates.hpp"
#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam::test {

class KineticOracle {
public:
    KineticOracle(const VariantKey& key, const Parameters& p)
        : key_(key), p_(p), axial_(key.axial_basis()), transverse_(key.transverse_basis()), flap_(key.flap_basis())
    {
        if (key.nt > 0 || key.extras.pitch || key.extras.twist)
            throw std::invalid_argument("KineticOracle: no twist field, pitch or pre-twist");
        // Outer rule: Gauss on every polynomial piece, with points enough for |r_dot|^2 of degree about
        // 4 * degree (u_x2 squared); AMM: the converged composite rule.
        const FieldBasis& t = transverse_;
        const QuadratureRule outer = t.polynomial()
                                         ? pieces_rule(0.0, 1.0, 2 * std::max(t.degree(), axial_.degree()) + 4)
                                         : transcendental_rule(key.ny + key.nx + key.nz);
        for (std::size_t g = 0; g < outer.nodes.size(); ++g) {
            Node n;
            n.xi = outer.nodes[g];
            n.weight = outer.weights[g];
            for (int i = 0; i < key.nx; ++i) {
                const Jet<double> j = axial_.at(i, n.xi);
                n.ax.push_back(j.v);
                n.ax_d1.push_back(j.d1);
            }
            for (int j = 0; j < key.ny; ++j) {
                const Jet<double> y = transverse_.at(j, n.xi);
                n.tr.push_back(y.v);
                n.tr_d2.push_back(y.d2);
            }
            for (int j = 0; j < key.nz; ++j) {
                const Jet<double> z = flap_.at(j, n.xi);
                n.fl.push_back(z.v);
                n.fl_d2.push_back(z.d2);
            }
            // Inner rule on [0, xi] for int (u_y')^2: (u_y')^2 has degree 2 (degree - 1).
            const QuadratureRule inner = t.polynomial() ? pieces_rule(0.0, n.xi, t.degree() + 1)
                                                        : scaled(transcendental_rule(std::max(key.ny, key.nz)), n.xi);
            n.inner = inner_products(transverse_, inner);
            n.inner_flap = inner_products(flap_, inner);
            nodes_.push_back(std::move(n));
        }
    }

    /// T at coordinates q, rates qd and (prescribed drive) hub rate theta_dot, any scalar type.
    template <class S>
    S kinetic(const S* q, const S* qd, const S& theta_dot_prescribed) const
    {
        const bool torque = key_.drive == Drive::torque;
        const S theta = torque ? q[0] : S(0.3);  // the energy does not depend on theta; any angle serves
        const S w = torque ? qd[0] : theta_dot_prescribed;
        const S c = std::cos(theta), s = std::sin(theta);
        const double L = p_.L, m = p_.rho * p_.S;
        const CoordinateLayout layout = coordinate_layout(key_);
        const int a = layout.first(FieldKind::axial), b = layout.first(FieldKind::inplane);
        const int z = key_.nz > 0 ? layout.first(FieldKind::flap) : 0;
        const S *A = q + a, *B = q + b, *A_dot = qd + a, *B_dot = qd + b, *Z = q + z, *Z_dot = qd + z;
        const double cb = key_.extras.cone ? std::cos(p_.precone) : 1.0,
                     sb = key_.extras.cone ? std::sin(p_.precone) : 0.0;
        S sum = 0.0;
        for (const Node& n : nodes_) {
            S ux1 = 0.0, ux1_dot = 0.0, uy = 0.0, uy_dot = 0.0, uz = 0.0, uz_dot = 0.0;
            for (int j = 0; j < key_.nz; ++j) {
                uz += Z[j] * n.fl[j];
                uz_dot += Z_dot[j] * n.fl[j];
            }
            for (int i = 0; i < key_.nx; ++i) {
                ux1 += A[i] * n.ax[i];
                ux1_dot += A_dot[i] * n.ax[i];
            }
            for (int j = 0; j < key_.ny; ++j) {
                uy += B[j] * n.tr[j];
                uy_dot += B_dot[j] * n.tr[j];
            }
            // u_x2 = -1/2 int_0^x (du_y/dx)^2 dx' = -1/(2L) int_0^xi (du_y/dxi)^2 dxi', and its time derivative: the
            // inner rule's sum of w_k (sum_j B_j phi_j'(xi_k))^2 with the square multiplied out, sum_ij B_i B_j
            // (sum_k w_k phi_i'(xi_k) phi_j'(xi_k)), whose inner sums do not depend on the state.
            const S ux2 = -(quadratic(n.inner, B, B, key_.ny) + quadratic(n.inner_flap, Z, Z, key_.nz)) / (2.0 * L);
            const S ux2_dot = -(quadratic(n.inner, B, B_dot, key_.ny) + quadratic(n.inner_flap, Z, Z_dot, key_.nz)) / L;
            // r = R(theta) p with p = (a + (x + u_x) cb - u_z sb, u_y, (x + u_x) sb + u_z cb); r_dot = w R'(theta) p +
            // R(theta) p_dot, and the component along the axis p_z_dot.
            const S along = L * n.xi + ux1 + ux2, along_dot = ux1_dot + ux2_dot;
            const S px = p_.a + along * cb - uz * sb, py = uy;
            const S px_dot = along_dot * cb - uz_dot * sb, py_dot = uy_dot, pz_dot = along_dot * sb + uz_dot * cb;
            const S rx_dot = w * (-s * px - c * py) + (c * px_dot - s * py_dot);
            const S ry_dot = w * (c * px - s * py) + (s * px_dot + c * py_dot);
            sum += n.weight * m * (rx_dot * rx_dot + ry_dot * ry_dot + pz_dot * pz_dot);
        }
        return 0.5 * p_.J_oh * w * w + 0.5 * L * sum;
    }

    /// U = 1/2 int (ES u_x1'^2 + EI u_y''^2 + EI_flap u_z''^2) dx.
    template <class S>
    S potential(const S* q) const
    {
        const double L = p_.L, ES = p_.E * p_.S, EI = p_.E * p_.I, EI_flap = p_.E * p_.I_flap;
        const CoordinateLayout layout = coordinate_layout(key_);
        const int a = layout.first(FieldKind::axial), b = layout.first(FieldKind::inplane);
        const int z = key_.nz > 0 ? layout.first(FieldKind::flap) : 0;
        S sum = 0.0;
        for (const Node& n : nodes_) {
            S strain = 0.0, curvature = 0.0, flap = 0.0;
            for (int i = 0; i < key_.nx; ++i) strain += q[a + i] * n.ax_d1[i] / L;
            for (int j = 0; j < key_.ny; ++j) curvature += q[b + j] * n.tr_d2[j] / (L * L);
            for (int j = 0; j < key_.nz; ++j) flap += q[z + j] * n.fl_d2[j] / (L * L);
            sum += n.weight * (ES * strain * strain + EI * curvature * curvature + EI_flap * flap * flap);
        }
        return 0.5 * L * sum;
    }

    /// M = d2T/dqd2: second central differences, exact since T is quadratic in the rates; each pair once, the
    /// differences being symmetric in i and j (the generated M is checked whole against it).
    Eigen::MatrixXd mass(const Eigen::VectorXd& q, const HubInput& u) const
    {
        const int n = key_.nq();
        Eigen::MatrixXd M(n, n);
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
        for (int i = 0; i < n; ++i)
            for (int j = i; j < n; ++j) {
                const auto T = [&](double si, double sj) {
                    Eigen::VectorXd v = zero;
                    v[i] += si;
                    v[j] += sj;
                    return kinetic<double>(q.data(), v.data(), u.theta_dot);
                };
                M(i, j) = M(j, i) = (T(1, 1) - T(1, -1) - T(-1, 1) + T(-1, -1)) / 4.0;
            }
        return M;
    }

    /// Q = tau e_theta + dT/dq - (d2T/dqd dq) qd - (d2T/dqd dtheta_dot) theta_ddot - dU/dq.
    Eigen::VectorXd forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const HubInput& u) const
    {
        using C = std::complex<double>;
        const int n = key_.nq();
        const double h = 1e-30;  // complex step: no subtraction, so any small step is exact to round-off
        const auto complexify = [](const Eigen::VectorXd& v) { return Eigen::VectorXcd(v.cast<C>()); };
        // dT/dqd_i as a function of (q, qd, theta_dot), by a central difference exact for a quadratic.
        const auto momentum = [&](int i, const Eigen::VectorXcd& qc, const C& w) {
            Eigen::VectorXcd plus = complexify(qd), minus = complexify(qd);
            plus[i] += 1.0;
            minus[i] -= 1.0;
            return (kinetic<C>(qc.data(), plus.data(), w) - kinetic<C>(qc.data(), minus.data(), w)) / 2.0;
        };
        Eigen::VectorXd Q(n);
        for (int i = 0; i < n; ++i) {
            Eigen::VectorXcd qi = complexify(q);
            qi[i] += C(0.0, h);
            const Eigen::VectorXcd qdc = complexify(qd);
            const double dT_dq = kinetic<C>(qi.data(), qdc.data(), C(u.theta_dot)).imag() / h;
            const double dU_dq = potential<C>(qi.data()).imag() / h;
            // (d/dq of dT/dqd_i) along qd: one complex step in the direction qd.
            Eigen::VectorXcd along = complexify(q);
            for (int k = 0; k < n; ++k) along[k] += C(0.0, h * qd[k]);
            double Q_i = dT_dq - momentum(i, along, C(u.theta_dot)).imag() / h - dU_dq;
            if (key_.drive == Drive::torque) {
                if (i == 0) Q_i += u.tau;
            } else {
                Q_i -= momentum(i, complexify(q), C(u.theta_dot, h)).imag() / h * u.theta_ddot;
            }
            Q[i] = Q_i;
        }
        return Q;
    }

private:
    struct Node {
        double xi, weight;
        std::vector<double> ax, ax_d1, tr, tr_d2, fl, fl_d2;
        // sum_k w_k phi_i'(xi_k) phi_j'(xi_k) over the inner rule on [0, xi]: [i * ny + j]; the flapwise field's.
        std::vector<double> inner, inner_flap;
    };

    /// The inner rule's sums of w_k phi_i'(xi_k) phi_j'(xi_k) for the functions of f, row by row.
    static std::vector<double> inner_products(const FieldBasis& f, const QuadratureRule& inner)
    {
        const int n = f.size();
        std::vector<double> slopes, out(static_cast<std::size_t>(n * n), 0.0);
        for (const double x : inner.nodes)
            for (int j = 0; j < n; ++j) slopes.push_back(f.at(j, x).d1);
        for (std::size_t k = 0; k < inner.nodes.size(); ++k)
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    out[static_cast<std::size_t>(i * n + j)] +=
                        inner.weights[k] * slopes[k * n + static_cast<std::size_t>(i)] * slopes[k * n + static_cast<std::size_t>(j)];
        return out;
    }

    /// sum_ij a_i H_ij b_j.
    template <class S>
    static S quadratic(const std::vector<double>& H, const S* a, const S* b, int n)
    {
        S sum = 0.0;
        for (int i = 0; i < n; ++i) {
            S row = 0.0;
            for (int j = 0; j < n; ++j) row += H[static_cast<std::size_t>(i * n + j)] * b[j];
            sum += a[i] * row;
        }
        return sum;
    }

    /// Gauss with `points` nodes on each piece of [lo, hi] between the bases' interval ends.
    QuadratureRule pieces_rule(double lo, double hi, int points) const
    {
        std::vector<double> cuts{lo, hi};
        for (const FieldBasis* f : {&axial_, &transverse_, &flap_})
            for (int k = 1; f->size() > 0 && k < f->intervals(); ++k) {
                const double c = static_cast<double>(k) / f->intervals();
                if (c > lo && c < hi) cuts.push_back(c);
            }
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double a, double b) { return b - a < 1e-14; }), cuts.end());
        if (cuts.size() < 2) return {};
        return composite_gauss_legendre(cuts, points);
    }

    /// A rule on [0, 1] mapped onto [0, hi].
    static QuadratureRule scaled(QuadratureRule r, double hi)
    {
        for (double& x : r.nodes) x *= hi;
        for (double& w : r.weights) w *= hi;
        return r;
    }

    VariantKey key_;
    Parameters p_;
    FieldBasis axial_, transverse_, flap_;
    std::vector<Node> nodes_;
};

}  // namespace hubbeam::test
