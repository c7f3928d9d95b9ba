// The error indicator's comparison (a run's rows, run_rows.cpp): every value a row writes, from the run and from a
// re-run of the same stretch, each column's difference relative to its largest value in the run.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <hubbeam/simulate.hpp>

namespace hubbeam {

/// The values row writes to a CSV line or the Python module's array (for_each_value's order), appended to out.
inline void append_row_values(const Row& row, const ColumnSet& set, std::vector<double>& out)
{
    for_each_value(row, set, [&out](double v) { out.push_back(v); });
}

/// The largest column difference: its size relative to the column's peak, and the column's index; fraction < 0 when
/// the two windows differ in length (a re-run that failed).
struct ColumnDifference {
    double fraction = 0.0;
    std::size_t column = 0;
};

/// run and again: rows of peak.size() values each (append_row_values). A column's difference counts against
/// max(peak, floor): floor is the size below which its values are round-off (tip_ux1 in the first 0.1 s of a
/// spin-up peaks at 2e-15 m); a column whose peak is 0 is one the variant does not have. A NaN difference is
/// infinitely large.
inline ColumnDifference largest_difference(const std::vector<double>& run, const std::vector<double>& again,
                                           const std::vector<double>& peak, const std::vector<double>& floor)
{
    if (run.size() != again.size()) return {-1.0, 0};
    ColumnDifference worst;
    const std::size_t width = peak.size();
    for (std::size_t i = 0; i < run.size(); ++i) {
        const std::size_t c = i % width;
        if (peak[c] == 0.0) continue;
        const double e = std::abs(run[i] - again[i]) / std::max(peak[c], floor[c]);
        if (std::isnan(e) || e > worst.fraction) worst = {std::isnan(e) ? INFINITY : e, c};
    }
    return worst;
}

}  // namespace hubbeam
