// Oracles several test files share, written for the tests alone: Q of Lagrange's equations by differences of a
// model's own energies, the roots of the tip-mass cantilever's frequency equation, and the roots of any frequency
// equation by a scan and bisection.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <vector>

#include <hubbeam/model.hpp>

namespace hubbeam::test {

/// Q of Lagrange's equations from energy() alone (docs/model.md section 5.1): tau e_theta + dT/dq - dp/dt - dU/dq,
/// p = dT/dqd, dp/dt at qdd = 0 along theta_dot(t) (prescribed). T, U and p are polynomials of degree <= 2 along
/// every direction taken, except U along a torque variant's theta under gravity, which is affine in (sin theta,
/// cos theta): there the central difference over 2 sin(1) in place of 2 is exact (and without gravity U does not
/// depend on theta at all). State: any type with members u (HubInput), q and qd (Eigen vectors).
template <class State>
Eigen::VectorXd lagrange_forces(const Model& model, const State& s)
{
    using Eigen::VectorXd;
    const int n = model.nq();
    const bool torque = model.key().drive == Drive::torque;
    const auto T = [&](const HubInput& u, const VectorXd& q, const VectorXd& qd) {
        return model.energy(u, q.data(), qd.data()).kinetic();
    };
    const auto U = [&](const VectorXd& q) { return model.energy(s.u, q.data(), s.qd.data()).U; };
    const auto p = [&](const HubInput& u, const VectorXd& q) {
        VectorXd r(n);
        for (int j = 0; j < n; ++j) {
            const VectorXd e = VectorXd::Unit(n, j);
            r(j) = 0.5 * (T(u, q, s.qd + e) - T(u, q, s.qd - e));
        }
        return r;
    };
    HubInput later = s.u, earlier = s.u;  // theta_dot(t +- 1 s) along theta_ddot (theta does not enter T)
    later.theta_dot += s.u.theta_ddot;
    earlier.theta_dot -= s.u.theta_ddot;
    const VectorXd p_dot = 0.5 * (p(later, s.q + s.qd) - p(earlier, s.q - s.qd));
    VectorXd Q(n);
    for (int j = 0; j < n; ++j) {
        const VectorXd e = VectorXd::Unit(n, j);
        const double dT = 0.5 * (T(s.u, s.q + e, s.qd) - T(s.u, s.q - e, s.qd));
        const double dU = (U(s.q + e) - U(s.q - e)) / (torque && j == 0 ? 2.0 * std::sin(1.0) : 2.0);
        Q(j) = dT - p_dot(j) - dU;
    }
    if (torque) Q(0) += s.u.tau;
    return Q;
}

/// The first `count` roots z of 1 + cos z cosh z + mu z (cos z sinh z - sin z cosh z) = 0 (a cantilever with a
/// point mass mu m L at its tip, no rotary inertia; omega = z^2 sqrt(EI / (m L^4))), by bisection between the sign
/// changes of a fine scan. Divided by cosh z, which keeps the sign and the size finite.
inline std::vector<double> tip_mass_roots(double mu, int count)
{
    const auto f = [mu](double z) {
        return 1.0 / std::cosh(z) + std::cos(z) + mu * z * (std::cos(z) * std::tanh(z) - std::sin(z));
    };
    std::vector<double> roots;
    for (double z = 0.05; static_cast<int>(roots.size()) < count; z += 0.01) {
        double lo = z, hi = z + 0.01;
        if ((f(lo) < 0.0) == (f(hi) < 0.0)) continue;
        for (int k = 0; k < 100; ++k) {
            const double mid = 0.5 * (lo + hi);
            ((f(lo) < 0.0) == (f(mid) < 0.0) ? lo : hi) = mid;
        }
        roots.push_back(0.5 * (lo + hi));
    }
    return roots;
}

/// The roots of f in (first, last]: each sign change between `steps` equal intervals from first, bisected until the
/// bracket is within `relative` of its upper end (at most 200 halvings).
inline std::vector<double> bracketed_roots(const std::function<double(double)>& f, double first, double last,
                                           int steps, double relative)
{
    std::vector<double> roots;
    double w0 = first, f0 = f(w0);
    for (int n = 1; n <= steps; ++n) {
        const double w1 = first + (last - first) * n / steps, f1 = f(w1);
        if ((f0 < 0.0) != (f1 < 0.0)) {
            double lo = w0, hi = w1, flo = f0;
            for (int it = 0; it < 200 && hi - lo > relative * hi; ++it) {
                const double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm < 0.0) == (flo < 0.0)) {
                    lo = mid, flo = fm;
                } else {
                    hi = mid;
                }
            }
            roots.push_back(0.5 * (lo + hi));
        }
        w0 = w1, f0 = f1;
    }
    return roots;
}

}  // namespace hubbeam::test
