// AMM: assumed modes of the clamped-free beam (docs/model.md section 4), axial sines and transverse bending
// modes in the cancellation-free form, as functions of xi = x/L.
#pragma once

#include <cmath>
#include <numbers>

#include "common.hpp"

namespace hubbeam::amm {

/// b_i = beta_i L, the i-th root (i >= 1) of 1 + cos z cosh z = 0, by Newton on cos z + 1/cosh z = 0
/// (the same roots, without the overflow of cosh).
inline double cantilever_root(int i)
{
    double z = i == 1 ? 1.8751 : i == 2 ? 4.6941 : (i - 0.5) * std::numbers::pi;
    for (int it = 0; it < 50; ++it) {
        const double sech = 1.0 / std::cosh(z);
        const double f = std::cos(z) + sech;
        const double df = -std::sin(z) - sech * std::tanh(z);
        const double dz = f / df;
        z -= dz;
        if (std::abs(dz) < 1e-15 * z) break;
    }
    return z;
}

/// Constants of the stable mode form phi = cos z - s sin z - A e^(z-b) - (1+s)/2 e^(-z), z = b xi.
struct Mode {
    double b, s, A;
};

inline Mode mode(int i)
{
    const double b = cantilever_root(i);
    const double eb = std::exp(-b), e2b = std::exp(-2.0 * b);
    const double den = 1.0 + e2b + 2.0 * eb * std::cos(b);
    return {b, (1.0 - e2b - 2.0 * eb * std::sin(b)) / den, (eb + std::cos(b) + std::sin(b)) / den};
}

/// Axial mode i (1-based): sin((2i-1) pi xi / 2).
template <class T> T axial(int i, const T& xi)
{
    using std::sin;
    return sin(T((2 * i - 1) * std::numbers::pi / 2) * xi);
}

/// Transverse clamped-free mode with constants md, normalised so that int_0^1 phi^2 dxi = 1.
template <class T> T transverse(const Mode& md, const T& xi)
{
    using std::cos, std::exp, std::sin;
    const T z = T(md.b) * xi;
    return cos(z) - T(md.s) * sin(z) - T(md.A) * exp(z - T(md.b)) - T(0.5 * (1.0 + md.s)) * exp(-z);
}

}  // namespace hubbeam::amm
