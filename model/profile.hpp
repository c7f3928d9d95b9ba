// A tabulated profile's distributions along the span (docs/model.md section 11.2): values at stations x/L, linear
// between them, for the runtime's numerical paths (the generator integrates the same hat functions exactly).
#pragma once

#include <cstddef>
#include <vector>

#include "interface.hpp"

namespace hubbeam {

/// Value j (ProfileValue) of a profile at xi in [0, 1]: values[w k + j] at stations[k] (w values per station, planar
/// or not), linear between stations.
inline double profile_value(const std::vector<double>& stations, const std::vector<double>& values, ProfileValue j,
                            double xi)
{
    const std::size_t n = stations.size(), v = static_cast<std::size_t>(j), w = values.size() / n;
    std::size_t k = 0;
    while (k + 2 < n && xi > stations[k + 1]) ++k;
    const double t = (xi - stations[k]) / (stations[k + 1] - stations[k]);
    return (1.0 - t) * values[w * k + v] + t * values[w * (k + 1) + v];
}

}  // namespace hubbeam
