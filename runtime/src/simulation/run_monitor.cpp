// A run's invariant monitor and summary (Simulation::Run): which energy stays constant and from when, its drift row
// by row, and at the end the summary with the checks that find the rows untrustworthy.
#include "simulation/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <hubbeam/shortest.hpp>
#include <hubbeam/simulate.hpp>
#include <string>
#include <vector>

#include "simulation/error_check.hpp"
#include "simulation/run_rows.hpp"
#include "terms.hpp"

namespace hubbeam {

/// The summary's description of the run (variant, source, algebra, stepper) and which energy its monitor watches
/// from when, or why it watches none.
void Simulation::Run::start_summary()
{
    summary_.variant = model_.key().name();
    summary_.source = model_.source();
    if (!model_.origin().empty()) summary_.source += ", " + model_.origin();
    summary_.algebra = system_.linear_algebra();
    summary_.stepper = sim_.stepper_;
    summary_.stepper_why = sim_.stepper_why_;
    summary_.initial = sim_.initial_how_;
    // The invariant monitor starts after the drive's last breakpoint, from where its Jacobi integral is constant; with
    // the hub's work a state, E + dissipated - work is constant from the start; with damping the Jacobi integral
    // plus the dissipated energy is (docs/model.md section 11.4). Gravity under a prescribed rotation leaves nothing
    // constant: U_g changes with the prescribed angle.
    const std::vector<double> all_breaks = scene_.motion.breakpoints();
    summary_.t_steady = all_breaks.empty() ? 0.0 : *std::max_element(all_breaks.begin(), all_breaks.end());
    summary_.energy_balance = system_.auxiliary().count() > 0 || scene_.control.has_value();
    if (system_.auxiliary().work) summary_.t_steady = 0.0;
    const bool turning = scene_.motion.kind != Motion::Kind::held;
    if (reads_driven_angle(model_.key()) && turning)
        summary_.monitor_off = mass_reads_angle(model_.key())
                                   ? "a moving hub under a prescribed rotation: T follows the prescribed angle, no "
                                     "energy is constant"
                                   : "gravity under a prescribed rotation: U_g follows the prescribed angle, no energy "
                                     "is constant";
    // A drive that changes up to the run's end (a table to t_end, a spin-up longer than the run) leaves no row after
    // which the Jacobi integral is constant: a drift of 0 J over a single row would check nothing.
    const double t_last = times_(times_.last());
    if (summary_.monitor_off.empty() && summary_.t_steady >= t_last * (1.0 - same_instant))
        summary_.monitor_off = "the drive changes up to t = " + shortest(summary_.t_steady) +
                               " s and the run ends at " + shortest(t_last) + " s: no energy is constant while it does";
    // The reference of the Jacobi integral's drift: the vibration energy, the largest U since; under gravity U holds
    // the weight's potential, which can stay <= 0 (a free hub swinging below the horizontal), and its range since is
    // the energy that T and U exchange.
    summary_.invariant_reference = summary_.energy_balance               ? "the largest energy in it"
                                   : potential_reads_angle(model_.key()) ? "the range of U since"
                                                                         : "the vibration energy";
    // A run started at its equilibrium (initial.state) may hardly move: U's range is then round-off, and the energy
    // the equilibrium holds, |U| at the start, is the scale a drift is measured against.
    if (scene_.initial != InitialState::rest && !summary_.energy_balance)
        summary_.invariant_reference += " or |U| at the start";
}

/// The invariant monitor (docs/model.md section 7): once the drive is steady (after its last breakpoint) the Jacobi
/// integral is constant, and its drift against the vibration energy (the largest U since) says whether the rows can
/// be trusted. And the error indicator's record: the columns' peaks and the rows of its windows.
void Simulation::Run::monitor(const Row& r)
{
    if (summary_.energy_balance && summary_.monitor_off.empty() && r.t >= summary_.t_steady) {
        // E + dissipated - work against the largest energy in it (the hub's kinetic energy can dwarf U).
        const double balance = r.jacobi + r.extras.dissipated - r.extras.work;
        if (summary_.vibration_energy < 0.0) jacobi0_ = balance, summary_.vibration_energy = 0.0;
        summary_.jacobi_drift = std::max(summary_.jacobi_drift, std::abs(balance - jacobi0_));
        // Under a prescribed rotation the rigid spin's energy is not in the balance (T0 cancels): U and what was
        // dissipated measure it, as the Jacobi integral's drift is measured without damping.
        const double energy =
            model_.key().drive == Drive::torque ? std::abs(r.kinetic) + std::abs(r.potential) : r.potential;
        summary_.vibration_energy =
            std::max({summary_.vibration_energy, energy, std::abs(r.extras.dissipated), std::abs(r.extras.work)});
    } else if (summary_.monitor_off.empty() && r.t > 0.0 &&
               r.t >= summary_.t_steady) {  // from the first row after rest
        if (summary_.vibration_energy < 0.0) jacobi0_ = r.jacobi, summary_.vibration_energy = 0.0;
        summary_.jacobi_drift = std::max(summary_.jacobi_drift, std::abs(r.jacobi - jacobi0_));
        u_min_ = std::min(u_min_, r.potential);
        u_max_ = std::max(u_max_, r.potential);
        summary_.vibration_energy =
            std::max(summary_.vibration_energy, potential_reads_angle(model_.key()) ? u_max_ - u_min_ : r.potential);
        if (scene_.initial != InitialState::rest)
            summary_.vibration_energy = std::max(summary_.vibration_energy, std::abs(potential0_));
    }
    if (r.t == 0.0) potential0_ = r.potential;
    check_.record(r, values_);
}

/// The summary of the run that ended with failure (empty: it reached t_end), after the checks that can still find
/// it untrustworthy or find the tolerance, not the model, behind a failure.
RunSummary Simulation::Run::finish(std::string failure)
{
    summary_.steps = stepper_->steps();
    summary_.rejected_steps = stepper_->rejected();
    summary_.newton = stepper_->newton_form();
    summary_.rhs_evals = system_.evaluations();
    summary_.jacobian_evals = system_.jacobian_evaluations();
    summary_.t_reached = t_;
    const auto checked = std::chrono::steady_clock::now();
    summary_.wall_seconds = std::chrono::duration<double>(checked - start_).count() - check_.whole_run_seconds();
    if (!failure.empty()) check_.rows_so_far(summary_);  // the run failed already: the summary's figure only
    if (failure.empty())
        failure = untrustworthy();
    else if (!model_failure_.empty() || failure.rfind("unstable: the equations", 0) == 0)
        failure = tolerance_as_cause(failure);
    if (non_finite_)
        failure += last_row_ < t_ ? "; the rows up to t = " + shortest(last_row_) + " s are written, not this one"
                                  : "; no row is written";
    if (summary_.check_rtol > 0.0)  // a check ran
        summary_.check_wall_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - checked).count() +
            check_.whole_run_seconds();
    summary_.completed = failure.empty();
    summary_.failure = failure;
    return summary_;
}

/// For a run that reached t_end: why its rows cannot be trusted (empty if they can), from the invariant monitor
/// and the error indicator; both find the tolerance too loose.
std::string Simulation::Run::untrustworthy()
{
    char text[480];
    const double drift = summary_.vibration_energy > 0.0 ? summary_.jacobi_drift / summary_.vibration_energy : 0.0;
    if (drift > invariant_tolerance) {
        // What drifted: the balance with damping or control, else the Jacobi integral once the drive is steady.
        const bool balance = summary_.energy_balance;
        std::snprintf(text, sizeof text,
                      "untrustworthy: the %s drifted by %.3g J %s t = %g s, %.2g of %s (more than %g): the "
                      "tolerance is too loose for the stepper; tighten --rtol/--atol",
                      balance ? "energy balance E + dissipated - work" : "Jacobi integral", summary_.jacobi_drift,
                      balance ? "from" : "after the drive ended at", summary_.t_steady, drift,
                      summary_.invariant_reference.c_str(), invariant_tolerance);
        return text;
    }
    return check_.verdict(summary_);
}

}  // namespace hubbeam
