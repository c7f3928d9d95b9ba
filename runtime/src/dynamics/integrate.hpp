// Integrator adapter: the equations of a Model as a first-order system y = (q, qd) for GSL odeiv2, with the
// linear algebra chosen from the model's structure (mass_solver.hpp).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <gsl/gsl_odeiv2.h>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>
#include <hubbeam/motion.hpp>

#include "dynamics/stepper_names.hpp"

namespace hubbeam {

/// The GSL step type of a name from stepper_names(), or nullptr (also for a family other than GSL's).
const gsl_odeiv2_step_type* step_type(const std::string& name);

/// The state at t in [t0, t1] from the states y0, y1 and their derivatives f0, f1 at the ends of a step, for
/// y = (positions, rates, z) of size 2k + auxiliary with f = (rates, accelerations, dz/dt): the positions by the
/// quintic Hermite interpolant of their values, rates and accelerations at both ends (error O(h^6)), the rates by
/// its derivative (O(h^5)); the auxiliary states z (integrals of the state: FirstOrderSystem::Auxiliary) by the
/// cubic Hermite interpolant of their values and rates (O(h^4)).
void interpolate_state(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                       double t, int size, double* y, int auxiliary = 0);

/// The position error of interpolate_state at the middle of a step, relative to atol + rtol |position|, largest
/// over the positions: the quintic's error is about E s^3 (1-s)^3, so its error in acceleration at s = 1/2 is
/// -24 / h^2 times its error in position there; fm = f(t_mid, interpolated state) gives the true acceleration.
/// An auxiliary state's is the step's increment z1 - z0 against Simpson's rule over its rates at the ends and the
/// middle: how far its rate is from being integrated by three values.
double interpolation_error(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1,
                           const double* y_mid, const double* f_mid, int size, double atol, double rtol,
                           int auxiliary = 0);

class RightHandSide;

/// The auxiliary states at the end of y, z' = g(t, q, qd), present only where a run needs them (the paper's scenes
/// have none): the controller's integral of the angle error (ki != 0), the dissipated energy int 2 D dt (damping:
/// 2 D = qd_e^T (alpha M_ee + beta K_e) qd_e, M_ee the elastic block of M at q = 0, K_e the undeformed beam's
/// stiffness) and the hub's work int tau theta_dot dt (a torque-driven hub with a controller or damping: with it
/// the energy balance E + dissipated - work = E(0) holds, docs/model.md section 11.4).
struct Auxiliary {
    bool integral = false, dissipated = false, work = false;
    int count() const { return int{integral} + int{dissipated} + int{work}; }
    /// Those a run of key needs, damped or not (dissipates of the model, Scene::damped), controlled by control (or
    /// nullptr), with the parameters whose damping it accounts for (nullptr: the system keeps no energy account, as
    /// for the tests of its kernels alone); with integral, the angle error's integral even at ki = 0 (where the
    /// sensitivity to ki is the integral's).
    static Auxiliary of(const VariantKey& key, bool damped, const Control* control, const Parameters* parameters,
                        bool integral = false);
};

/// dy/dt = (qd, M(q)^-1 Q(t, q, qd), z') for one model and hub motion, by the right-hand-side strategy chosen for
/// the model's structure (acceleration.hpp); counts its evaluations. With quasi-static axial coordinates y holds only
/// theta (torque) and B with their rates: A solves the axial rows of Lagrange's equations with A_dot = A_ddot = 0
/// (and the hub acceleration's axial term dropped) at every evaluation, and the remaining rows are
/// M_rr qdd_r = Q_r: the stiff axial modes are gone, the centrifugal stretch and its coupling to bending stay.
/// With a control (a torque model), the motion is the reference and the torque is the control's law of the state,
/// evaluated at every right-hand side; the auxiliary states (Auxiliary::of) follow the positions and rates. A damped
/// model's dissipated energy is a state when parameters are given (its alpha and beta: simulations pass them).
/// Throws std::invalid_argument for a control of a model whose hub is not torque-driven.
class FirstOrderSystem {
public:
    FirstOrderSystem(const Model& model, const Motion& motion, Axial axial = Axial::dynamic,
                     const Control* control = nullptr, const Parameters* parameters = nullptr, bool integral = false);
    virtual ~FirstOrderSystem();
    FirstOrderSystem(const FirstOrderSystem&) = delete;
    FirstOrderSystem& operator=(const FirstOrderSystem&) = delete;

    /// The length of y: the state's (state_size), and in a system that carries more (sensitivity.hpp) those too.
    virtual int size() const { return state_size(); }
    /// The model's states: the kept coordinates, their rates and the auxiliary states.
    int state_size() const { return 2 * static_cast<int>(kept_.size()) + aux_.count(); }
    /// The entries of y after the positions and rates (the auxiliary states, and whatever a derived system adds):
    /// they are the last entries of y.
    virtual int auxiliary_count() const { return aux_.count(); }
    /// How many blocks of state_size() entries y holds: 1, or in a system that carries the state's sensitivities
    /// 1 + their count. The system is then block lower triangular: each later block's rates depend on the state and
    /// on that block alone, linearly, through the state's Jacobian. A stepper may solve the state first, with this
    /// class's own rhs and jacobian (FirstOrderSystem::rhs, called so), then each block with the state's matrices.
    virtual int blocks() const { return 1; }
    /// The leading entries of y whose error the step-size control weighs: all of them, or in a system whose
    /// sensitivities are left out of it (solver.sensitivity_error_control = "off") the state's alone.
    virtual int controlled_size() const { return size(); }
    const Auxiliary& auxiliary() const { return aux_; }
    /// Where an auxiliary state sits in y (-1 when absent).
    int integral_index() const { return integral_; }
    int dissipated_index() const { return dissipated_; }
    int work_index() const { return work_at_; }
    /// The hub torque at (t, y) (N m): the control's (saturated) law, or the motion's tau; 0 for a prescribed
    /// rotation.
    double torque(double t, const double* y);
    /// The model's input at the state y: the drive's at t, or under a control the torque its law gives (the hub's
    /// angle and rate are then states, not inputs).
    HubInput input_at(double t, const double* y);
    /// Whether a control's law clips the torque at (t, y): where that switches, the torque's derivatives by the
    /// state jump (the simulation steps to the switch, as to the drive's breakpoints). False without a control, and
    /// for a law given as code.
    bool saturated(double t, const double* y);
    /// The model's full q and qd (nq each) of a state y at time t: y itself for dynamic axial coordinates;
    /// with quasi-static ones, A solved from the axial equations and A_dot = 0.
    void full_state(double t, const double* y, double* q, double* qd);
    /// GSL status: GSL_SUCCESS, or GSL_EBADFUNC when M is not positive definite or the result is not finite.
    virtual int rhs(double t, const double* y, double* dydt);
    /// The model's full qdd (nq) at the state y at time t, from this class's rhs: quasi-static axial coordinates'
    /// are 0, as full_state's rates; NaN everywhere when the rhs fails.
    void full_acceleration(double t, const double* y, double* qdd);
    /// Jacobian for the implicit steppers (row-major, as GSL wants): dfdy (size x size) and dfdt (size) from the
    /// model's exact derivatives when it has them (with the control's dtau/dy through dQ/dtau), else
    /// finite_difference_jacobian.
    virtual int jacobian(double t, const double* y, double* dfdy, double* dfdt);
    /// Whether mass_form_jacobian serves: exact derivatives, every coordinate integrated, a control (if any) given
    /// by its gains, not as code, and no auxiliary state that feeds back into the accelerations (the controller's
    /// integral).
    bool has_mass_form() const;
    /// Whether every auxiliary state is a quadrature of the state, z' = g(t, q, qd), that no rate of q or qd reads
    /// (the dissipated energy and the hub's work; not the controller's integral, which the torque reads): an implicit
    /// stepper may then solve for (q, qd) alone and integrate z from their stages.
    bool auxiliary_are_quadratures() const;
    /// The Jacobian's lower blocks before M^-1, each n x n row-major: M(q), K = dQ/dq - (dM/dq) qdd and C = dQ/dqd
    /// (with a control's dQ/dtau dtau/dq and dQ/dtau dtau/dqd, zero where it saturates), so that dqdd/dq = M^-1 K and
    /// dqdd/dqd = M^-1 C. Sparse where the Jacobian is dense (FEM and B-spline meshes: banded, with the hub's row and
    /// column under torque), for Newton matrices kept in that form. Counts as a Jacobian evaluation.
    int mass_form_jacobian(double t, const double* y, double* M, double* K, double* C);
    /// Whether jacobian() is exact and jacobian_product serves: the model's derivative kernels, dynamic axial
    /// coordinates, a control (if any) given by its gains, not as code.
    bool has_exact_jacobian() const;
    /// J v_j + (0, M^-1 g_j, 0) for k vectors v_j of state_size() entries, one after another in v, and k forcings
    /// g_j of nq entries in g, into out as v: the Jacobian's products from one linearization of the forces, with one
    /// solve with M per vector. Needs has_exact_jacobian(). GSL status.
    int jacobian_product(double t, const double* y, int k, const double* v, const double* g, double* out);
    /// The later blocks' rates at zero sensitivities: b in their rates J sigma + b (blocks), into dydt's later
    /// blocks, with the state's rates in its first (y's later blocks are not read). A stepper that forms J at a stage
    /// then has the blocks' linear equations whole. The default evaluates rhs with those blocks zeroed.
    virtual int blocks_forcing(double t, const double* y, double* dydt);
    /// M(q)^-1 times k columns of nq entries, in place, at the state y. Needs has_exact_jacobian(). GSL status.
    int mass_solve(double t, const double* y, int k, double* columns);
    /// Central differences of rhs: the fallback for models without derivatives, and the tests' oracle.
    int finite_difference_jacobian(double t, const double* y, double* dfdy, double* dfdt);
    /// Evaluations of rhs, including those a finite-difference Jacobian makes.
    long evaluations() const { return evaluations_; }
    /// Jacobians formed (either way).
    long jacobian_evaluations() const { return jacobian_evaluations_; }
    gsl_odeiv2_system* gsl() { return &sys_; }
    /// How accelerations are computed, for the summary: folded M^-1, or which mass solver.
    std::string linear_algebra() const;
    /// The tip deflection u_y(L) of the last state at which M was found not positive definite (NaN if none): a
    /// failed step's cause, since GSL reports only that the function failed.
    double indefinite_mass_tip() const;

protected:
    /// A derived system's y is longer: GSL's drivers are told so.
    void set_dimension(int size) { sys_.dimension = static_cast<std::size_t>(size); }
    const Control* control() const { return control_; }

private:
    struct Work;
    const Model& model_;
    const Motion& motion_;
    int n_;
    Axial axial_;
    std::vector<int> kept_;  // the model's coordinates that are states of y (all of them unless quasi-static)
    const Control* control_;
    Auxiliary aux_;
    int integral_ = -1, dissipated_ = -1, work_at_ = -1;
    bool saturated_ = false;  // the last torque() was clipped: its derivatives by the state are zero
    int exact_jacobian(const ExactJacobian& exact, double t, const double* y, double* dfdy, double* dfdt);
    /// M qdd = Q at y under u, linearized before M^-1: qdd, dQ/dq - (dM/dq) qdd, dQ/dqd and dQ/du into the Work.
    int force_linearization(const ExactJacobian& exact, const HubInput& u, const double* y);
    /// rhs() of a system with a control or auxiliary states.
    int extended_rhs(double t, const double* y, double* dydt);
    /// u_y(L) and its rate of a state y (linear in the kept coordinates: tip_row).
    HubState hub_state(const double* y) const;
    /// motion_.at(t), remembered for the last two distinct t.
    const HubInput& drive_at(double t);

    std::array<double, 2> drive_t_{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    std::array<HubInput, 2> drive_;
    int drive_older_ = 0;  // the entry drive_at replaces next
    long evaluations_ = 0;
    long jacobian_evaluations_ = 0;
    std::unique_ptr<Work> work_;
    gsl_odeiv2_system sys_;
};

}  // namespace hubbeam
