// Lagrange's equations: d/dt(dT/dqd) - dT/dq + dU/dq = force, written as M qdd = Q.
#include "lagrange.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

Equations lagrange(const ex& T, const ex& U, const Coordinates& c)
{
    const std::size_t n = c.q.size();
    Equations e;
    e.M.resize(n * n);
    e.Q.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const ex p = T.diff(c.qd[i]);  // generalized momentum
        for (std::size_t j = 0; j < n; ++j) e.M[i * n + j] = p.diff(c.qd[j]).expand();
        ex Q = c.force[i] + T.diff(c.q[i]) - U.diff(c.q[i]);
        for (std::size_t j = 0; j < n; ++j) Q -= p.diff(c.q[j]) * c.qd[j];
        for (const auto& [u, u_dot] : c.driven) Q -= p.diff(u) * u_dot;
        e.Q[i] = Q.expand();
    }
    const symbol lambda("lambda");
    exmap scale;
    for (const symbol& v : c.qd) scale[v] = lambda * v;
    const ex Tl = T.subs(scale).expand();
    e.T2 = Tl.coeff(lambda, 2);
    e.T1 = Tl.coeff(lambda, 1);
    e.T0 = Tl.coeff(lambda, 0);
    e.U = U;
    e.momentum = T.diff(c.spin).expand();
    return e;
}

Poly PolyCoordinates::d_dq(const Poly& P, std::size_t i) const
{
    Poly d = P.diff(q[i]);
    if (static_cast<int>(i) == angle) {  // d/dtheta = d/dtheta + cos d/dsin - sin d/dcos
        d += P.diff(angle_sin).times(angle_cos);
        d -= P.diff(angle_cos).times(angle_sin);
    }
    return d;
}

PolyEquations lagrange(const Poly& T, const Poly& U, const PolyCoordinates& c)
{
    const std::size_t n = c.q.size();
    PolyEquations e;
    e.M.resize(n * n);
    e.Q.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Poly p = T.diff(c.qd[i]);  // generalized momentum
        for (std::size_t j = 0; j < n; ++j) e.M[i * n + j] = p.diff(c.qd[j]);
        Poly Q = c.force[i];
        Q += c.d_dq(T, i);
        Q -= c.d_dq(U, i);
        Q -= c.dissipation.diff(c.qd[i]);
        for (std::size_t j = 0; j < n; ++j) Q -= c.d_dq(p, j).times(c.qd[j]);
        for (const auto& [u, u_dot] : c.driven) Q -= p.diff(u).times(u_dot);
        if (c.angle_rate >= 0) {  // d/dt sin = cos theta_dot, d/dt cos = -sin theta_dot
            Q -= p.diff(c.angle_sin).times(c.angle_cos).times(c.angle_rate);
            Q += p.diff(c.angle_cos).times(c.angle_sin).times(c.angle_rate);
        }
        e.Q[i] = std::move(Q);
    }
    e.T2 = T.of_degree(c.qd, 2);
    e.T1 = T.of_degree(c.qd, 1);
    e.T0 = T.of_degree(c.qd, 0);
    e.U = U;
    e.momentum = T.diff(c.spin);
    return e;
}

}  // namespace hubbeam::gen
