// The stepper for a scene that names none: the candidate of the lower predicted cost, from the stiffness of the
// equations at rest, the tolerance and the size of the system.
#pragma once

#include <string>

#include <hubbeam/model.hpp>
#include "dynamics/integrate.hpp"

namespace hubbeam {

/// The highest natural frequency (rad/s) of the linearized equations at rest, no spin: sqrt of the largest
/// eigenvalue of K x = lambda M x with K = -dQ/dq at q = qd = 0, u = 0. With quasi-static axial coordinates
/// their rows and columns are left out (they are not integrated).
double highest_frequency(const Model& model, Axial axial);

/// What the automatic choice weighs, from one eigenproblem of the equations linearized at rest, no spin. It depends
/// on the model and the axial treatment only: a simulation computes it once for its choice, its pilot and its
/// checks' re-runs.
struct RatesAtRest {
    /// The largest |lambda| (1/s) of the first-order equations: the highest frequency when the beam is undamped; with
    /// damping the fast decay rates count too (stiffness-proportional damping makes the stiff axial modes overdamped,
    /// their fast rate about beta omega^2). What bounds an explicit step.
    double omega_max = 0.0;
    /// The lowest positive natural frequency (rad/s), kept coordinates only (a free hub's rigid rotation left out):
    /// the motion the tolerance must follow.
    double omega_1 = 0.0;
};
RatesAtRest rates_at_rest(const Model& model, Axial axial);

/// The predicted work of the automatic choice's candidates over a run of t_end s at rtol: steps from the stiffness,
/// the tolerance and each method's order, times flops per step from the number of states (auxiliary: those beside
/// q and qd, FirstOrderSystem::Auxiliary).
struct StepperCosts {
    double omega_max = 0.0, omega_1 = 0.0;  // RatesAtRest's
    double steps_rk8pd = 0.0, steps_gauss4 = 0.0;
    bool stability_bound = false;      // rk8pd's steps set by omega_max, not accuracy
    double rk8pd = 0.0, gauss4 = 0.0;  // flops
    double gauss4_step = 0.0;          // flops per gauss4 step
};

/// gauss4's steps over the start of the run, measured: a pilot run from rest. Under a hub torque the rule cannot
/// predict them: the drive's kinks (the torque switching on and off) excite the discretization's high modes by
/// amounts that decide whether gauss4 must resolve them, which the pilot sees.
struct Pilot {
    double t = 0.0;          // where it ended (s): its window's end, or earlier once gauss4 had lost
    long steps = 0;          // gauss4's steps to t
    long steps_to_half = 0;  // of which those that ended by t / 2: the rest, its second half's, give the rate it prices
    double rtol = 0.0;       // the tolerance it ran at
    bool failed = false;     // a step failed: gauss4 cannot run the scene at rtol
    /// Where its Newton matrices were banded (the mass form, fine meshes): the flops of one factorization and of one
    /// solve, which price its steps in place of a dense LU's; 0 where they were dense.
    double band_factor_flops = 0.0, band_solve_flops = 0.0;
};

/// gauss4's steps over a run of t_end s at the pilot's tolerance: its own steps, and the rest of the run at the rate
/// of its second half. The start is no sample of the run: the first steps grow from h0, and where damping takes the
/// modes the start excites, the steps lengthen as they decay (the controlled hub with stiffness-proportional damping
/// of docs/performance.md, FEM at Nx = 16, Ny = 64: 5,800 steps a second over the first half of its 0.75 s pilot,
/// 2,500 over the second, 1,500 over the rest of the run). The second half's rate is what the pilot has seen last;
/// where the steps lengthen further it still overestimates.
double pilot_extrapolated_steps(const Pilot& pilot, double t_end);

/// What a pilot should cover, for a scene whose costs without one are c: its window (s) and the steps beyond which
/// gauss4 may have lost to rk8pd, from where the pilot asks whether it has (pilot_lost).
struct PilotPlan {
    double t = 0.0;
    long budget = 0;
};

/// Whether the automatic choice needs a pilot for a model at rtol: under a hub torque, where gauss4 is allowed.
bool needs_pilot(const Model& model, double rtol);

/// The pilot's window, the longer of a thirtieth of the run and half the lowest mode's period (but not past
/// t_end), and its budget: the break-even steps of that window at the rule's price of a step.
PilotPlan pilot_plan(const StepperCosts& c, double t_end);

/// Whether gauss4 has lost by what pilot has seen, c being predicted_costs with it: its steps extrapolated cost more
/// than rk8pd's run, and its steps no longer thin out fast. Past its budget the pilot stops there, so that it costs
/// no more than the choice it serves, and runs on while its extrapolation still wins (at its budget a damped start's
/// steps still thin out, pilot_extrapolated_steps, and c prices a step by the pilot's own Newton matrices, a band's
/// on a fine mesh where the budget priced a dense LU). While its second half's rate is below 0.7 of its first
/// half's, a decaying start whose end the second half cannot see yet, it runs on too, up to the break-even steps of
/// its window at c's price: at the budget the damped controlled hub of docs/performance.md at Ny = 32, Nx = 0 thins
/// out to 0.55 and 0.59 (BSIM, FEM), the other pilots of its grids to 0.72 and more (the first steps' growth from
/// h0), but the undamped hub at FEM Nx = Ny = 16, 0.61, whose dense Newton matrices price its budget as the plan did.
bool pilot_lost(const Pilot& pilot, const StepperCosts& c, double t_end);

/// The predicted costs; with a pilot, gauss4's steps are pilot_extrapolated_steps (scaled to rtol, as the accuracy of
/// an order-4 method asks: rtol^(-1/5)); rates, when given, are rates_at_rest(model, axial).
StepperCosts predicted_costs(const Model& model, Axial axial, double rtol, double t_end, int auxiliary = 0,
                             const Pilot* pilot = nullptr, const RatesAtRest* rates = nullptr);

struct StepperChoice {
    std::string stepper;  // rk8pd or gauss4
    std::string why;      // for the summary
};

/// The tightest rtol at which the automatic choice takes gauss4.
inline constexpr double gauss4_tightest_rtol = 1e-10;

/// The candidate of the lower predicted cost (predicted_costs): rk8pd, explicit, where the steps accuracy needs
/// are not much shorter than stability allows; gauss4, implicit, where stiff modes (axial coordinates, fine FEM and
/// B-spline meshes) would hold an explicit step far below what accuracy needs.
StepperChoice automatic_stepper(const Model& model, Axial axial, double rtol, double t_end, int auxiliary = 0,
                                const Pilot* pilot = nullptr, const RatesAtRest* rates = nullptr);

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
