// The steady oscillation of the tip after the drive: frequency from the upward mean crossings of tip_uy and
// amplitude as half its range (the paper's Table 1 quantities).
#pragma once

#include <algorithm>
#include <vector>

#include <hubbeam/simulate.hpp>

namespace hubbeam {

struct Oscillation {
    double frequency = 0.0;  // Hz; 0 when fewer than `min_crossings` upward crossings were seen
    double amplitude = 0.0;  // m
    int crossings = 0;
};

/// tip_uy's oscillation over the rows from t0 on (crossings interpolated linearly between rows).
inline Oscillation steady_oscillation(const std::vector<Row>& rows, double t0, int min_crossings = 5)
{
    double mean = 0.0, lo = 1e300, hi = -1e300;
    int count = 0;
    for (const Row& r : rows)
        if (r.t >= t0) {
            mean += r.tip_uy;
            lo = std::min(lo, r.tip_uy);
            hi = std::max(hi, r.tip_uy);
            ++count;
        }
    if (count == 0) return {};
    mean /= count;
    std::vector<double> crossings;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const double a = rows[i - 1].tip_uy - mean, b = rows[i].tip_uy - mean;
        if (rows[i - 1].t >= t0 && a < 0.0 && b >= 0.0)
            crossings.push_back(rows[i - 1].t + (rows[i].t - rows[i - 1].t) * a / (a - b));
    }
    Oscillation o;
    o.amplitude = (hi - lo) / 2.0;
    o.crossings = static_cast<int>(crossings.size());
    if (o.crossings >= min_crossings)
        o.frequency = (crossings.size() - 1) / (crossings.back() - crossings.front());
    return o;
}

}  // namespace hubbeam
