// The stepper for a scene that names none: judged by the stiffness of its equations, the highest natural
// frequency of the beam at rest against the step an explicit stepper needs for accuracy.
#pragma once

#include <string>

#include "integrate.hpp"
#include "model.hpp"

namespace hubbeam {

/// The highest natural frequency (rad/s) of the linearized equations at rest, no spin: sqrt of the largest
/// eigenvalue of K x = lambda M x with K = -dQ/dq at q = qd = 0, u = 0. With quasi-static axial coordinates
/// their rows and columns are left out (they are not integrated).
double highest_frequency(const Model& model, Axial axial);

/// The largest |lambda| (1/s) of the first-order equations linearized at rest, no spin: the highest frequency when
/// the beam is undamped; with damping the fast decay rates count too (stiffness-proportional damping makes the
/// stiff axial modes overdamped, their fast rate about beta omega^2). What bounds an explicit step.
double highest_rate(const Model& model, Axial axial);

/// Above this highest frequency (rad/s) the equations count as stiff: an explicit Runge-Kutta step is then
/// stability-bound at about 5 / omega_max s, shorter than the ~0.03 s that rtol 1e-8 needs for the bending
/// motion of the paper's beam (measured with hubbeam bench; docs/performance.md "Which stepper for which scene").
inline constexpr double stiff_frequency = 200.0;

struct StepperChoice {
    std::string stepper;  // rk8pd (non-stiff) or rk4imp (stiff)
    std::string why;      // for the summary
};

/// The fastest stepper at the default tolerance in the benchmark: rk8pd for non-stiff equations; for stiff ones
/// rk4imp (implicit, with the model's Jacobian) where M is constant (prescribed rotation), and rk8pd where M
/// depends on q (hub torque, order full): there each implicit step refactors M and its Jacobian needs dM/dq, and
/// rk8pd's stability-bound steps come out cheaper (cases/: 0.10 against 0.15 s prescribed, 0.38 against 0.15 s
/// under torque).
StepperChoice automatic_stepper(const Model& model, Axial axial);

/// The lowest hub rate (rad/s, up to 1000) at which the equations linearized about the straight beam lose
/// stability: the effective stiffness -dQ/dq at q = qd = 0, steady spin, stops being positive definite (the
/// hub angle itself, cyclic, left out). The zero-order model's is its first bending frequency (docs/model.md
/// section 7); the first and full orders stay stable: infinity.
double critical_spin(const Model& model);

/// The mean step, times the highest frequency, that an explicit stepper averages on stiff undamped equations, where
/// stability and not accuracy sets its steps (measured over the 30 s paper spin-up with axial coordinates, omega_max
/// 6862 rad/s, rtol 1e-8: rk2 1.1, rk4 2.5, rkf45 0.42, rkck 0.47, rk8pd 3.1, msadams 0.21; the first second's
/// steps are up to 6 times longer, before the stiff modes are excited). Infinite for the implicit steppers.
double stability_step_factor(const std::string& stepper);

/// cond(M) at rest in the 2-norm (from M's eigenvalues; infinite when M is not positive definite): what round-off
/// in the accelerations is amplified by. M is the model's whole mass matrix in SI units: every coordinate, the hub
/// angle's row included under torque (whose J_oh + J_ob dwarfs the beam's smallest eigenvalue).
double mass_condition(const Model& model);

}  // namespace hubbeam
