// Stage "lagrange": Lagrange's equations of the second kind by symbolic differentiation of T and U.
#pragma once

#include <utility>
#include <vector>

#include <ginac/ginac.h>

#include "poly.hpp"

namespace hubbeam::gen {

struct Coordinates {
    std::vector<GiNaC::symbol> q, qd;
    /// Inputs that T depends on and whose time derivative is known, e.g. (theta_dot, theta_ddot) under a
    /// prescribed rotation: d/dt of dT/dqd then gains d2T/dqd du * u_dot.
    std::vector<std::pair<GiNaC::symbol, GiNaC::symbol>> driven;
    /// Generalized force on each coordinate (tau on theta, zero on A and B).
    std::vector<GiNaC::ex> force;
    /// The hub rate, for the angular momentum dT/dtheta_dot.
    GiNaC::symbol spin;
};

/// M qdd = Q, with T split by degree in qd and the angular momentum.
struct Equations {
    std::vector<GiNaC::ex> M;  // nq x nq, row-major: d2T/dqd_i dqd_j
    std::vector<GiNaC::ex> Q;  // force + dT/dq - sum_j d2T/dqd dq_j qd_j - sum d2T/dqd du u_dot - dU/dq
    GiNaC::ex T2, T1, T0, U;
    GiNaC::ex momentum;
};

Equations lagrange(const GiNaC::ex& T, const GiNaC::ex& U, const Coordinates& c);

/// The same for T and U as Polys: coordinates, rates and drive values are indices of the Polys' variables. This
/// is the generator's route (fast at scale); the expression route above is its test oracle.
struct PolyCoordinates {
    std::vector<int> q, qd;
    std::vector<std::pair<int, int>> driven;  // (u, u_dot)
    std::vector<Poly> force;
    int spin = -1;
    /// The dissipation function D: the force on q_i gains -dD/dqd_i (zero: no damping).
    Poly dissipation;
    /// Where q_i's sine and cosine are variables of their own (a torque variant's theta under gravity): q index,
    /// sin and cos variables; -1 if none. Derivatives by q_i then follow the chain rule through them.
    int angle = -1, angle_sin = -1, angle_cos = -1;
    /// Where the angle is the drive's (a prescribed theta, no coordinate) but sin and cos are variables: theta_dot's
    /// variable, through which d/dt of the momenta reaches them; -1 otherwise.
    int angle_rate = -1;

    /// dP/dq_i, through sin and cos of the angle coordinate.
    Poly d_dq(const Poly& P, std::size_t i) const;
};
struct PolyEquations {
    std::vector<Poly> M, Q;  // as Equations
    Poly T2, T1, T0, U;
    Poly momentum;
};
PolyEquations lagrange(const Poly& T, const Poly& U, const PolyCoordinates& c);

}  // namespace hubbeam::gen
