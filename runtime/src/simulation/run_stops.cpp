// Why a run stops, in words: a failed step and its likely cause, the model's limits, the step budget, and a failure
// the tolerance rather than the model caused.
#include "simulation/run.hpp"

#include <cmath>
#include <cstdio>
#include <hubbeam/shortest.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "dynamics/stepper.hpp"
#include "dynamics/stiffness.hpp"
#include "models/model_operations.hpp"
#include "simulation/run_rows.hpp"

namespace hubbeam {

std::string at_time(double t)
{
    std::ostringstream s;
    s << " at t = " << t << " s";
    return s.str();
}

namespace {

/// The message for a failed step, or empty for success. code is the stepper's own for it; hint says what to do: for
/// equations that failed to evaluate the cause the system found, otherwise a stepper that suits the scene (or nothing).
std::string step_failure(StepStatus status, const StepCode& code, double t, const std::string& hint)
{
    if (status == StepStatus::success) return {};
    if (status == StepStatus::equations_failed)
        return "unstable: the equations became singular or non-finite" + at_time(t) + " (" + hint + ")";
    // The families' own words ("failure", "no progress") say little: what they mean for a step.
    std::string what;
    switch (status) {
        case StepStatus::no_step:
            what = "the stepper could not take a step that meets the tolerance";
            break;
        case StepStatus::no_progress:
            what = "the step size fell to round-off without meeting the tolerance";
            break;
        case StepStatus::not_converged:
            what = "the implicit stepper's iteration did not converge";
            break;
        default:
            what = code.words;
            break;
    }
    return "integration failed" + at_time(t) + ": " + what + " (" + code.code + ")" +
           (hint.empty() ? "; try a looser rtol/atol" : "; " + hint);
}

}  // namespace

/// Why a row cannot stand, from the model's limits (empty if it can): the hub rate past the spin above which the
/// straight beam is unstable, a hub angle beyond max_hub_angle, or a tip deflection beyond the beam's length.
std::string model_limit(const Row& r, double critical, double L)
{
    char text[300];
    if (std::abs(r.theta_dot) > critical) {
        std::snprintf(text, sizeof text,
                      "unstable: the hub rate %.4g rad/s has passed %.4g rad/s, above which the straight beam of "
                      "this model is unstable (its effective stiffness loses definiteness; order zero: the first "
                      "bending frequency) at t = %g s; order first or full stays stable",
                      r.theta_dot, critical, r.t);
        return text;
    }
    if (std::abs(r.theta) > max_hub_angle) {
        std::snprintf(text, sizeof text,
                      "the hub angle %.4g rad has passed %g rad, beyond which double precision no longer resolves "
                      "its small changes, at t = %g s",
                      r.theta, max_hub_angle, r.t);
        return text;
    }
    if (!std::isfinite(r.tip_uy) || std::abs(r.tip_uy) > L)
        return "unstable: tip deflection " + std::to_string(r.tip_uy) + " m exceeds the beam length" + at_time(r.t) +
               "; the small-deformation model no longer holds";
    return {};
}

/// The message for a failed step (empty for success), with its likely cause.
std::string Simulation::Run::why_failed(StepStatus status)
{
    if (status == StepStatus::success) return {};
    return step_failure(status, stepper_->failure_code(), t_,
                        status == StepStatus::equations_failed ? singular_cause() : failure_hint());
}

std::string Simulation::Run::failure_hint() const
{
    if (scene_.solver.rtol < 1e-14)  // about 50 ulps: no step meets a relative error below that
        return "rtol " + shortest(scene_.solver.rtol) + " is below what double precision can meet: use 1e-13 or more";
    return sim_.faster_stepper_hint();
}

/// Why the equations failed to evaluate: M lost definiteness (where, and what to do), or overflow.
std::string Simulation::Run::singular_cause() const
{
    const double tip = system_.indefinite_mass_tip();
    if (std::isnan(tip)) return "accelerations overflowed";
    char text[400];
    std::snprintf(text, sizeof text, "the mass matrix is not positive definite at a tip deflection of %.3g m, %.3g L",
                  tip, tip / scene_.parameters.L);
    std::string cause = text;
    if (model_.key().order == Order::first)
        cause +=
            ": order first truncates the kinetic energy for small deflections and its M can lose definiteness "
            "at large ones; --order full keeps M positive definite at any deflection";
    else
        cause += ": round-off in a badly conditioned mass matrix; fewer DOFs or another method";
    return cause;
}

/// The step budget: a run that needs more than solver.max_steps steps stops, early when its pace so far projects
/// past the budget (checked from a twentieth of it on), with the reason its steps are short.
std::string Simulation::Run::over_budget() const
{
    const long taken = stepper_->steps();
    if (taken < budget_ / 20 || t_ <= 0.0) return {};
    const double projected = static_cast<double>(taken) * scene_.output.t_end / t_;
    if (taken < budget_ && projected <= static_cast<double>(budget_)) return {};
    const double h = t_ / static_cast<double>(taken), omega = highest_frequency(model_, scene_.axial);
    char text[600];
    std::snprintf(text, sizeof text,
                  "too many steps: %ld by t = %g s, about %.3g to t_end, more than solver.max_steps = %ld; "
                  "the mean step %.3g s is %.3g / omega_max (highest frequency %.4g rad/s): ",
                  taken, t_, projected, budget_, h, h * omega, omega);
    std::string why = text;
    const std::string hint = sim_.faster_stepper_hint();
    // Round-off in the accelerations, about eps cond(M) relative, above the tolerance shrinks the steps of
    // every stepper; otherwise an explicit stepper on stiff equations is held by stability.
    if (const double cond = mass_condition(model_); cond * 0x1p-52 > scene_.solver.rtol) {
        std::snprintf(text, sizeof text,
                      "round-off bounds the steps (cond(M) %.3g at rest, of the whole mass "
                      "matrix in SI units%s, times the machine epsilon above rtol): fewer DOFs, another method, or a "
                      "looser rtol",
                      cond, model_.key().drive == Drive::torque ? " with the hub's row" : "");
        why += text;
    } else if (!hint.empty()) {
        why += "the steps are bound by stability, not accuracy: " + hint;
    } else {
        why += "the tolerance and the scene's stiffness need these steps: raise --max-steps to go on, or loosen rtol";
    }
    return why;
}

/// A run stopped by the model's limits or singular equations: if a re-run from rest at the tighter tolerance gets
/// past that time, the run's own error and not the model caused it, and the message says so.
std::string Simulation::Run::tolerance_as_cause(const std::string& failure)
{
    // The rows up to the failure: its row, or after a failed step the next row.
    std::vector<double> times;
    const bool at_row = !model_failure_.empty();
    for (long i = 1; i <= times_.last(); ++i) {
        times.push_back(times_(i));
        if (at_row ? times_(i) >= t_ * (1.0 - same_instant) : times_(i) > t_ * (1.0 + same_instant)) break;
    }
    return check_.tolerance_as_cause(failure, times, summary_);
}

}  // namespace hubbeam
