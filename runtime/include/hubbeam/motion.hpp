// Hub motion of a scene: the prescribed spin-up (paper eq. 58) or the applied torque pulse (eq. 59).
#pragma once

#include <vector>

#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

struct Motion {
    enum class Kind { spin_up, torque } kind = Kind::spin_up;
    double omega0 = 4.0;        // spin-up: final rate Omega0 (rad/s)
    double spin_time = 15.0;    // spin-up: T_s (s)
    double tau0 = 1.0;          // torque: amplitude tau0 (N m)
    double torque_time = 10.0;  // torque: T_t (s), one full sine period

    /// Prescribed rotation (spin-up) or hub torque (torque): which variant form the scene needs.
    Drive drive() const { return kind == Kind::spin_up ? Drive::prescribed : Drive::torque; }
    /// u = (tau, theta_dot, theta_ddot) at t.
    HubInput at(double t) const;
    /// du/dt = (dtau/dt, theta_ddot, dtheta_ddot/dt) at t, for the time derivative of the implicit steppers'
    /// Jacobian (dfdt); differentiated by hand from docs/model.md section 6, eqs. 58 and 59.
    HubInput rate(double t) const;
    /// Prescribed theta(t) (spin-up only; 0 for torque).
    double theta(double t) const;
    /// int_0^t tau dt (torque only; 0 for spin-up).
    double torque_impulse(double t) const;
    /// Times where the drive is not smooth: the integrator stops and restarts there.
    std::vector<double> breakpoints() const;
};

}  // namespace hubbeam
