// Simulation: steps the integrators (stepper.hpp) freely (rows interpolated) or from output time to output time,
// through the drive's breakpoints, turning states into rows, and stops with a message when the solution goes bad.
#include <hubbeam/simulate.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <hubbeam/make_model.hpp>
#include "dynamics/integrate.hpp"
#include "dynamics/stepper.hpp"
#include "dynamics/stiffness.hpp"
#include "models/model_operations.hpp"
#include "simulation/column_check.hpp"
#include "simulation/error_check.hpp"
#include "simulation/run_rows.hpp"
#include "simulation/sensitivity.hpp"
#include "text/shortest.hpp"

namespace hubbeam {

namespace {


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

std::string at_time(double t)
{
    std::ostringstream s;
    s << " at t = " << t << " s";
    return s.str();
}

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
    case StepStatus::no_step: what = "the stepper could not take a step that meets the tolerance"; break;
    case StepStatus::no_progress: what = "the step size fell to round-off without meeting the tolerance"; break;
    case StepStatus::not_converged: what = "the implicit stepper's iteration did not converge"; break;
    default: what = code.words; break;
    }
    return "integration failed" + at_time(t) + ": " + what + " (" + code.code + ")" +
           (hint.empty() ? "; try a looser rtol/atol" : "; " + hint);
}

/// The run's output times: row 0 at t = 0, rows at multiples of dt_out, and a last one at t_end when dt_out does
/// not divide it, so that a run that exits 0 has reached t_end.
class OutputTimes {
public:
    explicit OutputTimes(const OutputOptions& o)
        : grid_(o.dt_out), t_end_(o.t_end),
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

/// The state at rest: the free hub at its initial angle (q[0], the first state: kept_coordinates keeps it first).
std::vector<double> initial_state(const FirstOrderSystem& system, const Model& model, const Scene& scene)
{
    std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0);
    if (model.key().drive == Drive::torque) y[0] = scene.motion.initial_theta();
    return y;
}

/// gauss4 from rest over plan's window at the scene's tolerances, the drive's breakpoints stepped to as a run does,
/// stopped once its steps exceed plan's budget (gauss4 has lost by then). Deterministic, as the choice must be.
Pilot pilot_run(const Scene& scene, const Model& model, PilotPlan plan)
{
    FirstOrderSystem system(model, scene.motion, scene.axial, scene.controller(), &scene.parameters);
    std::vector<double> y = initial_state(system, model, scene);
    const std::unique_ptr<Stepper> stepper =
        make_stepper(system, gauss_stepper, 0.0, y.data(), scene.solver.h0, scene.solver.atol, scene.solver.rtol);
    Pilot pilot{.t = 0.0, .steps = 0, .rtol = scene.solver.rtol};
    std::vector<double> stops = breaks_before(scene.motion, plan.t);
    stops.push_back(plan.t);
    for (const double stop : stops) {
        while (pilot.t < stop && stepper->steps() <= plan.budget)
            if (stepper->step(pilot.t, stop, y.data(), INFINITY) != StepStatus::success) {
                pilot.failed = true;
                return pilot;
            }
        if (stepper->steps() > plan.budget) break;
        stepper->restart(pilot.t, y.data());
    }
    pilot.steps = stepper->steps();
    return pilot;
}

}  // namespace

// ---- What a run and the error check's re-runs share (run_rows.hpp) ----

/// The drive's breakpoints inside (0, t_last), in order.
std::vector<double> breaks_before(const Motion& motion, double t_last)
{
    std::vector<double> breaks;
    for (double b : motion.breakpoints())
        if (b > 0.0 && b < t_last) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    return breaks;
}

/// The equations a run of scene integrates: the state's, or with the sensitivities of scene.output.sensitivities.
std::unique_ptr<FirstOrderSystem> system_of(const Model& model, const Scene& scene)
{
    if (!scene.output.sensitivities.empty()) return std::make_unique<SensitivitySystem>(model, scene);
    return std::make_unique<FirstOrderSystem>(model, scene.motion, scene.axial, scene.controller(), &scene.parameters);
}

RowMaker::RowMaker(const Model& model, const Motion& motion, FirstOrderSystem& system, const Control* control)
    : model_(model), motion_(motion), system_(system), control_(control),
      sensitivities_(dynamic_cast<SensitivitySystem*>(&system)), q_(static_cast<std::size_t>(model.nq())), qd_(q_),
      derived_(sensitivities_ != nullptr ? static_cast<std::size_t>(sensitivities_->count()) *
                                               sensitivity_outputs_of(model.key()).size()
                                         : 0),
      extended_(control != nullptr || system.auxiliary().count() > 0)
{
}

Row RowMaker::operator()(double t, const double* y)
{
    system_.full_state(t, y, q_.data(), qd_.data());
    const double* q = q_.data();
    const double* qd = qd_.data();
    const bool torque = model_.key().drive == Drive::torque;
    HubInput u = motion_.at(t);
    RowExtras extras;
    if (extended_) {
        if (torque) extras.tau = system_.torque(t, y);
        if (control_ != nullptr) {
            extras.theta_ref = u.theta;
            u = HubInput{};  // the model's input: the torque alone
            u.tau = extras.tau;
        }
        const auto at = [y](int i) { return i >= 0 ? y[i] : 0.0; };
        extras.controller_integral = at(system_.integral_index());
        extras.dissipated = at(system_.dissipated_index());
        extras.work = at(system_.work_index());
    }
    const Tip tip = model_.tip(q);
    extras.tip_uz = tip.uz;
    extras.tip_phi = tip.phi;
    const Energy e = model_.energy(u, q, qd);
    const double theta = torque ? q[0] : u.theta, theta_dot = torque ? qd[0] : u.theta_dot;
    Row r{t, theta, theta_dot, tip.uy, tip.ux1, tip.ux, e.kinetic(), e.U, model_.momentum(u, q, qd), e.T2 - e.T0 + e.U,
          extras};
    if (sensitivities_ != nullptr) {
        sensitivities_->outputs(t, y, derived_.data());
        r.derived = derived_.data();
    }
    return r;
}

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

/// One run of Simulation::run: the integration's state, with one member function per job (setup, the two stepping
/// loops, rows to the sink, the diagnosis of a stop, the checks and the summary).
class Simulation::Run {
public:
    explicit Run(const Simulation& simulation);
    RunSummary operator()(const RowSink& sink, const StopRequest& stop);

private:
    /// What free stepping carries from step to step: the step's start, the derivatives at its ends, the step limit.
    struct FreeStep {
        explicit FreeStep(std::size_t size) : y0(size), f0(size), f1(size), yi(size), y_mid(size), f_mid(size) {}
        std::vector<double> y0, f0, f1, yi, y_mid, f_mid;
        bool have_f0 = false, have_f1 = false;
        double t0 = 0.0;
        // Longest step whose interpolated rows stay within the tolerance (interpolation_error), learnt from the
        // steps that held rows: the quintic's error grows as h^6.
        double h_max = std::numeric_limits<double>::infinity();
    };

    std::string free_steps(const RowSink& sink, const StopRequest& stop);
    bool limit_interpolation(FreeStep& s);
    bool saturation_switch(FreeStep& s);
    void interpolate(const FreeStep& s, double t, double* y) const;
    std::string rows_in_step(FreeStep& s, long& i, const RowSink& sink, const StopRequest& stop);
    std::string row_steps(const RowSink& sink, const StopRequest& stop);
    const char* stop_requested(const StopRequest& stop);
    void restart();

    std::string emit(double ti, const double* state, const RowSink& sink);
    void monitor(const Row& r);

    std::string why_failed(StepStatus status);
    std::string failure_hint() const;
    std::string singular_cause() const;
    std::string over_budget() const;

    RunSummary finish(std::string failure);
    std::string untrustworthy();
    std::string tolerance_as_cause(const std::string& failure);

    const Simulation& sim_;
    const Scene& scene_;
    const Model& model_;
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    // The state's equations, or with the sensitivities beside them (system_of).
    const std::unique_ptr<FirstOrderSystem> owned_system_;
    FirstOrderSystem& system_;
    std::vector<double> y_;
    std::unique_ptr<Stepper> stepper_;
    RowMaker make_row_;
    const OutputTimes times_;
    std::vector<double> breaks_;  // the drive's, then the saturation switches found on the way
    std::size_t next_break_ = 0;
    const double critical_;  // critical_spin: passing it stops the run at once, not after metres of deflection
    const long budget_;      // solver.max_steps
    double t_ = 0.0, last_row_ = 0.0;
    RunSummary summary_;
    double jacobi0_ = 0.0;
    double u_min_ = INFINITY, u_max_ = -INFINITY;  // U's range since t_steady (the drift's reference under gravity)
    std::string model_failure_;  // set when a row broke a model limit
    RunErrorCheck check_;        // the error indicator; its columns are the ones a row writes
    std::vector<double> values_;  // the last row's values (append_row_values)
    bool non_finite_ = false;  // the run stopped at a row with a non-finite value, not written
};

Simulation::Run::Run(const Simulation& simulation)
    : sim_(simulation), scene_(simulation.scene_), model_(*simulation.model_),
      owned_system_(system_of(model_, scene_)), system_(*owned_system_), y_(initial_state(system_, model_, scene_)),
      stepper_(make_stepper(system_, sim_.stepper_, 0.0, y_.data(), scene_.solver.h0, scene_.solver.atol,
                            scene_.solver.rtol)),
      make_row_(model_, scene_.motion, system_, scene_.controller()), times_(scene_.output),
      breaks_(breaks_before(scene_.motion, times_(times_.last()))), critical_(critical_spin(model_)),
      budget_(scene_.solver.max_steps),
      check_(scene_, model_, system_, y_, times_(times_.last()),
             !sim_.check_error_ ? ErrorCheck::off : sim_.whole_run_ ? ErrorCheck::full : ErrorCheck::on,
             [&sim = sim_](double rtol) { return sim.automatic(rtol).stepper; })
{
    summary_.variant = model_.key().name();
    summary_.source = model_.source();
    if (!model_.origin().empty()) summary_.source += ", " + model_.origin();
    summary_.algebra = system_.linear_algebra();
    summary_.stepper = sim_.stepper_;
    summary_.stepper_why = sim_.stepper_why_;
    // The invariant monitor starts after the drive's last breakpoint, from where its Jacobi integral is constant; with
    // the hub's work a state, E + dissipated - work is constant from the start; with damping the Jacobi integral
    // plus the dissipated energy is (docs/model.md section 11.4). Gravity under a prescribed rotation leaves nothing
    // constant: U_g changes with the prescribed angle.
    const std::vector<double> all_breaks = scene_.motion.breakpoints();
    summary_.t_steady = all_breaks.empty() ? 0.0 : *std::max_element(all_breaks.begin(), all_breaks.end());
    summary_.energy_balance = system_.auxiliary().count() > 0 || scene_.control.has_value();
    if (system_.auxiliary().work) summary_.t_steady = 0.0;
    const bool turning = scene_.motion.kind != Motion::Kind::held;
    if (model_.key().extras.gravity && model_.key().drive == Drive::prescribed && turning)
        summary_.monitor_off = "gravity under a prescribed rotation: U_g follows the prescribed angle, no energy is "
                               "constant";
    // A drive that changes up to the run's end (a table to t_end, a spin-up longer than the run) leaves no row after
    // which the Jacobi integral is constant: a drift of 0 J over a single row would check nothing.
    const double t_last = times_(times_.last());
    if (summary_.monitor_off.empty() && summary_.t_steady >= t_last * (1.0 - same_instant))
        summary_.monitor_off = "the drive changes up to t = " + shortest(summary_.t_steady) + " s and the run ends at " +
                               shortest(t_last) + " s: no energy is constant while it does";
    // The reference of the Jacobi integral's drift: the vibration energy, the largest U since; under gravity U holds
    // the weight's potential, which can stay <= 0 (a free hub swinging below the horizontal), and its range since is
    // the energy that T and U exchange.
    summary_.invariant_reference = summary_.energy_balance       ? "the largest energy in it"
                                   : model_.key().extras.gravity ? "the range of U since"
                                                                 : "the vibration energy";
}

RunSummary Simulation::Run::operator()(const RowSink& sink, const StopRequest& stop)
{
    if (std::string failure = emit(0.0, y_.data(), sink); !failure.empty()) return finish(failure);
    return finish(scene_.solver.stepping == Stepping::free ? free_steps(sink, stop) : row_steps(sink, stop));
}

// ---- Stepping ----

/// Steps as the tolerance chooses them, to the drive's breakpoints and the last row; rows inside a step are
/// interpolated from its ends (the derivatives there cost one right-hand side per step that holds a row).
std::string Simulation::Run::free_steps(const RowSink& sink, const StopRequest& stop)
{
    FreeStep s(static_cast<std::size_t>(system_.size()));
    const double t_last = times_(times_.last());
    long i = 1;
    while (i <= times_.last()) {
        if (const char* why = stop_requested(stop)) return why;
        const bool to_break = next_break_ < breaks_.size();
        double target = to_break ? breaks_[next_break_] : t_last;
        // Where interpolating the rows would hold the steps to a quarter of the rows' spacing or less, a step that
        // ends at the next row is exact and cheaper. With a measured midpoint, an undamped stiff mode ringing at the
        // tolerance (the tip modes of BSIM's paper basis at Ny = 32) fails the interpolant at any step that does not
        // resolve it, and steps shortened to resolve it meet the stepper's error test where it is largest (omega h of
        // a few), from where the step never grew back (333,242 steps for that spin-up at Nx = 0). h_max grows back
        // by a quarter a row, so the interpolant is tried again once the ringing is gone.
        const bool to_row = stepper_->has_midpoint() && 4.0 * s.h_max < scene_.output.dt_out;
        if (to_row && times_(i) < target) target = times_(i);
        s.t0 = t_;
        s.y0 = y_;
        const StepStatus status = stepper_->step(t_, target, y_.data(), to_row ? INFINITY : s.h_max);
        if (std::string failure = why_failed(status); !failure.empty()) return failure;
        if (std::string failure = over_budget(); !failure.empty()) return failure;
        check_.step_from(s.t0, s.y0, t_);
        s.have_f1 = false;
        if (times_(i) < t_ * (1.0 - same_instant) && !limit_interpolation(s)) {
            // Too long a step to interpolate its rows within the tolerance (the first step to reach a row after a
            // start, whose length nothing bounded yet): taken again from its start, no longer than h_max.
            t_ = s.t0;
            y_ = s.y0;
            stepper_->retake(t_, y_.data());
            s.have_f1 = false;
            continue;
        }
        if (saturation_switch(s)) continue;
        if (to_row && t_ >= times_(i) * (1.0 - same_instant)) s.h_max *= 1.25;
        if (std::string failure = rows_in_step(s, i, sink, stop); !failure.empty()) return failure;
        std::swap(s.f0, s.f1);  // the derivative at this step's end starts the next step
        s.have_f0 = s.have_f1;
        if (to_break && t_ >= breaks_[next_break_]) {  // not a row that ended the step before the breakpoint
            ++next_break_;
            restart();
        }
    }
    return {};
}

/// Whether a control's saturation switches inside the step just taken: the torque's derivatives by the state jump
/// there, and a step across the kink has a first-order error that gauss4's step doubling does not estimate (its
/// sensitivities to the gains came 1e-5 off at rtol 1e-10, 1e-11 with the switch a breakpoint). The switch, located
/// on the step's interpolant, becomes a breakpoint, and the step is taken again from its start (its rows not yet
/// written); true then. gauss4 only: the explicit steppers' embedded estimates see the kink, and GSL's rk4imp
/// shrinks its step to nanoseconds there before it takes one across, after which a step to the switch fails.
bool Simulation::Run::saturation_switch(FreeStep& s)
{
    if (!scene_.control || scene_.control->law || sim_.stepper_ != gauss_stepper) return false;
    const bool before = system_.saturated(s.t0, s.y0.data());
    if (system_.saturated(t_, y_.data()) == before) return false;
    if (!s.have_f0) system_.rhs(s.t0, s.y0.data(), s.f0.data());
    if (!s.have_f1) system_.rhs(t_, y_.data(), s.f1.data());
    s.have_f0 = s.have_f1 = true;
    double lo = s.t0, hi = t_;
    for (int k = 0; k < 60 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)); ++k) {
        const double mid = 0.5 * (lo + hi);
        interpolate(s, mid, s.yi.data());
        (system_.saturated(mid, s.yi.data()) == before ? lo : hi) = mid;
    }
    // A switch within a thousandth of the step from either end changes the step's error by no more than that
    // fraction of a kink's (and is the switch a step ended at, met again where the integrated state has not quite
    // crossed): no breakpoint, whose step would be too short to take.
    const double h = t_ - s.t0;
    if (hi - s.t0 <= 1e-3 * h || t_ - hi <= 1e-3 * h) return false;
    breaks_.insert(breaks_.begin() + static_cast<std::ptrdiff_t>(next_break_), hi);
    t_ = s.t0;
    y_ = s.y0;
    stepper_->retake(t_, y_.data());
    s.have_f1 = false;
    return true;
}

/// The state at t inside the free step s (its end derivatives known), block by block: the state's own, then a
/// sensitivity system's derivatives of it, each with the state's layout, so each gets the quintic of positions.
void Simulation::Run::interpolate(const FreeStep& s, double t, double* y) const
{
    const int size = system_.size(), n = system_.state_size(), aux = system_.auxiliary().count();
    for (int b = 0; b < size; b += n)
        interpolate_state(s.t0, s.y0.data() + b, s.f0.data() + b, t_, y_.data() + b, s.f1.data() + b, t, n, y + b, aux);
}

/// For a step that holds rows: the interpolant's error at the step's middle bounds the next steps (h_max); false when
/// the stepper's own middle state shows it exceeds the tolerance in this step.
bool Simulation::Run::limit_interpolation(FreeStep& s)
{
    // The interpolant's error is weighed where the steps' is (controlled_size): the sensitivities' only when their
    // error is controlled.
    const int controlled = system_.controlled_size();
    if (!s.have_f0) system_.rhs(s.t0, s.y0.data(), s.f0.data());
    system_.rhs(t_, y_.data(), s.f1.data());
    s.have_f0 = s.have_f1 = true;
    const double t_mid = 0.5 * (s.t0 + t_);
    interpolate(s, t_mid, s.y_mid.data());
    // y is blocks of the state's layout: the state, then a sensitivity system's derivatives of it.
    const int n = system_.state_size(), aux = system_.auxiliary().count();
    if (stepper_->midpoint(s.f_mid.data())) {
        // The stepper's own state at the middle: the interpolant's error there measured, not estimated from the
        // acceleration (whose stiff terms overstate a position error by (omega h)^2 / 24). An interpolated rate
        // differences the positions at the ends over h, so their round-off, 2 eps |p| / h at most twice over
        // (the quintic's weights at the middle are 1.875), is no error a shorter step could remove: it counts as
        // tolerance, or a large angle's rate would shrink the steps without end.
        const int k = (n - aux) / 2;
        const double h = t_ - s.t0, eps = std::numeric_limits<double>::epsilon();
        double ratio = 0.0;
        for (int i = 0; i < controlled; ++i) {
            double tolerance = scene_.solver.atol + scene_.solver.rtol * std::abs(s.f_mid[i]);
            if (const int j = i % n; j >= k && j < 2 * k)
                tolerance += 4.0 * eps * (std::abs(s.y0[i - k]) + std::abs(y_[i - k])) / h;
            ratio = std::max(ratio, std::abs(s.y_mid[i] - s.f_mid[i]) / tolerance);
        }
        // A growth under a fifth is not taken, as for the stepper's own steps: h_max then stays put instead of
        // creeping up to the step that fails this test, and the Newton matrices factored for it stay valid (the main
        // job: 1,414 steps and 32 refactorizations, against 1,679 steps and 346).
        const double growth = std::min(4.0, 0.9 * std::pow(std::max(ratio, 1e-12), -1.0 / 5.0));
        s.h_max = h * (growth > 1.0 && growth < 1.2 ? 1.0 : growth);
        return ratio <= 1.0;
    }
    // Estimated only: the step stands (GSL's steppers, whose output this has always been), the next ones obey h_max.
    system_.rhs(t_mid, s.y_mid.data(), s.f_mid.data());
    double ratio = 0.0;
    for (int b = 0; b < controlled; b += n)
        ratio = std::max(ratio, interpolation_error(s.t0, s.y0.data() + b, s.f0.data() + b, t_, y_.data() + b,
                                                    s.f1.data() + b, s.y_mid.data() + b, s.f_mid.data() + b, n,
                                                    scene_.solver.atol, scene_.solver.rtol, aux));
    s.h_max = (t_ - s.t0) * std::min(4.0, 0.9 * std::pow(std::max(ratio, 1e-12), -1.0 / 6.0));
    return true;
}

/// The rows from index i up to the step's end t_, interpolated where they fall inside the step; advances i.
std::string Simulation::Run::rows_in_step(FreeStep& s, long& i, const RowSink& sink, const StopRequest& stop)
{
    for (; i <= times_.last() && times_(i) <= t_ * (1.0 + same_instant); ++i) {
        const double ti = times_(i);
        if (const char* why = stop_requested(stop)) return why;
        const double* state = y_.data();
        if (std::abs(ti - t_) > same_instant * ti) {
            if (!s.have_f0) system_.rhs(s.t0, s.y0.data(), s.f0.data());
            if (!s.have_f1) system_.rhs(t_, y_.data(), s.f1.data());
            s.have_f0 = s.have_f1 = true;
            interpolate(s, ti, s.yi.data());
            state = s.yi.data();
        }
        if (std::string failure = emit(ti, state, sink); !failure.empty()) return failure;
        last_row_ = ti;
    }
    return {};
}

/// A step ends at every row, and at each breakpoint on the way.
std::string Simulation::Run::row_steps(const RowSink& sink, const StopRequest& stop)
{
    const auto advance = [&](double t1) { return why_failed(stepper_->advance(t_, t1, y_.data())); };
    for (long i = 1; i <= times_.last(); ++i) {
        if (const char* why = stop ? stop() : nullptr) return why;
        const double ti = times_(i);
        check_.step_from(t_, y_, ti);
        for (; next_break_ < breaks_.size() && breaks_[next_break_] <= ti * (1.0 + same_instant); ++next_break_) {
            const double b = breaks_[next_break_];
            const double tb = std::abs(b - ti) <= same_instant * ti ? ti : b;
            if (std::string failure = advance(tb); !failure.empty()) return failure;
            restart();
        }
        if (t_ < ti)
            if (std::string failure = advance(ti); !failure.empty()) return failure;
        if (std::string failure = over_budget(); !failure.empty()) return failure;
        if (std::string failure = emit(ti, y_.data(), sink); !failure.empty()) return failure;
    }
    return {};
}

/// The stop request's reason, or nullptr to go on; a stop ends the run at the last row written.
const char* Simulation::Run::stop_requested(const StopRequest& stop)
{
    const char* why = stop ? stop() : nullptr;
    if (why != nullptr) t_ = last_row_;
    return why;
}

/// At a breakpoint the drive's derivatives jump: the step history is discarded there.
void Simulation::Run::restart()
{
    stepper_->restart(t_, y_.data());
    check_.restarted(t_, y_);
}

// ---- Rows ----

/// The row at ti to the sink (the observer first), then the monitors; or why the run must stop.
std::string Simulation::Run::emit(double ti, const double* state, const RowSink& sink)
{
    const Row r = make_row_(ti, state);
    values_.clear();
    append_row_values(r, check_.columns().set, values_);
    for (std::size_t c = 0; c < values_.size(); ++c)
        if (!std::isfinite(values_[c])) {  // not a row to write: the run ends with the rows before it
            model_failure_ = "unstable: the solution became non-finite" + at_time(ti) + " (" + check_.columns().names[c] +
                             " is " + std::to_string(values_[c]) + ")";
            non_finite_ = true;
            t_ = ti;
            return model_failure_;
        }
    if (sim_.observer_) sim_.observer_(ti, make_row_.q());
    summary_.max_abs_tip_uy = std::max(summary_.max_abs_tip_uy, std::abs(r.tip_uy));
    sink(r);
    last_row_ = ti;
    if (!(std::abs(r.theta_dot) > critical_)) monitor(r);
    model_failure_ = model_limit(r, critical_, scene_.parameters.L);
    if (!model_failure_.empty()) t_ = ti;  // the run ends with this row, whatever the step reached
    return model_failure_;
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
        const double energy = model_.key().drive == Drive::torque ? std::abs(r.kinetic) + std::abs(r.potential) : r.potential;
        summary_.vibration_energy = std::max({summary_.vibration_energy, energy, std::abs(r.extras.dissipated),
                                              std::abs(r.extras.work)});
    } else if (summary_.monitor_off.empty() && r.t > 0.0 && r.t >= summary_.t_steady) {  // from the first row after rest
        if (summary_.vibration_energy < 0.0) jacobi0_ = r.jacobi, summary_.vibration_energy = 0.0;
        summary_.jacobi_drift = std::max(summary_.jacobi_drift, std::abs(r.jacobi - jacobi0_));
        u_min_ = std::min(u_min_, r.potential);
        u_max_ = std::max(u_max_, r.potential);
        summary_.vibration_energy =
            std::max(summary_.vibration_energy, model_.key().extras.gravity ? u_max_ - u_min_ : r.potential);
    }
    check_.record(r, values_);
}

// ---- Why a run stops ----

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
        cause += ": order first truncates the kinetic energy for small deflections and its M can lose definiteness "
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
        std::snprintf(text, sizeof text, "round-off bounds the steps (cond(M) %.3g at rest, of the whole mass "
                      "matrix in SI units%s, times the machine epsilon above rtol): fewer DOFs, another method, or a "
                      "looser rtol", cond, model_.key().drive == Drive::torque ? " with the hub's row" : "");
        why += text;
    } else if (!hint.empty()) {
        why += "the steps are bound by stability, not accuracy: " + hint;
    } else {
        why += "the tolerance and the scene's stiffness need these steps: raise --max-steps to go on, or loosen rtol";
    }
    return why;
}

// ---- Checks and summary ----

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
    if (failure.empty()) failure = untrustworthy();
    else if (!model_failure_.empty() || failure.rfind("unstable: the equations", 0) == 0)
        failure = tolerance_as_cause(failure);
    if (non_finite_)
        failure += last_row_ < t_ ? "; the rows up to t = " + shortest(last_row_) + " s are written, not this one"
                                  : "; no row is written";
    if (summary_.check_rtol > 0.0)  // a check ran
        summary_.check_wall_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - checked).count() + check_.whole_run_seconds();
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

namespace {

/// The auxiliary states a run of scene carries (FirstOrderSystem::Auxiliary).
int auxiliary_count(const Scene& scene)
{
    return Auxiliary::of(scene.key(), scene.controller(), &scene.parameters, scene.wants({"ki"})).count();
}

}  // namespace

Simulation::Simulation(const Scene& scene, const std::function<void(const std::string&)>& note)
    : scene_(scene), model_(make_model(scene.key(), scene.parameters, scene.source, note))
{
    choose_stepper();
}

Simulation::Simulation(const Scene& scene, std::shared_ptr<const Model> model) : scene_(scene), model_(std::move(model))
{
    const std::string variant = scene.key().name();
    if (model_ == nullptr) throw std::invalid_argument("a simulation of variant " + variant + " was given no model");
    if (!(model_->key() == scene.key()))
        throw std::invalid_argument("a model of variant " + model_->key().name() + " cannot run a scene of variant " +
                                    variant);
    // A model holds its parameters in its coefficients: one built at others would run another beam.
    if (!model_->parameters().empty() && model_->parameters() != scene.parameters.packed())
        throw std::invalid_argument("the model of variant " + variant +
                                    " was built at other physical parameters than the scene's");
    choose_stepper();
}

void Simulation::choose_stepper()
{
    check_error_ = scene_.solver.error_check != ErrorCheck::off;
    whole_run_ = scene_.solver.error_check == ErrorCheck::full;
    stepper_ = scene_.solver.stepper;
    if (stepper_ == automatic_stepper_word) {
        const StepperChoice choice = automatic(scene_.solver.rtol);
        stepper_ = choice.stepper;
        stepper_why_ = choice.why;
    }
}

Simulation::~Simulation() = default;

StepperChoice Simulation::automatic(double rtol) const
{
    const double t_end = scene_.output.t_end;
    const int auxiliary = auxiliary_count(scene_);
    if (!rates_) rates_ = std::make_unique<RatesAtRest>(rates_at_rest(*model_, scene_.axial));
    if (!pilot_decided_ && needs_pilot(*model_, scene_.solver.rtol)) {
        const StepperCosts rule =
            predicted_costs(*model_, scene_.axial, scene_.solver.rtol, t_end, auxiliary, nullptr, rates_.get());
        pilot_ = std::make_unique<Pilot>(pilot_run(scene_, *model_, pilot_plan(rule, t_end)));
    }
    pilot_decided_ = true;  // needs_pilot's eigenvalues once, not at every check's re-run
    return automatic_stepper(*model_, scene_.axial, rtol, t_end, auxiliary,
                             rtol >= gauss4_tightest_rtol ? pilot_.get() : nullptr, rates_.get());
}

std::string Simulation::faster_stepper_hint() const
{
    if (!stepper_why_.empty()) return {};  // chosen automatically already
    const StepperChoice choice = automatic(scene_.solver.rtol);
    if (choice.stepper == stepper_) return {};
    return "--stepper " + choice.stepper + " suits this scene (" + choice.why.substr(choice.why.find(' ') + 1) + ")";
}

RunSummary Simulation::run(const RowSink& sink, const StopRequest& stop) { return Run(*this)(sink, stop); }

RunSummary simulate(const Scene& scene, const RowSink& sink) { return Simulation(scene).run(sink); }

ColumnSet optional_columns_of(const Scene& scene)
{
    const Control* control = scene.controller();
    const VariantKey key = scene.key();
    const Auxiliary aux = Auxiliary::of(key, control, &scene.parameters, scene.wants({"ki"}));
    const bool torque = key.drive == Drive::torque && (control != nullptr || key.extras.damping);
    const bool has[] = {key.nz > 0, key.nt > 0, torque, control != nullptr && !control->law, aux.integral,
                        aux.dissipated, aux.work};
    static_assert(std::size(has) == optional_width);
    ColumnSet set;
    for (std::size_t i = 0; i < optional_width; ++i)
        if (has[i]) set.bits |= 1u << i;
    set.derived = sensitivity_columns(scene.output.sensitivities, key);
    return set;
}

std::vector<std::string> sensitivity_outputs_of(const VariantKey& key)
{
    std::vector<std::string> outputs(std::begin(sensitivity_outputs), std::end(sensitivity_outputs));
    if (key.nz > 0) outputs.emplace_back(blade_sensitivity_outputs[0]);
    if (key.nt > 0) outputs.emplace_back(blade_sensitivity_outputs[1]);
    return outputs;
}

std::vector<std::string> sensitivity_columns(const std::vector<std::string>& parameters, const VariantKey& key)
{
    std::vector<std::string> names;
    const std::vector<std::string> outputs = sensitivity_outputs_of(key);
    for (const std::string& p : parameters)
        for (const std::string& o : outputs) names.push_back("d_" + o + "/d_" + p);
    return names;
}

std::vector<std::string> row_column_names(const ColumnSet& set)
{
    std::vector<std::string> names;
    for (const RowColumn& c : row_columns) names.emplace_back(c.name);
    for (std::size_t i = 0; i < optional_width; ++i)
        if (set.has(i)) names.emplace_back(optional_columns[i].name);
    names.insert(names.end(), set.derived.begin(), set.derived.end());
    return names;
}

std::string row_header(const ColumnSet& set)
{
    std::string h;
    for (const std::string& name : row_column_names(set)) h += (h.empty() ? "" : ",") + name;
    return h;
}

const char* row_header()
{
    static const std::string header = [] {
        std::string h;
        for (const RowColumn& c : row_columns) {
            if (!h.empty()) h += ',';
            h += c.name;
        }
        return h;
    }();
    return header.c_str();
}

}  // namespace hubbeam
