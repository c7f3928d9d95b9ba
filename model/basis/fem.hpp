// FEM: Hermite cubic (transverse) and linear (axial) elements on a uniform mesh (docs/model.md section 4),
// root node removed; one polynomial piece per element, in xi = x/L.
#pragma once

#include "common.hpp"

namespace hubbeam::fem {

/// Transverse function i (0-based; node i/2+1, deflection if i even, xi-slope if odd) on element k of n.
/// The slope DOF is du_y/dxi = L du_y/dx, so that the shape functions are pure functions of xi.
template <class T> T transverse(int i, int n, int k, const T& xi)
{
    const int node = i / 2 + 1;
    const bool slope = i % 2 == 1;
    const T s = xi * T(n) - T(k);
    const T l = frac<T>(1, n);  // element length in xi
    if (node == k + 1) return slope ? l * (s * s * s - s * s) : frac<T>(3) * s * s - frac<T>(2) * s * s * s;
    if (node == k) {
        return slope ? l * (s - frac<T>(2) * s * s + s * s * s)
                     : frac<T>(1) - frac<T>(3) * s * s + frac<T>(2) * s * s * s;
    }
    return frac<T>(0);
}

/// Axial hat function i (0-based, node i+1) on element k of n.
template <class T> T axial(int i, int n, int k, const T& xi)
{
    const int node = i + 1;
    const T s = xi * T(n) - T(k);
    if (node == k + 1) return s;
    if (node == k) return frac<T>(1) - s;
    return frac<T>(0);
}

}  // namespace hubbeam::fem
