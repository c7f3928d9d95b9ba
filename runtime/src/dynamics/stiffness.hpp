// The stepper for a scene that names none: the candidate of the lower predicted cost, from the stiffness of the
// equations at rest, the tolerance and the size of the system.
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

/// The lowest positive natural frequency (rad/s) of the linearized equations at rest, no spin, kept coordinates only
/// (a free hub's rigid rotation left out): the motion the tolerance must follow.
double lowest_frequency(const Model& model, Axial axial);

/// The predicted work of the automatic choice's candidates over a run of t_end s at rtol: steps from the stiffness,
/// the tolerance and each method's order, times flops per step from the number of states (auxiliary: those beside
/// q and qd, FirstOrderSystem::Auxiliary).
struct StepperCosts {
    double omega_max = 0.0, omega_1 = 0.0;   // highest_rate, lowest_frequency
    double steps_rk8pd = 0.0, steps_gauss4 = 0.0;
    bool stability_bound = false;             // rk8pd's steps set by omega_max, not accuracy
    double rk8pd = 0.0, gauss4 = 0.0;         // flops
};
StepperCosts predicted_costs(const Model& model, Axial axial, double rtol, double t_end, int auxiliary = 0);

struct StepperChoice {
    std::string stepper;  // rk8pd or gauss4
    std::string why;      // for the summary
};

/// The tightest rtol at which the automatic choice takes gauss4.
inline constexpr double gauss4_tightest_rtol = 1e-10;

/// The candidate of the lower predicted cost (predicted_costs): rk8pd, explicit, where the steps accuracy needs
/// are not much shorter than stability allows; gauss4, implicit, where stiff modes (axial coordinates, fine FEM and
/// B-spline meshes) would hold an explicit step far below what accuracy needs.
StepperChoice automatic_stepper(const Model& model, Axial axial, double rtol, double t_end, int auxiliary = 0);

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
