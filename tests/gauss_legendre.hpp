// Gauss-Legendre quadrature written for the tests alone, so that their oracles do not lean on the project's own
// quadrature (model/basis/quadrature.hpp).
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace hubbeam::test {

/// Nodes and weights on [-1, 1].
struct GaussRule {
    std::vector<double> x, w;
};

/// The n-point rule: Newton's method on P_n from the three-term recurrence.
inline GaussRule gauss_legendre(int n)
{
    GaussRule r;
    for (int i = 1; i <= n; ++i) {
        double z = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5)), dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;  // P_0, P_1, then the recurrence up to P_n
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            const double step = p1 / dp;
            z -= step;
            if (std::abs(step) < 1e-16) break;
        }
        r.x.push_back(z);
        r.w.push_back(2.0 / ((1.0 - z * z) * dp * dp));
    }
    return r;
}

}  // namespace hubbeam::test
