// The run's output times (a run's rows): multiples of dt_out computed as the decimals they are, and t_end.
#pragma once

#include <cmath>

#include <hubbeam/config.hpp>
#include "simulation/run_rows.hpp"

namespace hubbeam {

/// Output time i * dt. A decimal dt = n / 10^d gives (i n) / 10^d, a quotient of exact integers and so the
/// double nearest the decimal multiple (0.35, not 0.35000000000000003); other dt give i * dt.
class OutputClock {
public:
    explicit OutputClock(double dt) : dt_(dt)
    {
        for (int d = 0; d <= 9; ++d, scale_ *= 10.0) {
            const double n = std::round(dt * scale_);
            if (n >= 1.0 && std::abs(n - dt * scale_) <= 1e-9 * n) {
                n_ = n;
                return;
            }
        }
    }
    double operator()(long i) const
    {
        const double in = static_cast<double>(i) * n_;
        return n_ > 0.0 && in < 0x1p53 ? in / scale_ : static_cast<double>(i) * dt_;
    }

private:
    double dt_, scale_ = 1.0, n_ = 0.0;
};

/// The run's output times: row 0 at t = 0, rows at multiples of dt_out, and a last one at t_end when dt_out does
/// not divide it, so that a run that exits 0 has reached t_end.
class OutputTimes {
public:
    explicit OutputTimes(const OutputOptions& o)
        : grid_(o.dt_out),
          t_end_(o.t_end),
          grid_rows_(static_cast<long>(std::floor(o.t_end / o.dt_out * (1.0 + same_instant))))
    {
        last_ = grid_rows_ + (grid_(grid_rows_) < t_end_ * (1.0 - same_instant) ? 1 : 0);
    }
    /// The last row's index.
    long last() const { return last_; }
    double operator()(long i) const { return i > grid_rows_ ? t_end_ : grid_(i); }

private:
    OutputClock grid_;
    double t_end_;
    long grid_rows_, last_ = 0;
};

}  // namespace hubbeam
