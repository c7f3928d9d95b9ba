// Simulation: steps GSL's odeiv2 integrators freely (rows interpolated) or from output time to output time,
// through the drive's breakpoints, turning states into rows, and stops with a message when the solution goes bad.
#include "simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include <gsl/gsl_errno.h>

#include "integrate.hpp"
#include "make_model.hpp"
#include "shortest.hpp"
#include "stiffness.hpp"

namespace hubbeam {

namespace {

// Times are compared relative to their size: an output time and a breakpoint closer than this are one
// instant, and t_end / dt_out within this of an integer counts as that integer.
constexpr double same_instant = 1e-12;

struct DriverDeleter {
    void operator()(gsl_odeiv2_driver* d) const { gsl_odeiv2_driver_free(d); }
};

/// GSL's error handler off for one scope (GSL's default aborts the process; odeiv2 failures must come
/// back as status codes), restored afterwards so that the caller's handler is left as it was.
class QuietGsl {
public:
    QuietGsl() : previous_(gsl_set_error_handler_off()) {}
    ~QuietGsl() { gsl_set_error_handler(previous_); }
    QuietGsl(const QuietGsl&) = delete;
    QuietGsl& operator=(const QuietGsl&) = delete;

private:
    gsl_error_handler_t* previous_;
};

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

/// The message for a failed step, or empty for success. hint says what to do: for GSL_EBADFUNC the cause the
/// system found, otherwise a stepper that suits the scene (or nothing).
std::string step_failure(int status, double t, const std::string& hint)
{
    if (status == GSL_SUCCESS) return {};
    if (status == GSL_EBADFUNC)
        return "unstable: the equations became singular or non-finite" + at_time(t) + " (" + hint + ")";
    // GSL's own words ("failure", "no progress") say little: what they mean for a step.
    std::string what;
    switch (status) {
    case GSL_FAILURE: what = "the stepper could not take a step that meets the tolerance"; break;
    case GSL_ENOPROG: what = "the step size fell to round-off without meeting the tolerance"; break;
    case GSL_EMAXITER: what = "the implicit stepper's iteration did not converge"; break;
    default: what = gsl_strerror(status); break;
    }
    return "integration failed" + at_time(t) + ": " + what + " (GSL status " + std::to_string(status) + ")" +
           (hint.empty() ? "; try a looser rtol/atol" : "; " + hint);
}

/// The drive's breakpoints inside (0, t_last), in order.
std::vector<double> breaks_before(const Motion& motion, double t_last)
{
    std::vector<double> breaks;
    for (double b : motion.breakpoints())
        if (b > 0.0 && b < t_last) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    return breaks;
}

}  // namespace

Simulation::Simulation(const Scene& scene, const std::function<void(const std::string&)>& note) : scene_(scene)
{
    model_ = make_model(scene.key(), scene.parameters, scene.source, note);
    stepper_ = scene.solver.stepper;
    if (stepper_ == automatic_stepper_word) {
        const StepperChoice choice = automatic_stepper(*model_, scene.axial);
        stepper_ = choice.stepper;
        stepper_why_ = choice.why;
    }
}

Simulation::~Simulation() = default;

std::string Simulation::faster_stepper_hint() const
{
    if (!stepper_why_.empty()) return {};  // chosen automatically already
    const StepperChoice choice = automatic_stepper(*model_, scene_.axial);
    if (choice.stepper == stepper_) return {};
    return "--stepper " + choice.stepper + " suits this scene (" + choice.why.substr(choice.why.find(' ') + 1) + ")";
}

RunSummary Simulation::run(const RowSink& sink, const StopRequest& stop)
{
    const auto start = std::chrono::steady_clock::now();
    const QuietGsl quiet;
    const Model& model = *model_;
    const VariantKey& key = model.key();
    const Motion& motion = scene_.motion;
    RunSummary summary;
    summary.variant = key.name();
    summary.source = model.source();
    if (!model.origin().empty()) summary.source += ", " + model.origin();

    FirstOrderSystem system(model, motion, scene_.axial);
    summary.algebra = system.linear_algebra();
    summary.stepper = stepper_;
    summary.stepper_why = stepper_why_;
    const gsl_odeiv2_step_type* type = step_type(stepper_);
    if (type == nullptr) throw std::invalid_argument("unknown stepper '" + stepper_ + "'");
    const std::unique_ptr<gsl_odeiv2_driver, DriverDeleter> driver(gsl_odeiv2_driver_alloc_y_new(
        system.gsl(), type, scene_.solver.h0, scene_.solver.atol, scene_.solver.rtol));
    if (!driver) throw std::runtime_error("GSL could not allocate the " + stepper_ + " driver");

    const int n = model.nq();
    const bool torque = key.drive == Drive::torque;
    std::vector<double> y(static_cast<std::size_t>(system.size()), 0.0);
    std::vector<double> q_full(static_cast<std::size_t>(n)), qd_full(static_cast<std::size_t>(n));
    double t = 0.0;
    long steps = 0;

    auto row_at = [&](double ti, const double* state) {
        system.full_state(ti, state, q_full.data(), qd_full.data());
        const double* q = q_full.data();
        const double* qd = qd_full.data();
        if (observer_) observer_(ti, q);
        const HubInput u = motion.at(ti);
        const Tip tip = model.tip(q);
        const Energy e = model.energy(u, q, qd);
        const double theta = torque ? q[0] : motion.theta(ti), theta_dot = torque ? qd[0] : u.theta_dot;
        const Row r{ti, theta, theta_dot, tip.uy, tip.ux1, tip.ux, e.kinetic(), e.U, model.momentum(u, q, qd),
                    e.T2 - e.T0 + e.U};
        summary.max_abs_tip_uy = std::max(summary.max_abs_tip_uy, std::abs(r.tip_uy));
        return r;
    };
    // The invariant monitor: once the drive is steady (after its last breakpoint) the Jacobi integral is constant
    // (docs/model.md section 7); its drift against the vibration energy (the largest U since) says whether the
    // rows can be trusted.
    const std::vector<double> all_breaks = motion.breakpoints();
    summary.t_steady = all_breaks.empty() ? 0.0 : *std::max_element(all_breaks.begin(), all_breaks.end());
    double jacobi0 = 0.0;
    auto finish = [&](std::string failure) {
        if (failure.empty() && summary.jacobi_drift > invariant_tolerance * summary.vibration_energy &&
            summary.vibration_energy > 0.0) {
            char text[320];
            std::snprintf(text, sizeof text,
                          "untrustworthy: the Jacobi integral drifted by %.3g J after the drive ended at t = %g s, "
                          "%.2g of the vibration energy (more than %g): the tolerance is too loose for the stepper",
                          summary.jacobi_drift, summary.t_steady, summary.jacobi_drift / summary.vibration_energy,
                          invariant_tolerance);
            failure = text;
        }
        summary.steps = steps + static_cast<long>(driver->e->count);
        summary.rhs_evals = system.evaluations();
        summary.jacobian_evals = system.jacobian_evaluations();
        summary.completed = failure.empty();
        summary.failure = failure;
        summary.t_reached = t;
        summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return summary;
    };
    const auto failure_hint = [&]() -> std::string {
        if (scene_.solver.rtol < 1e-14)  // about 50 ulps: no step meets a relative error below that
            return "rtol " + shortest(scene_.solver.rtol) + " is below what double precision can meet: use 1e-13 or more";
        return faster_stepper_hint();
    };
    // Why the equations failed to evaluate: M lost definiteness (where, and what to do), or overflow.
    const auto singular_cause = [&]() -> std::string {
        const double tip = system.indefinite_mass_tip();
        if (std::isnan(tip)) return "accelerations overflowed";
        char text[400];
        std::snprintf(text, sizeof text, "the mass matrix is not positive definite at a tip deflection of %.3g m, %.3g L",
                      tip, tip / scene_.parameters.L);
        std::string cause = text;
        if (key.order == Order::first)
            cause += ": order first truncates the kinetic energy for small deflections and its M can lose definiteness "
                     "at large ones; --order full keeps M positive definite at any deflection";
        else
            cause += ": round-off in a badly conditioned mass matrix; fewer DOFs or another method";
        return cause;
    };
    const auto why_failed = [&](int status) -> std::string {
        if (status == GSL_SUCCESS) return {};
        return step_failure(status, t, status == GSL_EBADFUNC ? singular_cause() : failure_hint());
    };
    auto advance = [&](double t1) { return why_failed(gsl_odeiv2_driver_apply(driver.get(), &t, t1, y.data())); };
    // The step budget: a run that needs more than solver.max_steps steps stops, early when its pace so far projects
    // past the budget (checked from a twentieth of it on), with the reason its steps are short.
    const long budget = scene_.solver.max_steps;
    auto over_budget = [&]() -> std::string {
        const long taken = steps + static_cast<long>(driver->e->count);
        if (taken < budget / 20 || t <= 0.0) return {};
        const double projected = static_cast<double>(taken) * scene_.output.t_end / t;
        if (taken < budget && projected <= static_cast<double>(budget)) return {};
        const double h = t / static_cast<double>(taken), omega = highest_frequency(model, scene_.axial);
        char text[600];
        std::snprintf(text, sizeof text,
                      "too many steps: %ld by t = %g s, about %.3g to t_end, more than solver.max_steps = %ld; "
                      "the mean step %.3g s is %.3g / omega_max (highest frequency %.4g rad/s): ",
                      taken, t, projected, budget, h, h * omega, omega);
        std::string why = text;
        const std::string hint = faster_stepper_hint();
        // Round-off in the accelerations, about eps cond(M) relative, above the tolerance shrinks the steps of
        // every stepper; otherwise an explicit stepper on stiff equations is held by stability.
        if (const double cond = mass_condition(model); cond * 0x1p-52 > scene_.solver.rtol) {
            std::snprintf(text, sizeof text, "round-off bounds the steps (cond(M) %.3g at rest, of the whole mass "
                          "matrix in SI units%s, times the machine epsilon above rtol): fewer DOFs, another method, or a "
                          "looser rtol", cond, key.drive == Drive::torque ? " with the hub's row" : "");
            why += text;
        } else if (!hint.empty()) {
            why += "the steps are bound by stability, not accuracy: " + hint;
        } else {
            why += "the tolerance and the scene's stiffness need these steps: raise --max-steps to go on, or loosen rtol";
        }
        return why;
    };
    // At a breakpoint the drive's derivatives jump: the step history is discarded there.
    auto restart = [&] {
        steps += static_cast<long>(driver->e->count);
        gsl_odeiv2_driver_reset(driver.get());
    };

    sink(row_at(0.0, y.data()));
    const OutputClock grid(scene_.output.dt_out);
    const double t_end = scene_.output.t_end;
    const long grid_rows = static_cast<long>(std::floor(t_end / scene_.output.dt_out * (1.0 + same_instant)));
    // Rows at multiples of dt_out, and a last one at t_end when dt_out does not divide it: a run that exits 0
    // has reached t_end.
    const bool last_off_grid = grid(grid_rows) < t_end * (1.0 - same_instant);
    const long rows = grid_rows + (last_off_grid ? 1 : 0);
    const auto clock = [&](long i) { return i > grid_rows ? t_end : grid(i); };
    const std::vector<double> breaks = breaks_before(motion, clock(rows));
    auto next_break = breaks.begin();
    // Known before the run: the spin above which this model's straight beam is unstable (infinite for orders
    // first and full), so that passing it stops the run at once instead of after metres of deflection.
    const double critical = critical_spin(model);
    // A row to the sink, or why the run must stop (the small-deformation model no longer holds).
    auto emit = [&](double ti, const double* state) -> std::string {
        const Row r = row_at(ti, state);
        sink(r);
        if (std::abs(r.theta_dot) > critical) {
            char text[300];
            std::snprintf(text, sizeof text,
                          "unstable: the hub rate %.4g rad/s has passed %.4g rad/s, above which the straight beam of "
                          "this model is unstable (its effective stiffness loses definiteness; order zero: the first "
                          "bending frequency) at t = %g s; order first or full stays stable",
                          r.theta_dot, critical, ti);
            return text;
        }
        if (ti >= summary.t_steady) {
            if (summary.vibration_energy < 0.0) jacobi0 = r.jacobi, summary.vibration_energy = 0.0;
            summary.jacobi_drift = std::max(summary.jacobi_drift, std::abs(r.jacobi - jacobi0));
            summary.vibration_energy = std::max(summary.vibration_energy, r.potential);
        }
        if (!std::isfinite(r.tip_uy) || std::abs(r.tip_uy) > scene_.parameters.L)
            return "unstable: tip deflection " + std::to_string(r.tip_uy) + " m exceeds the beam length" + at_time(ti) +
                   "; the small-deformation model no longer holds";
        return {};
    };

    if (scene_.solver.stepping == Stepping::free) {
        // Steps as the tolerance chooses them, to the drive's breakpoints and the last row; rows inside a step are
        // interpolated from its ends (the derivatives there cost one right-hand side per step that holds a row).
        const int size = system.size();
        std::vector<double> y0(static_cast<std::size_t>(size)), f0(y0), f1(y0), yi(y0);
        bool have_f0 = false;
        double h = scene_.solver.h0;
        // Longest step whose interpolated rows stay within the tolerance (interpolation_error), learnt from the
        // steps that held rows: the quintic's error grows as h^6.
        double h_max = std::numeric_limits<double>::infinity();
        std::vector<double> y_mid(y0), f_mid(y0);
        const double t_last = clock(rows);
        long i = 1;
        double last_row = 0.0;
        // A stop request is honoured between rows, asked before each step and each row; the run then ends at the
        // last row written.
        auto stop_here = [&]() -> const char* {
            const char* why = stop ? stop() : nullptr;
            if (why != nullptr) t = last_row;
            return why;
        };
        while (i <= rows) {
            if (const char* why = stop_here()) return finish(why);
            const bool to_break = next_break != breaks.end();
            const double target = to_break ? *next_break : t_last;
            const double t0 = t;
            y0 = y;
            h = std::min(h, h_max);
            const int status =
                gsl_odeiv2_evolve_apply(driver->e, driver->c, driver->s, system.gsl(), &t, target, &h, y.data());
            if (std::string failure = why_failed(status); !failure.empty()) return finish(failure);
            if (std::string failure = over_budget(); !failure.empty()) return finish(failure);
            bool have_f1 = false;
            if (i <= rows && clock(i) < t * (1.0 - same_instant)) {  // rows inside the step: check the interpolant
                if (!have_f0) system.rhs(t0, y0.data(), f0.data());
                system.rhs(t, y.data(), f1.data());
                have_f0 = have_f1 = true;
                const double t_mid = 0.5 * (t0 + t);
                interpolate_state(t0, y0.data(), f0.data(), t, y.data(), f1.data(), t_mid, size, y_mid.data());
                system.rhs(t_mid, y_mid.data(), f_mid.data());
                const double ratio = interpolation_error(t0, y0.data(), f0.data(), t, y.data(), f1.data(), y_mid.data(),
                                                         f_mid.data(), size, scene_.solver.atol, scene_.solver.rtol);
                h_max = (t - t0) * std::min(4.0, 0.9 * std::pow(std::max(ratio, 1e-12), -1.0 / 6.0));
            }
            for (; i <= rows && clock(i) <= t * (1.0 + same_instant); ++i) {
                const double ti = clock(i);
                if (const char* why = stop_here()) return finish(why);
                const double* state = y.data();
                if (std::abs(ti - t) > same_instant * ti) {
                    if (!have_f0) system.rhs(t0, y0.data(), f0.data());
                    if (!have_f1) system.rhs(t, y.data(), f1.data());
                    have_f0 = have_f1 = true;
                    interpolate_state(t0, y0.data(), f0.data(), t, y.data(), f1.data(), ti, size, yi.data());
                    state = yi.data();
                }
                if (std::string failure = emit(ti, state); !failure.empty()) return finish(failure);
                last_row = ti;
            }
            std::swap(f0, f1);  // the derivative at this step's end starts the next step
            have_f0 = have_f1;
            if (to_break && t >= target) {
                ++next_break;
                restart();
                h = std::min(h, scene_.solver.h0);  // a fresh start, as after a reset of the driver
            }
        }
        return finish({});
    }

    for (long i = 1; i <= rows; ++i) {
        if (const char* why = stop ? stop() : nullptr) return finish(why);
        const double ti = clock(i);
        for (; next_break != breaks.end() && *next_break <= ti * (1.0 + same_instant); ++next_break) {
            const double tb = std::abs(*next_break - ti) <= same_instant * ti ? ti : *next_break;
            if (std::string failure = advance(tb); !failure.empty()) return finish(failure);
            restart();
        }
        if (t < ti)
            if (std::string failure = advance(ti); !failure.empty()) return finish(failure);
        if (std::string failure = over_budget(); !failure.empty()) return finish(failure);
        if (std::string failure = emit(ti, y.data()); !failure.empty()) return finish(failure);
    }
    return finish({});
}

RunSummary simulate(const Scene& scene, const RowSink& sink) { return Simulation(scene).run(sink); }

}  // namespace hubbeam
