// The error indicator (error_check.hpp): windows of a run, or the whole run, re-run at a tighter tolerance from the
// run's own states and compared with its rows column by column.
#include "simulation/error_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <hubbeam/shortest.hpp>
#include <utility>


#include "dynamics/stepper.hpp"
#include "dynamics/stiffness.hpp"
#include "simulation/column_check.hpp"
#include "simulation/run_rows.hpp"
#include "simulation/sensitivity.hpp"

namespace hubbeam {

namespace {

// The error indicator (RunSummary::estimated_error). Its windows are this fraction of the run (at least one row
// interval): the run's own error accumulates over the run, and a window of a fiftieth measures its rate at a
// sixth of a run's cost at the tighter tolerance (measured on the main job: 15 to 20 %).
constexpr double check_window_fraction = 1.0 / 50.0;
// The window across the drive's end is this fraction of the others: the error made at the kink shows in the rows
// right after it and stays, so a short window sees it (cases/torque_tau1.toml's tip_ux1: 4.1e-6 of its peak with a
// fifth, against a true error of 4.9e-6).
constexpr double drive_end_window_share = 1.0 / 5.0;
// The re-run's tolerances: this many times tighter than the run's, and than the scene defaults at the loosest, so
// that its own error is small beside the error it measures.
constexpr double check_tightening = 10.0;

// Below this size (m, rad, rad/s, J, N m, ... in SI units) a column's values are round-off, not a measure to be
// relative to: its difference counts against this floor. A derivative by a parameter p counts against this floor
// over |p|, a change of the output over a relative change of p.
constexpr double round_off_floor = 1e-9;

/// The tighter tolerances of the error indicator's re-runs: check_tightening times the run's, or the defaults'.
CheckTolerance check_tolerance(const SolverOptions& solver)
{
    const SolverOptions defaults;
    return {std::max(std::min(solver.rtol, defaults.rtol) / check_tightening, 1e-13),
            std::min(solver.atol, defaults.atol) / check_tightening};
}

/// Whether a run's tolerances are looser than the scene defaults' (SolverOptions) in rtol or atol: error_check on then
/// compares it with the whole run re-run, not with windows (RunErrorCheck's constructor says why).
bool looser_than_defaults(const SolverOptions& solver)
{
    const SolverOptions defaults;
    return solver.rtol > defaults.rtol || solver.atol > defaults.atol;
}

/// The rows' values (append_row_values with set) of a re-run of the scene from state y (of the run's system) at t0
/// to each of times (ascending, > t0), at tol with the stepper that suits the scene, a step ending at each row and
/// breakpoint. Fewer rows than times: the re-run failed there (a step, or a model limit).
std::vector<double> rerun(const Scene& scene, const Model& model, double t0, std::vector<double> y,
                          const std::vector<double>& times, CheckTolerance tol, const std::string& stepper_name,
                          const ColumnSet& set)
{
    const std::unique_ptr<FirstOrderSystem> system = system_of(model, scene);
    const std::unique_ptr<Stepper> stepper =
        make_stepper(*system, stepper_name, t0, y.data(), scene.solver.h0, tol.atol, tol.rtol);
    RowMaker make_row(model, scene, *system);
    const std::vector<double> breaks = times.empty() ? std::vector<double>{} : breaks_before(scene.motion, times.back());
    auto next = std::upper_bound(breaks.begin(), breaks.end(), t0 * (1.0 + same_instant));
    const double critical = critical_spin(model);
    std::vector<double> values;
    double t = t0;
    for (const double ti : times) {
        for (; next != breaks.end() && *next < ti * (1.0 - same_instant); ++next) {
            if (stepper->advance(t, *next, y.data()) != StepStatus::success) return values;
            stepper->restart(t, y.data());
        }
        if (stepper->advance(t, ti, y.data()) != StepStatus::success) return values;
        if (stepper->steps() > scene.solver.max_steps) return values;
        const Row r = make_row(ti, y.data());
        if (!model_limit(r, critical, scene.parameters.L).empty()) return values;
        append_row_values(r, set, values);
    }
    return values;
}

/// The largest difference of window's rows from a re-run of it, in any column, relative to the column's peak in the
/// run (largest_difference); a negative fraction when the re-run failed.
ColumnDifference window_error(const Scene& scene, const Model& model, const CheckWindow& window,
                              const CheckedColumns& columns, const std::vector<double>& peak, CheckTolerance tol,
                              const std::string& stepper)
{
    const std::vector<double> again =
        rerun(scene, model, window.t0, window.y0, window.times, tol, stepper, columns.set);
    return largest_difference(window.values, again, peak, columns.floor);
}

}  // namespace

CheckedColumns checked_columns(const Scene& scene, const FirstOrderSystem& system)
{
    CheckedColumns c{optional_columns_of(scene), {}, {}};
    c.names = row_column_names(c.set);
    c.floor.assign(c.names.size() - c.set.derived.size(), round_off_floor);
    if (const auto* s = dynamic_cast<const SensitivitySystem*>(&system))
        for (int j = 0; j < s->count(); ++j)
            c.floor.insert(c.floor.end(), sensitivity_outputs_of(scene.key()).size(), round_off_floor / s->scale(j));
    return c;
}

void CheckWindow::add(const Row& r, const ColumnSet& set)
{
    times.push_back(r.t);
    append_row_values(r, set, values);
}

/// The whole run re-run alongside at the tighter tolerance (error_check full): a step to each row the run writes, as
/// rerun steps, and each column's largest difference kept, so that it holds one row however long the run. Catches
/// an error made anywhere, which the windows see only where they are (a multistep stepper's mid-run error).
class WholeRunCheck {
public:
    WholeRunCheck(const Scene& scene, const Model& model, std::vector<double> y0, CheckTolerance tol,
                  const std::string& stepper, const CheckedColumns& columns)
        : scene_(scene), system_(system_of(model, scene)), y_(std::move(y0)),
          stepper_(make_stepper(*system_, stepper, 0.0, y_.data(), scene.solver.h0, tol.atol, tol.rtol)),
          make_row_(model, scene, *system_),
          breaks_(breaks_before(scene.motion, INFINITY)), critical_(critical_spin(model)), columns_(columns),
          worst_(columns.names.size(), 0.0), when_(worst_.size(), 0.0)
    {
    }
    /// The re-run to the run's row at t (> the last one) and its values compared with the run's there; nothing once
    /// the re-run has failed (a step, the step budget or a model limit).
    void compare(double t, const std::vector<double>& values)
    {
        if (failed_ || !advance(t)) {
            failed_ = true;
            return;
        }
        again_.clear();
        append_row_values(make_row_(t, y_.data()), columns_.set, again_);
        for (std::size_t c = 0; c < worst_.size(); ++c) {
            const double d = std::abs(values[c] - again_[c]);
            if (std::isnan(d) || d > worst_[c]) worst_[c] = std::isnan(d) ? INFINITY : d, when_[c] = t;
        }
        t_compared_ = t;
    }
    /// The largest difference so far relative to the column's peak in the run (largest_difference's measure).
    ColumnDifference largest(const std::vector<double>& peak) const
    {
        return largest_difference(worst_, std::vector<double>(worst_.size(), 0.0), peak, columns_.floor);
    }
    /// When column's largest difference was met.
    double when(std::size_t column) const { return when_[column]; }
    /// The last row compared (0: none).
    double t_compared() const { return t_compared_; }

private:
    bool advance(double ti)
    {
        for (; next_ < breaks_.size() && breaks_[next_] < ti * (1.0 - same_instant); ++next_) {
            // A breakpoint at the last row's time was reached there: only the restart is left.
            const bool ahead = breaks_[next_] > t_ * (1.0 + same_instant);
            if (ahead && stepper_->advance(t_, breaks_[next_], y_.data()) != StepStatus::success) return false;
            stepper_->restart(t_, y_.data());
        }
        if (stepper_->advance(t_, ti, y_.data()) != StepStatus::success) return false;
        if (stepper_->steps() > scene_.solver.max_steps) return false;
        return model_limit(make_row_(ti, y_.data()), critical_, scene_.parameters.L).empty();
    }

    const Scene& scene_;
    const std::unique_ptr<FirstOrderSystem> system_;
    std::vector<double> y_;
    const std::unique_ptr<Stepper> stepper_;
    RowMaker make_row_;
    const std::vector<double> breaks_;
    std::size_t next_ = 0;
    const double critical_;
    const CheckedColumns& columns_;
    std::vector<double> again_, worst_, when_;  // worst_: each column's largest |difference|, met at when_
    double t_ = 0.0, t_compared_ = 0.0;
    bool failed_ = false;
};

// ---- RunErrorCheck ----

RunErrorCheck::RunErrorCheck(const Scene& scene, const Model& model, const FirstOrderSystem& system,
                             const std::vector<double>& y0, double t_last, ErrorCheck mode, StepperAt stepper_at)
    : scene_(scene), model_(model), stepper_at_(std::move(stepper_at)), on_(mode != ErrorCheck::off),
      columns_(checked_columns(scene, system)), peak_(columns_.names.size(), 0.0)
{
    const double t_end = scene.output.t_end;
    window_ = std::min(t_end, std::max(t_end * check_window_fraction, scene.output.dt_out));
    drive_end_window_ = std::max(window_ * drive_end_window_share, scene.output.dt_out);
    start_.t0 = 0.0;
    start_.y0 = y0;  // the initial state
    if (const std::vector<double> breaks = breaks_before(scene.motion, t_last); !breaks.empty())
        drive_end_ = breaks.back();
    // The windows measure the error a run makes at its start, its end and across its drive's end, and scale the end
    // window's to the run: that holds where the steppers' error control keeps the error in step with the tolerance
    // all along, as at the defaults and tighter (where the windows' estimate was measured against whole runs:
    // test_error_estimate.cpp). Looser, it does not. An integrated column (dissipated, work) takes an error in every
    // step, bounded by rtol times its own growing value, that adds up over the run and that no window of a fiftieth
    // sees; and a transient during the drive can be off while the start and the end are right. At rtol 1e-2, 9 of
    // the 51 runs of cases/ by msadams, cvode and gauss4 that exited 0 were 1.1 to 31 % off (dissipated mostly;
    // blade_from_file's tip_ux 1.4 % at t = 5 s with gauss4, 0.05 % at its end), their windows' estimates 5e-5 to
    // 0.009. Only a re-run from the start through the error sees it, so such a run is compared with the whole run
    // re-run, as under full. That costs a run at the check's tolerance (the defaults' tenth for every looser run),
    // more than the loose run itself; a run at the defaults or tighter keeps the windows and their cost.
    if (on_ && (mode == ErrorCheck::full || looser_than_defaults(scene.solver))) {
        const CheckTolerance tol = check_tolerance(scene.solver);
        whole_ = std::make_unique<WholeRunCheck>(scene, model, y0, tol, stepper_at_(tol.rtol), columns_);
    }
}

RunErrorCheck::~RunErrorCheck() = default;

void RunErrorCheck::record(const Row& r, const std::vector<double>& values)
{
    if (!on_) return;
    for (std::size_t c = 0; c < peak_.size(); ++c) peak_[c] = std::max(peak_[c], std::abs(values[c]));
    last_row_ = r.t;
    if (whole_) {
        const auto start = std::chrono::steady_clock::now();
        if (r.t > 0.0) whole_->compare(r.t, values);
        whole_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return;
    }
    if (r.t > 0.0 && r.t <= window_ * (1.0 + same_instant)) start_.add(r, columns_.set);
    else if (end_.t0 >= 0.0 && r.t > end_.t0) end_.add(r, columns_.set);
    const double t_drive = across_drive_end_.t0;
    if (t_drive >= 0.0 && r.t > t_drive * (1.0 + same_instant) &&
        r.t <= (t_drive + drive_end_window_) * (1.0 + same_instant))
        across_drive_end_.add(r, columns_.set);
}

// The end window starts at a state the run computed, not an interpolated one (whose error would excite the stiff
// modes the re-run then resolves).
void RunErrorCheck::step_from(double t, const std::vector<double>& y, double t_next)
{
    if (!on_ || whole_ || end_.t0 >= 0.0) return;
    if (t_next < scene_.output.t_end - window_ || t <= window_) return;
    end_.t0 = t;
    end_.y0 = y;
}

// Steps end at the breakpoint, so the window across the drive's end starts at a state the run computed.
void RunErrorCheck::restarted(double t, const std::vector<double>& y)
{
    if (!on_ || whole_ || across_drive_end_.t0 >= 0.0 || !(drive_end_ > window_)) return;
    if (std::abs(t - drive_end_) > same_instant * drive_end_) return;
    across_drive_end_.t0 = t;
    across_drive_end_.y0 = y;
}

std::string RunErrorCheck::verdict(RunSummary& summary)
{
    if (whole_) return whole_run_verdict(summary, true);
    if (!on_ || start_.times.empty()) return {};
    return windows_verdict(summary);
}

void RunErrorCheck::rows_so_far(RunSummary& summary)
{
    if (whole_) whole_run_verdict(summary, false);
}

/// The check's tolerances, which the summary reports.
CheckTolerance RunErrorCheck::tolerance(RunSummary& summary) const
{
    const CheckTolerance tol = check_tolerance(scene_.solver);
    summary.check_rtol = tol.rtol;
    summary.check_atol = tol.atol;
    return tol;
}

ColumnDifference RunErrorCheck::compare(const CheckWindow& w, CheckTolerance tol) const
{
    return window_error(scene_, model_, w, columns_, peak_, tol, stepper_at_(tol.rtol));
}

/// The windows' largest difference, the end window's scaled to the run, into summary; the message if above tolerance.
std::string RunErrorCheck::windows_verdict(RunSummary& summary)
{
    const CheckTolerance tol = tolerance(summary);
    // The start window from rest: an error made at once (a fast mode excited by a loose tolerance) stays.
    auto [measured, column] = compare(start_, tol);
    const CheckWindow* where = &start_;
    double error = measured;
    if (measured >= 0.0 && !end_.times.empty()) {
        // The error made in the last window, times the square root of the windows the run holds: the windows'
        // errors add up as independent ones would (a linear sum overstates the atol-sized noise of a coordinate
        // near zero eightfold in cases/torque_tau1.toml); a mode that the stepper amplifies shows in the window.
        const auto [end_measured, end_column] = compare(end_, tol);
        const double t1 = end_.times.back();
        const double scaled = end_measured < 0.0 ? -1.0 : end_measured * std::sqrt(t1 / (t1 - end_.t0));
        if (scaled < 0.0 || scaled > error) error = scaled, measured = end_measured, column = end_column, where = &end_;
    }
    if (error >= 0.0 && !across_drive_end_.times.empty()) {
        // Across the drive's end (a torque switched off, a spin-up reaching its rate): the profile's kink, where the
        // stepper restarts, can make at once an error that then stays, as at a start from rest (most of the error
        // of cases/torque_tau1.toml's tip_ux1, which neither of the other windows sees).
        const auto [kink_measured, kink_column] = compare(across_drive_end_, tol);
        if (kink_measured < 0.0 || kink_measured > error)
            error = kink_measured, measured = kink_measured, column = kink_column, where = &across_drive_end_;
    }
    summary.estimated_error = error;
    if (error < 0.0) return {};  // the re-run failed where the run did not: nothing to compare
    summary.error_column = columns_.names[column];
    if (!(error > error_tolerance)) return {};
    char rate[120] = "", text[480];
    if (where == &end_) std::snprintf(rate, sizeof rate, ", about %.2g over the run", error);
    std::snprintf(text, sizeof text,
                  "untrustworthy: the run's error exceeds %g: its %s differs by %.2g of its largest value from a re-run "
                  "at rtol %g, atol %g over t = %g to %g s%s; tighten --rtol/--atol",
                  error_tolerance, summary.error_column.c_str(), measured, tol.rtol, tol.atol, where->t0,
                  where->times.back(), rate);
    return text;
}

/// Under error_check full: the run's largest difference from its re-run alongside, over the rows compared (all of them
/// unless the re-run failed first), into the summary; for a completed run, why its rows cannot be trusted (empty if
/// they can). Unscaled: the re-run measured the error at every row, where the windows extrapolate.
std::string RunErrorCheck::whole_run_verdict(RunSummary& summary, bool completed)
{
    const double t1 = whole_->t_compared();
    if (t1 <= 0.0) return {};  // no row after the start compared: the re-run failed at once, or the run did
    const CheckTolerance tol = tolerance(summary);
    const ColumnDifference d = whole_->largest(peak_);
    summary.estimated_error = d.fraction;
    summary.error_column = columns_.names[d.column];
    const bool all = completed && t1 >= last_row_ * (1.0 - same_instant);
    summary.error_from = all ? "the whole run" : "the run to t = " + shortest(t1) + " s";
    if (!completed || !(d.fraction > error_tolerance)) return {};
    char text[400];
    std::snprintf(text, sizeof text,
                  "untrustworthy: the run's error exceeds %g: its %s differs by %.2g of its largest value at t = %g s "
                  "from %s re-run at rtol %g, atol %g; tighten --rtol/--atol",
                  error_tolerance, summary.error_column.c_str(), d.fraction, whole_->when(d.column),
                  summary.error_from.c_str(), tol.rtol, tol.atol);
    return text;
}

std::string RunErrorCheck::tolerance_as_cause(const std::string& failure, const std::vector<double>& times,
                                              RunSummary& summary)
{
    if (!on_) return failure;
    const CheckTolerance tol = check_tolerance(scene_.solver);
    if (tol.rtol >= scene_.solver.rtol && tol.atol >= scene_.solver.atol) return failure;  // as tight as it gets
    if (times.empty()) return failure;
    tolerance(summary);
    const std::vector<double> again =  // from the run's start
        rerun(scene_, model_, 0.0, start_.y0, times, tol, stepper_at_(tol.rtol), columns_.set);
    if (again.size() < times.size() * columns_.names.size()) return failure;  // the model fails there at the tighter tolerance too
    // What happened, without the clauses that blame the model.
    std::string what = failure.substr(0, std::min({failure.find(" ("), failure.find("; "), failure.find(", above")}));
    if (what.rfind("unstable: ", 0) == 0) what.erase(0, 10);
    char text[200];
    std::snprintf(text, sizeof text, "): a re-run at rtol %g, atol %g passes t = %g s; tighten --rtol/--atol", tol.rtol,
                  tol.atol, times.back());
    return "untrustworthy: the run's error, not the model, stopped it (" + what + text;
}

}  // namespace hubbeam
