// Spin-up and torque profiles of docs/model.md section 6, the held hub, a step, and the tables' interpolants.
#include <hubbeam/motion.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace hubbeam {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// sin x and cos x: one glibc call where there is one (the drive is evaluated at every right-hand side).
std::pair<double, double> sin_cos(double x)
{
#if defined(__GLIBC__)
    double s, c;
    ::sincos(x, &s, &c);
    return {s, c};
#else
    return {std::sin(x), std::cos(x)};
#endif
}

}  // namespace

// ---- DriveTable ----

struct DriveTable::Gsl {
    gsl_interp* interp = nullptr;
    Gsl() = default;
    Gsl(const Gsl&) = delete;
    Gsl& operator=(const Gsl&) = delete;
    ~Gsl() { gsl_interp_free(interp); }
};

namespace {

const gsl_interp_type* gsl_type(DriveTable::Interpolation i)
{
    // Natural end conditions (zero second derivative at the first and last rows): GSL's one non-periodic C2
    // cubic. A hub that starts from rest and ends at a constant rate meets them exactly; elsewhere the
    // acceleration is pulled towards zero within a few rows of the ends (docs/scene.md says so).
    return i == DriveTable::Interpolation::cubic_spline ? gsl_interp_cspline : gsl_interp_linear;
}

}  // namespace

std::size_t DriveTable::min_rows(Interpolation interpolation)
{
    return gsl_interp_type_min_size(gsl_type(interpolation));
}

DriveTable::DriveTable(std::vector<double> t, std::vector<double> v, Interpolation interpolation)
    : t_(std::move(t)), v_(std::move(v)), interpolation_(interpolation), gsl_(std::make_unique<Gsl>())
{
    const std::size_t n = t_.size();
    if (v_.size() != n) throw std::invalid_argument("a drive table needs one value per time");
    if (n < min_rows(interpolation_))
        throw std::invalid_argument("a drive table needs at least " + std::to_string(min_rows(interpolation_)) + " rows");
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(t_[i]) || !std::isfinite(v_[i])) throw std::invalid_argument("a drive table value is not finite");
        if (i > 0 && !(t_[i] > t_[i - 1])) throw std::invalid_argument("a drive table's times must increase strictly");
    }
    // Checked above: gsl_interp_init's own refusals would go to GSL's error handler, which aborts by default.
    gsl_->interp = gsl_interp_alloc(gsl_type(interpolation_), n);
    if (gsl_->interp == nullptr) throw std::bad_alloc();
    if (gsl_interp_init(gsl_->interp, t_.data(), v_.data(), n) != GSL_SUCCESS)
        throw std::invalid_argument("GSL could not build the drive table's interpolant");
    if (interpolation_ == Interpolation::cubic_spline) {
        // The third derivative of a cubic is constant on each piece: the difference of the spline's second
        // derivatives at the piece's ends over its width (exact, no differencing error of its own).
        std::vector<double> m(n);
        for (std::size_t i = 0; i < n; ++i) gsl_interp_eval_deriv2_e(gsl_->interp, t_.data(), v_.data(), t_[i], nullptr, &m[i]);
        d3_.resize(n - 1);
        for (std::size_t i = 0; i + 1 < n; ++i) d3_[i] = (m[i + 1] - m[i]) / (t_[i + 1] - t_[i]);
    }
}

DriveTable::~DriveTable() = default;

DriveTable::Values DriveTable::at(double t) const
{
    // No gsl_interp_accel: it is lookup state, and a Motion's copies run on several threads; the binary search
    // over the rows is what it would save.
    const double tc = std::clamp(t, t_.front(), t_.back());
    Values r;
    gsl_interp_eval_e(gsl_->interp, t_.data(), v_.data(), tc, nullptr, &r.value);
    gsl_interp_eval_deriv_e(gsl_->interp, t_.data(), v_.data(), tc, nullptr, &r.d1);
    gsl_interp_eval_deriv2_e(gsl_->interp, t_.data(), v_.data(), tc, nullptr, &r.d2);
    if (interpolation_ == Interpolation::cubic_spline) {
        // The piece GSL evaluates: t_[i] <= tc < t_[i + 1], the last piece at the last row.
        const auto above = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), tc) - t_.begin());
        r.d3 = d3_[std::min(above == 0 ? 0 : above - 1, d3_.size() - 1)];
    }
    if (const double h = t - tc; h != 0.0) {  // the end piece continued: its Taylor series is exact
        r.value += h * (r.d1 + h * (r.d2 / 2.0 + h * r.d3 / 6.0));
        r.d1 += h * (r.d2 + h * r.d3 / 2.0);
        r.d2 += h * r.d3;
    }
    return r;
}

double DriveTable::integral_from_start(double t) const
{
    const double tc = std::clamp(t, t_.front(), t_.back());
    double inside = 0.0;
    if (tc > t_.front()) gsl_interp_eval_integ_e(gsl_->interp, t_.data(), v_.data(), t_.front(), tc, nullptr, &inside);
    if (const double h = t - tc; h != 0.0) {
        const Values e = at(tc);
        inside += h * (e.value + h * (e.d1 / 2.0 + h * (e.d2 / 6.0 + h * e.d3 / 24.0)));
    }
    return inside;
}

double DriveTable::integral(double t) const { return integral_from_start(t) - integral_from_start(0.0); }

// ---- Motion ----

HubInput Motion::at(double t) const
{
    HubInput u;
    switch (kind) {
    case Kind::spin_up:
        if (t <= spin_time) {
            const auto [s, c] = sin_cos(two_pi * t / spin_time);
            u.theta_dot = omega0 * (t / spin_time - s / two_pi);
            u.theta_ddot = omega0 / spin_time * (1.0 - c);
            u.theta = theta0 + omega0 * (t * t / (2.0 * spin_time) + spin_time * (c - 1.0) / (two_pi * two_pi));
        } else {
            u.theta_dot = omega0;
            u.theta = theta0 + omega0 * (t - spin_time / 2.0);
        }
        break;
    case Kind::torque:
        if (t <= torque_time) u.tau = tau0 * std::sin(two_pi * t / torque_time);
        break;
    case Kind::held:
    case Kind::step: u.theta = angle; break;
    case Kind::table: {
        const DriveTable::Values v = table->at(t);
        u.theta = theta0 + v.value;
        u.theta_dot = v.d1;
        u.theta_ddot = v.d2;
        break;
    }
    case Kind::torque_table: u.tau = table->at(t).value; break;
    }
    return u;
}

HubInput Motion::rate(double t) const
{
    // Same branches as at(t): the profile's pieces are differentiated separately (the breakpoints restart the
    // integrator, so it never differentiates across them).
    HubInput r;
    switch (kind) {
    case Kind::spin_up:
        if (t <= spin_time) {
            const double w = two_pi / spin_time;
            r.theta_dot = omega0 / spin_time * (1.0 - std::cos(w * t));  // = theta_ddot
            r.theta_ddot = omega0 / spin_time * w * std::sin(w * t);
        }
        break;
    case Kind::torque:
        if (t <= torque_time) {
            const double w = two_pi / torque_time;
            r.tau = tau0 * w * std::cos(w * t);
        }
        break;
    case Kind::held:
    case Kind::step: break;
    case Kind::table: {
        const DriveTable::Values v = table->at(t);
        r.theta_dot = v.d2;
        r.theta_ddot = v.d3;
        break;
    }
    case Kind::torque_table: r.tau = table->at(t).d1; break;
    }
    return r;
}

double Motion::theta(double t) const { return at(t).theta; }

// A step is a reference whose hub starts where it is, at theta0 (0): the step is at t = 0.
double Motion::initial_theta() const { return drive() == Drive::torque || kind == Kind::step ? theta0 : theta(0.0); }

double Motion::torque_impulse(double t) const
{
    if (kind == Kind::torque_table) return table->integral(t);
    if (kind != Kind::torque) return 0.0;
    const double tt = t < torque_time ? t : torque_time;
    return tau0 * torque_time / two_pi * (1.0 - std::cos(two_pi * tt / torque_time));
}

std::vector<double> Motion::breakpoints() const
{
    switch (kind) {
    case Kind::spin_up: return {spin_time};
    case Kind::torque: return {torque_time};
    case Kind::held: return {};
    case Kind::step: return {};  // the step is at t = 0, where the run starts
    // A C2 spline is smooth across its rows (its third derivative jumps, which no stepper of this order sees);
    // its end is not.
    case Kind::table: return {table->last_time()};
    // Linear: the rate of the torque jumps at every row.
    case Kind::torque_table: return table->times();
    }
    return {};
}

}  // namespace hubbeam
