// Hub motion of a scene: the prescribed spin-up (paper eq. 58), the applied torque pulse (eq. 59), or a step of the
// angle; and the feedback law that makes a motion the reference of a torque-driven hub (Control).
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

struct Motion {
    /// step: theta = angle from t = 0 on, a reference only (a controlled hub's; docs/model.md section 9).
    enum class Kind { spin_up, torque, step } kind = Kind::spin_up;
    double omega0 = 4.0;        // spin-up: final rate Omega0 (rad/s)
    double spin_time = 15.0;    // spin-up: T_s (s)
    double tau0 = 1.0;          // torque: amplitude tau0 (N m)
    double torque_time = 10.0;  // torque: T_t (s), one full sine period
    double angle = 0.0;         // step: the angle (rad)

    /// Prescribed rotation (spin-up, step) or hub torque (torque): which variant form the motion alone needs; a
    /// controlled scene's drive is torque whatever its motion (Scene::key()).
    Drive drive() const { return kind == Kind::torque ? Drive::torque : Drive::prescribed; }
    /// u = (tau, theta_dot, theta_ddot) at t, and theta.
    HubInput at(double t) const;
    /// du/dt = (dtau/dt, theta_ddot, dtheta_ddot/dt) at t, for the time derivative of the implicit steppers'
    /// Jacobian (dfdt); differentiated by hand from docs/model.md section 6, eqs. 58 and 59.
    HubInput rate(double t) const;
    /// Prescribed theta(t) (spin-up, step; 0 for torque).
    double theta(double t) const;
    /// int_0^t tau dt (torque only; 0 for spin-up).
    double torque_impulse(double t) const;
    /// Times where the drive is not smooth: the integrator stops and restarts there.
    std::vector<double> breakpoints() const;
};

/// What a hub's torque law sees of the state: the hub's angle and rate, the tip deflection u_y(L) and its rate.
struct HubState {
    double theta = 0.0, theta_dot = 0.0, tip_uy = 0.0, tip_uy_dot = 0.0;
};

/// A torque law given as code, tau(t, state) in N m (the Python module's hubbeam.run(..., torque=f)). A non-finite
/// result stops the run as the equations failing there.
using TorqueLaw = std::function<double(double t, const HubState& state)>;

/// Feedback control of a free hub (scene table [control], docs/model.md section 9): the scene's motion is the
/// reference and the hub is torque-driven,
///     tau = -kp (theta - theta_ref) - kd (theta_dot - theta_dot_ref) - ki int (theta - theta_ref) dt - k_tip u_y(L),
/// clipped to [-tau_max, tau_max]. With law set, law(t, state) is the torque instead and the gains are unused.
struct Control {
    double kp = 0.0;     // N m/rad
    double kd = 0.0;     // N m s/rad
    double ki = 0.0;     // N m/(rad s); nonzero adds the integral of the angle error as a state
    double tau_max = std::numeric_limits<double>::infinity();  // N m, symmetric saturation
    double k_tip = 0.0;  // N m/m, feedback of u_y(L)
    TorqueLaw law;

    /// The PD(I) law's torque before saturation, from the state, the angle error's integral and the reference.
    double unclipped(const HubState& s, double integral, const HubInput& reference) const
    {
        return -kp * (s.theta - reference.theta) - kd * (s.theta_dot - reference.theta_dot) - ki * integral -
               k_tip * s.tip_uy;
    }
};

}  // namespace hubbeam
