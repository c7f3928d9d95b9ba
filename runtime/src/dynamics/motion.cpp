// Spin-up and torque profiles of docs/model.md section 6.
#include "motion.hpp"

#include <cmath>
#include <numbers>
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

HubInput Motion::at(double t) const
{
    HubInput u;
    if (kind == Kind::step) {
        u.theta = angle;
    } else if (kind == Kind::spin_up) {
        if (t <= spin_time) {
            const auto [s, c] = sin_cos(two_pi * t / spin_time);
            u.theta_dot = omega0 * (t / spin_time - s / two_pi);
            u.theta_ddot = omega0 / spin_time * (1.0 - c);
            u.theta = omega0 * (t * t / (2.0 * spin_time) + spin_time * (c - 1.0) / (two_pi * two_pi));
        } else {
            u.theta_dot = omega0;
            u.theta = omega0 * (t - spin_time / 2.0);
        }
    } else if (t <= torque_time) {
        u.tau = tau0 * std::sin(two_pi * t / torque_time);
    }
    return u;
}

HubInput Motion::rate(double t) const
{
    // Same branches as at(t): the profile's pieces are differentiated separately (the breakpoints restart the
    // integrator, so it never differentiates across them).
    HubInput r;
    if (kind == Kind::step) return r;
    if (kind == Kind::spin_up) {
        if (t <= spin_time) {
            const double w = two_pi / spin_time;
            r.theta_dot = omega0 / spin_time * (1.0 - std::cos(w * t));  // = theta_ddot
            r.theta_ddot = omega0 / spin_time * w * std::sin(w * t);
        }
    } else if (t <= torque_time) {
        const double w = two_pi / torque_time;
        r.tau = tau0 * w * std::cos(w * t);
    }
    return r;
}

double Motion::theta(double t) const
{
    if (kind == Kind::step) return angle;
    if (kind != Kind::spin_up) return 0.0;
    if (t <= spin_time)
        return omega0 * (t * t / (2.0 * spin_time) + spin_time * (std::cos(two_pi * t / spin_time) - 1.0) / (two_pi * two_pi));
    return omega0 * (t - spin_time / 2.0);
}

double Motion::torque_impulse(double t) const
{
    if (kind != Kind::torque) return 0.0;
    const double tt = t < torque_time ? t : torque_time;
    return tau0 * torque_time / two_pi * (1.0 - std::cos(two_pi * tt / torque_time));
}

std::vector<double> Motion::breakpoints() const
{
    if (kind == Kind::step) return {};  // the step is at t = 0, where the run starts
    return {kind == Kind::spin_up ? spin_time : torque_time};
}

}  // namespace hubbeam
