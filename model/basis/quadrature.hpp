// Gauss-Legendre rules on [0, 1]: exact for polynomials of degree 2n-1; shared by the generator (AMM
// integrals) and the runtime's hand-assembled matrices.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace hubbeam {

struct QuadratureRule {
    std::vector<double> nodes, weights;  // on [0, 1]
};

/// n-point Gauss-Legendre rule on [0, 1] (Newton on P_n from Tricomi's initial guesses).
inline QuadratureRule gauss_legendre(int n)
{
    QuadratureRule rule;
    rule.nodes.resize(n);
    rule.weights.resize(n);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = 0.0;
            for (int k = 1; k <= n; ++k) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            const double dz = p0 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        const double w = 1.0 / ((1.0 - z * z) * dp * dp);  // 2/((1-z^2)P'^2) on [-1,1], halved for [0,1]
        rule.nodes[i] = 0.5 * (1.0 - z);
        rule.nodes[n - 1 - i] = 0.5 * (1.0 + z);
        rule.weights[i] = rule.weights[n - 1 - i] = w;
    }
    return rule;
}

/// Gauss-Legendre with `points` nodes on every interval between consecutive cuts (sorted, from 0 to 1).
inline QuadratureRule composite_gauss_legendre(const std::vector<double>& cuts, int points)
{
    const QuadratureRule g = gauss_legendre(points);
    QuadratureRule rule;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double lo = cuts[k], width = cuts[k + 1] - cuts[k];
        for (int j = 0; j < points; ++j) {
            rule.nodes.push_back(lo + width * g.nodes[j]);
            rule.weights.push_back(width * g.weights[j]);
        }
    }
    return rule;
}

/// Points per panel of the rule for transcendental (AMM) integrands.
constexpr int transcendental_points = 20;

/// Equal panels for AMM integrands up to mode n: narrow enough for the highest mode (about n/2 waves on
/// [0, 1]) that 20 points per panel converge to round-off (checked against orthonormality in the tests).
inline int transcendental_panels(int n) { return 8 + 4 * n; }

/// The composite rule for AMM integrands up to mode n.
inline QuadratureRule transcendental_rule(int n)
{
    const int panels = transcendental_panels(n);
    std::vector<double> cuts;
    for (int k = 0; k <= panels; ++k) cuts.push_back(static_cast<double>(k) / panels);
    return composite_gauss_legendre(cuts, transcendental_points);
}

}  // namespace hubbeam
