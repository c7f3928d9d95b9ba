// A tabulated profile's distributions along the span (docs/model.md sections 11.2 and 12.4): values at stations x/L,
// linear between them, for the runtime's numerical paths (the generator integrates the same hat functions exactly).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "basis/quadrature.hpp"
#include "interface.hpp"

namespace hubbeam {

/// Entry j of a table with w = values.size() / stations.size() entries per station (values[w k + j] at stations[k]),
/// at xi in [0, 1], linear between stations.
inline double linear_between(const std::vector<double>& stations, const std::vector<double>& values, std::size_t j,
                             double xi)
{
    const std::size_t n = stations.size(), w = values.size() / n;
    // The interval [stations[k], stations[k + 1]] that holds xi (the first or last one beyond the ends).
    const auto above = std::upper_bound(stations.begin() + 1, stations.end() - 1, xi);
    const std::size_t k = static_cast<std::size_t>(above - stations.begin()) - 1;
    const double t = (xi - stations[k]) / (stations[k + 1] - stations[k]);
    return (1.0 - t) * values[w * k + j] + t * values[w * (k + 1) + j];
}

/// Value j (ProfileValue) of a profile at xi, planar (3 values per station) or a blade's (8).
inline double profile_value(const std::vector<double>& stations, const std::vector<double>& values, ProfileValue j,
                            double xi)
{
    return linear_between(stations, values, static_cast<std::size_t>(j), xi);
}

/// int_from^1 m(t) t^n dt of a profile's mass per length: 3-point Gauss-Legendre on each interval between stations,
/// exact for n <= 4 (m is linear there).
inline double mass_tail(const std::vector<double>& stations, const std::vector<double>& values, double from, int n)
{
    const QuadratureRule g3 = gauss_legendre(3);
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < stations.size(); ++k) {
        const double lo = std::max(from, stations[k]), hi = stations[k + 1];
        if (hi <= lo) continue;
        for (int j = 0; j < 3; ++j) {
            const double t = lo + (hi - lo) * g3.nodes[j];
            sum += (hi - lo) * g3.weights[j] * profile_value(stations, values, ProfileValue::m, t) * std::pow(t, n);
        }
    }
    return sum;
}

}  // namespace hubbeam
