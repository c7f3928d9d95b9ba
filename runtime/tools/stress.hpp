// The stability stress suite (hubbeam stress): high spin rates for every method and model order, DOF counts
// up to each method's limit with the mass matrix's conditioning, long runs' invariant drift per stepper, and
// beams far more flexible and far stiffer than the paper's. Every case states what must happen; the suite
// fails when a case that must stay bounded does not, or one that must be caught as unstable is not.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <hubbeam/simulate.hpp>

namespace hubbeam {

struct StressOptions {
    bool long_runs = false;  // 1000 s runs and every method's largest DOF count (minutes), else 100 s and Ny 8, 16
    bool quick = false;      // spin rates up to 20 rad/s only: the subset the test suite runs
    std::string output;      // CSV of the table; empty: none
};

struct StressRow {
    std::string group, name;
    std::string expect;  // "bounded", "unstable", or "report" (measured, nothing required)
    std::string status = "ok";  // or the run's failure
    bool pass = true;
    double max_tip = 0.0, drift = -1.0, wall = 0.0;  // m, Jacobi drift relative to the vibration energy, s
    std::string note;                                  // extra measure (condition number, first against full)
};

/// Runs the suite, printing one table line per case to out; returns the rows. run_stress_exit_code: 0 if every
/// row passes, 1 otherwise.
std::vector<StressRow> run_stress(const StressOptions& options, std::ostream& out, const StopRequest& stop);

}  // namespace hubbeam
