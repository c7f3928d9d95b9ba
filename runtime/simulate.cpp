// simulate(): drives GSL's odeiv2 driver from output time to output time (and through the drive's
// breakpoints), turning states into rows, and stops with a message when the solution goes bad.
#include "simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include <gsl/gsl_errno.h>

#include "fields.hpp"
#include "integrate.hpp"
#include "make_model.hpp"

namespace hubbeam {

namespace {

struct DriverDeleter {
    void operator()(gsl_odeiv2_driver* d) const { gsl_odeiv2_driver_free(d); }
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

}  // namespace

RunSummary simulate(const Scene& scene, const RowSink& sink)
{
    const auto start = std::chrono::steady_clock::now();
    VariantKey key = scene.variant;
    key.drive = scene.motion.drive();
    const std::unique_ptr<Model> model = make_model(key, scene.parameters, scene.source);
    const BeamFields fields(key, scene.parameters);
    RunSummary summary;
    summary.variant = key.name();
    summary.source = model->source();

    FirstOrderSystem system(*model, scene.motion);
    const gsl_odeiv2_step_type* type = step_type(scene.solver.stepper);
    if (type == nullptr) throw std::invalid_argument("unknown stepper '" + scene.solver.stepper + "'");
    std::unique_ptr<gsl_odeiv2_driver, DriverDeleter> driver(gsl_odeiv2_driver_alloc_y_new(
        system.gsl(), type, scene.solver.h0, scene.solver.atol, scene.solver.rtol));
    gsl_set_error_handler_off();  // failures come back as status codes and become RunSummary::failure

    const int n = model->nq();
    const bool torque = key.drive == Drive::torque;
    std::vector<double> y(static_cast<std::size_t>(2 * n), 0.0);
    const Motion& motion = scene.motion;
    const double L = scene.parameters.L;

    auto row_at = [&](double t) {
        const double* q = y.data();
        const double* qd = y.data() + n;
        const HubInput u = motion.at(t);
        const double* A = key.nx > 0 ? q + key.first_a() : nullptr;
        const BeamFields::Tip tip = fields.tip(A, q + key.first_b());
        const Energy e = model->energy(u, q, qd);
        Row r{t,       torque ? q[0] : motion.theta(t), torque ? qd[0] : u.theta_dot, tip.uy, tip.ux1, tip.ux,
              e.kinetic(), e.U, model->momentum(u, q, qd), e.T2 - e.T0 + e.U};
        summary.max_abs_tip_uy = std::max(summary.max_abs_tip_uy, std::abs(r.tip_uy));
        return r;
    };

    double t = 0.0;
    long steps = 0;
    auto finish = [&](const std::string& failure) {
        steps += static_cast<long>(driver->e->count);
        summary.steps = steps;
        summary.rhs_evals = system.evaluations();
        summary.completed = failure.empty();
        summary.failure = failure;
        summary.t_reached = t;
        summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return summary;
    };

    sink(row_at(0.0));
    const double dt = scene.output.dt_out;
    const OutputClock clock(dt);
    const long rows = static_cast<long>(std::floor(scene.output.t_end / dt * (1.0 + 1e-12)));
    std::vector<double> breaks;
    for (double b : motion.breakpoints())
        if (b > 0.0 && b < clock(rows)) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    auto next_break = breaks.begin();

    // Advances to t1; at a breakpoint the multistep history is discarded, since the drive's derivatives jump.
    auto advance = [&](double t1) -> std::string {
        const int status = gsl_odeiv2_driver_apply(driver.get(), &t, t1, y.data());
        if (status == GSL_EBADFUNC)
            return "unstable: the equations became singular or non-finite" + at_time(t) +
                   " (mass matrix not positive definite or accelerations overflowed)";
        if (status != GSL_SUCCESS)
            return std::string("integration failed") + at_time(t) + ": " + gsl_strerror(status) +
                   " (try a smaller rtol/atol or a stiff stepper such as msbdf)";
        return {};
    };
    for (long i = 1; i <= rows; ++i) {
        const double ti = clock(i);
        for (; next_break != breaks.end() && *next_break <= ti * (1.0 + 1e-12); ++next_break) {
            if (*next_break < ti * (1.0 - 1e-12))
                if (std::string failure = advance(*next_break); !failure.empty()) return finish(failure);
            if (std::abs(*next_break - ti) <= 1e-12 * ti)
                if (std::string failure = advance(ti); !failure.empty()) return finish(failure);
            steps += static_cast<long>(driver->e->count);
            gsl_odeiv2_driver_reset(driver.get());
        }
        if (t < ti)
            if (std::string failure = advance(ti); !failure.empty()) return finish(failure);
        const Row r = row_at(ti);
        sink(r);
        if (!std::isfinite(r.tip_uy) || std::abs(r.tip_uy) > L)
            return finish("unstable: tip deflection " + std::to_string(r.tip_uy) + " m exceeds the beam length" +
                          at_time(ti) + "; the small-deformation model no longer holds");
    }
    return finish({});
}

}  // namespace hubbeam
