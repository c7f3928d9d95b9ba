// BIM: Bernstein polynomials J_{m,i}(xi) = C(m,i) xi^i (1-xi)^(m-i) (docs/model.md section 4, paper eq. 29).
#pragma once

#include "common.hpp"

namespace hubbeam::bim {

template <class T> T bernstein(int m, int i, const T& xi)
{
    return T(binomial(m, i)) * ipow(xi, i) * ipow(frac<T>(1) - xi, m - i);
}

/// Transverse function i (0-based): J_{Ny+1, i+2}; the dropped J_{m,0}, J_{m,1} violate the clamp.
template <class T> T transverse(int i, int ny, const T& xi) { return bernstein(ny + 1, i + 2, xi); }

/// Axial function i (0-based): J_{Nx, i+1}; only J_{Nx,0} is nonzero at the root.
template <class T> T axial(int i, int nx, const T& xi) { return bernstein(nx, i + 1, xi); }

}  // namespace hubbeam::bim
