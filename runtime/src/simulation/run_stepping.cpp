// A run's stepping (Simulation::Run): free steps with rows interpolated inside them, or a step to every row,
// through the drive's breakpoints and a control's saturation switches.
#include "simulation/run.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "dynamics/integrate.hpp"
#include "dynamics/stepper.hpp"
#include "simulation/run_rows.hpp"

namespace hubbeam {

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

}  // namespace hubbeam
