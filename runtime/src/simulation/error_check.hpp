// The error indicator of a run (RunSummary::estimated_error): windows of the run, or the whole run (error_check full,
// or a run looser than the defaults), re-run at a tenfold tighter tolerance and compared in every column the run
// writes (column_check.hpp). A run (run.hpp) feeds it the run's rows and states and asks it, at the end, whether the
// rows can be trusted.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/simulate.hpp>
#include "dynamics/integrate.hpp"
#include "simulation/column_check.hpp"

namespace hubbeam {

/// The columns the error indicator compares: every one the run writes (row_column_names, as the CSV header).
struct CheckedColumns {
    ColumnSet set;
    std::vector<std::string> names;
    std::vector<double> floor;  // round_off_floor, in each column's units
};
CheckedColumns checked_columns(const Scene& scene, const FirstOrderSystem& system);

/// A stretch of the run to re-run at the tighter tolerance: its start and the state there, the times of the run's rows
/// in it and their values (append_row_values, one row after the other).
struct CheckWindow {
    double t0 = -1.0;  // < 0: not reached
    std::vector<double> y0;
    std::vector<double> times, values;
    void add(const Row& r, const ColumnSet& set);
};

/// The tighter tolerances of the error indicator's re-runs.
struct CheckTolerance {
    double rtol, atol;
};

class WholeRunCheck;

/// The error check of one run: it records the run's rows (each column's peak, and the windows' rows or the whole
/// run's comparison) and states where windows start, and at the end estimates the error into the run's summary.
class RunErrorCheck {
public:
    /// The stepper the re-runs use at a tolerance (the automatic choice there).
    using StepperAt = std::function<std::string(double rtol)>;
    /// For a run of scene from state y0 whose rows end at t_last; mode off records nothing but the columns, on the
    /// windows (the whole run for a run looser than the defaults), full the whole run.
    RunErrorCheck(const Scene& scene, const Model& model, const FirstOrderSystem& system, const std::vector<double>& y0,
                  double t_last, ErrorCheck mode, StepperAt stepper_at);
    ~RunErrorCheck();
    RunErrorCheck(const RunErrorCheck&) = delete;
    RunErrorCheck& operator=(const RunErrorCheck&) = delete;

    const CheckedColumns& columns() const { return columns_; }
    /// A row the run wrote, with its values (append_row_values with columns().set).
    void record(const Row& r, const std::vector<double>& values);
    /// A step of the run from t (state y) to t_next: the end window starts at the step before it reaches its start.
    void step_from(double t, const std::vector<double>& y, double t_next);
    /// A restart of the run's stepper at t (state y): the window across the drive's end starts at its last breakpoint.
    void restarted(double t, const std::vector<double>& y);
    /// For a run that reached t_end: the estimated error into summary; why the rows cannot be trusted (empty if they can).
    std::string verdict(RunSummary& summary);
    /// For a run that stopped early: the error of the rows so far into summary (error_check full only).
    void rows_so_far(RunSummary& summary);
    /// A run stopped by the model at times.back() (the rows up to it): the message, unless a re-run from rest at the
    /// tighter tolerance gets past it, which shows the run's error and not the model to blame.
    std::string tolerance_as_cause(const std::string& failure, const std::vector<double>& times, RunSummary& summary);
    /// The time the whole run's re-run took so far (error_check full), spent between the run's rows.
    double whole_run_seconds() const { return whole_seconds_; }

private:
    std::string windows_verdict(RunSummary& summary);
    ColumnDifference compare(const CheckWindow& w, CheckTolerance tol) const;
    std::string whole_run_verdict(RunSummary& summary, bool completed);
    CheckTolerance tolerance(RunSummary& summary) const;

    const Scene& scene_;
    const Model& model_;
    const StepperAt stepper_at_;
    const bool on_;
    const CheckedColumns columns_;
    std::vector<double> peak_;  // each column's largest |value| in the run
    double window_ = 0.0, drive_end_window_ = 0.0;  // the windows' lengths
    double drive_end_ = -1.0;  // the drive's last breakpoint inside the run, where across_drive_end_ starts
    CheckWindow start_, end_, across_drive_end_;
    std::unique_ptr<WholeRunCheck> whole_;  // error_check full, instead of the windows
    double whole_seconds_ = 0.0, last_row_ = 0.0;
};

}  // namespace hubbeam
