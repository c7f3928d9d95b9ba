// BSIM: cubic B-splines on n uniform intervals of xi (docs/model.md section 4), in two constructions of the
// same spline space: the paper's combination of uniform splines (eq. 41-43) and the clamped open-knot
// (Cox-de Boor) basis. Each function is returned as its polynomial piece on interval k.
#pragma once

#include "common.hpp"

namespace hubbeam::bsim {

/// The piece of phi3 (paper eq. 42) on eta in [j, j+1], j in {-2,-1,0,1}; zero elsewhere.
template <class T> T phi3_piece(int j, const T& eta)
{
    const T one = frac<T>(1), two = frac<T>(2), sixth = frac<T>(1, 6);
    switch (j) {
    case -2: return sixth * ipow(eta + two, 3);
    case -1: return sixth * (ipow(eta + two, 3) - frac<T>(4) * ipow(one + eta, 3));
    case 0: return sixth * (ipow(two - eta, 3) - frac<T>(4) * ipow(one - eta, 3));
    case 1: return sixth * ipow(two - eta, 3);
    default: return frac<T>(0);
    }
}

/// Uniform spline B_j(xi) = phi3(n xi - j) on interval k of n (support: intervals j-2 .. j+1).
template <class T> T uniform(int j, int n, int k, const T& xi) { return phi3_piece(k - j, xi * T(n) - T(j)); }

/// Paper eq. (41), i in -1..n+1, with slopes per knot interval: phi_-1 and phi_n carry the end values, phi_0 and
/// phi_(n+1) the end slopes d/deta (eta = n xi: their coordinates are h du_y/dx, h = L/n the knot spacing), all
/// other members vanish there with their slopes. Needs n >= 3.
/// Why per knot interval: so the slope members are of the others' size whatever n. Scaled to slopes per unit xi
/// (d/dxi = n d/deta) they shrank as 1/n, and the mass matrix's condition number grew as n^2 (1.2e6 at Ny = 64,
/// where this one stays below 330).
template <class T> T paper(int i, int n, int k, const T& xi)
{
    auto B = [&](int j) { return uniform(j, n, k, xi); };
    const T half = frac<T>(1, 2);
    if (i == -1) return frac<T>(3, 2) * B(0);
    if (i == 0) return half * B(0) - frac<T>(2) * B(-1);
    if (i == 1) return B(1) - half * B(0) + B(-1);
    if (i == n - 1) return B(n - 1) - half * B(n) + B(n + 1);
    if (i == n) return frac<T>(3, 2) * B(n);
    if (i == n + 1) return frac<T>(2) * B(n + 1) - half * B(n);
    return B(i);
}

/// Clamped open-knot cubic B-spline N_i (i in 0..n+2) on interval k of n, by Cox-de Boor's recursion
/// on the knots 0,0,0,0,1/n,...,(n-1)/n,1,1,1,1.
template <class T> T open(int i, int n, int k, const T& xi)
{
    auto knot = [n](int j) { return j <= 3 ? 0 : j >= n + 3 ? n : j - 3; };  // in units of 1/n
    // N_{j,p} restricted to interval k (which is [knot k+3, knot k+4]).
    auto rec = [&](auto&& self, int j, int p) -> T {
        if (p == 0) return frac<T>(j == k + 3 ? 1 : 0);
        T r = frac<T>(0);
        const int d1 = knot(j + p) - knot(j), d2 = knot(j + p + 1) - knot(j + 1);
        if (d1 != 0) r = r + (xi * T(n) - T(knot(j))) / T(d1) * self(self, j, p - 1);
        if (d2 != 0) r = r + (T(knot(j + p + 1)) - xi * T(n)) / T(d2) * self(self, j + 1, p - 1);
        return r;
    };
    return rec(rec, i, 3);
}

}  // namespace hubbeam::bsim
