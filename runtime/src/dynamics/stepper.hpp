// Stepper: one interface for the integrator families a run can select (GSL odeiv2's steppers, SUNDIALS CVODE), so
// that the simulation steps, restarts and counts alike whichever family took the step.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "dynamics/integrate.hpp"

namespace hubbeam {

/// How a step ended, in hubbeam's terms: each family translates its own codes (GSL's statuses, CVODE's flags) where it
/// returns them, so that a caller tells apart the failures it explains without knowing which family stepped.
enum class StepStatus {
    success,
    equations_failed,  // the equations failed to evaluate: M not positive definite, or a non-finite result
    no_step,           // no step met the tolerance
    no_progress,       // the step size fell to round-off without meeting the tolerance
    not_converged,     // an implicit stepper's iteration did not converge
    other,             // another failure of the family's: its code says which
};

/// A failed step in its family's own terms, for the run's message: the code ("GSL status -1": every family states
/// its failures in GSL's numbering, CVODE's flags by the GSL status of their kind, so that one message serves) and,
/// for StepStatus::other, the family's words for it.
struct StepCode {
    std::string code, words;
};

/// A stepper family's integrator of one FirstOrderSystem, with the run's tolerances. A stepper belongs to one run:
/// it holds the run's step history and work arrays.
class Stepper {
public:
    virtual ~Stepper() = default;
    /// One step from t towards target, never past it: t and y advance to the step's end. No step is longer than
    /// h_max (the simulation's limit for interpolating rows inside a step).
    virtual StepStatus step(double& t, double target, double* y, double h_max) = 0;
    /// Steps from t to t1 exactly (a step ends at t1).
    virtual StepStatus advance(double& t, double t1, double* y) = 0;
    /// Forgets the step history at (t, y): the drive's derivatives jump at a breakpoint, and a multistep or
    /// implicit method must not carry its past across. The next step starts from the initial step size again.
    virtual void restart(double t, const double* y) = 0;
    /// Takes the last step again from its start (t, y), where the caller found it too long for its own purposes
    /// (interpolating rows): the history goes, the step size the tolerance chose stays.
    virtual void retake(double t, const double* y) = 0;
    /// The state at the middle of the last step, where the stepper computed one (gauss4's step doubling does): false
    /// otherwise.
    virtual bool midpoint(double*) const { return false; }
    /// How the Newton systems were solved, for the summary (empty for a stepper without them, or that does not say).
    virtual std::string newton_form() const { return {}; }
    /// The flops of one factorization and one solve of its Newton matrices where they are banded (gauss4's mass form),
    /// for pricing the stepper (stiffness.hpp's Pilot); none where they are dense or it has none.
    virtual std::optional<std::pair<double, double>> banded_newton_flops() const { return std::nullopt; }
    /// Whether midpoint() gives a computed state (then the simulation measures its interpolant's error against it).
    virtual bool has_midpoint() const { return false; }
    /// Steps taken since construction, through restarts.
    virtual long steps() const = 0;
    /// Steps the error test rejected since construction (0 from a stepper that does not count them).
    virtual long rejected() const { return 0; }
    /// The family's code of the last failure step() or advance() returned (empty before any).
    const StepCode& failure_code() const { return failure_; }

protected:
    /// A GSL status (GSL's steppers', gauss4's from its system's, a CVODE flag's GSL kind) as a StepStatus; a
    /// failure's code is kept for failure_code(). The one place that reads GSL's numbers (stepper.cpp).
    StepStatus from_gsl(int status);

private:
    StepCode failure_;
};

/// The integrator of system named stepper (stepper_names()), starting at (t0, y0) with initial step h0 and
/// tolerances |error| <= atol + rtol |y| per component. Throws std::invalid_argument for an unknown name.
std::unique_ptr<Stepper> make_stepper(FirstOrderSystem& system, const std::string& stepper, double t0, const double* y0,
                                      double h0, double atol, double rtol);

/// gauss4 (gauss_stepper.cpp): hubbeam's own two-stage Gauss-Legendre stepper.
std::unique_ptr<Stepper> make_gauss_stepper(FirstOrderSystem& system, double h0, double atol, double rtol);

}  // namespace hubbeam
