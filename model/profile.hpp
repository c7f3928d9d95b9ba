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

/// Value j (ProfileValue) of a profile at xi, planar (3 values per station) or a blade's (max_profile_value_count).
inline double profile_value(const std::vector<double>& stations, const std::vector<double>& values, ProfileValue j,
                            double xi)
{
    return linear_between(stations, values, static_cast<std::size_t>(j), xi);
}

/// int_from^1 m(t) t^n dt of a profile's mass per length, for any `from`: each station interval's integral once
/// (3-point Gauss-Legendre, exact for n <= 4: m is linear there) summed from the tip, so that a tail costs one
/// interval's rule and a search, not a sum over every station (a table of 10,000 at as many nodes).
class MassTail {
public:
    MassTail(const std::vector<double>& stations, const std::vector<double>& values, int n)
        : stations_(stations), values_(values), n_(n), after_(stations.size(), 0.0)
    {
        for (std::size_t k = stations.size() - 1; k-- > 0;)
            after_[k] = after_[k + 1] + piece(stations[k], stations[k + 1]);
    }

    double operator()(double from) const
    {
        if (from >= stations_.back()) return 0.0;
        if (from <= stations_.front()) return after_.front();
        const std::size_t k =
            static_cast<std::size_t>(std::upper_bound(stations_.begin(), stations_.end(), from) - stations_.begin()) - 1;
        return piece(from, stations_[k + 1]) + after_[k + 1];
    }

private:
    double piece(double lo, double hi) const
    {
        static const QuadratureRule g3 = gauss_legendre(3);
        double sum = 0.0;
        for (int j = 0; j < 3; ++j) {
            const double t = lo + (hi - lo) * g3.nodes[j];
            sum += (hi - lo) * g3.weights[j] * profile_value(stations_, values_, ProfileValue::m, t) * std::pow(t, n_);
        }
        return sum;
    }

    const std::vector<double>& stations_;
    const std::vector<double>& values_;
    int n_;
    std::vector<double> after_;  // after_[k] = int_(stations_[k])^1 m t^n dt
};

}  // namespace hubbeam
