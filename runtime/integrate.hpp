// Integrator adapter: the equations of a Model as a first-order system y = (q, qd) for GSL odeiv2, with the
// linear algebra chosen from the model's structure (mass_solver.hpp).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gsl/gsl_odeiv2.h>

#include "model.hpp"
#include "motion.hpp"

namespace hubbeam {

/// The GSL odeiv2 step type names the integrator accepts ("msadams", "rk8pd", ...), in table order.
std::vector<std::string> stepper_names();
/// The GSL step type of a name from stepper_names(), or nullptr.
const gsl_odeiv2_step_type* step_type(const std::string& name);

/// dy/dt = (qd, M(q)^-1 Q(t, q, qd)) for one model and hub motion; counts its evaluations.
class FirstOrderSystem {
public:
    FirstOrderSystem(const Model& model, const Motion& motion);
    ~FirstOrderSystem();
    FirstOrderSystem(const FirstOrderSystem&) = delete;
    FirstOrderSystem& operator=(const FirstOrderSystem&) = delete;

    int size() const { return 2 * n_; }
    /// GSL status: GSL_SUCCESS, or GSL_EBADFUNC when M is not positive definite or the result is not finite.
    int rhs(double t, const double* y, double* dydt);
    /// Jacobian for the implicit steppers (row-major, as GSL wants): dfdy (2nq x 2nq) and dfdt (2nq) from the
    /// model's exact derivatives when it has them, else finite_difference_jacobian.
    int jacobian(double t, const double* y, double* dfdy, double* dfdt);
    /// Central differences of rhs: the fallback for models without derivatives, and the tests' oracle.
    int finite_difference_jacobian(double t, const double* y, double* dfdy, double* dfdt);
    /// Evaluations of rhs, including those a finite-difference Jacobian makes.
    long evaluations() const { return evaluations_; }
    /// Jacobians formed (either way).
    long jacobian_evaluations() const { return jacobian_evaluations_; }
    gsl_odeiv2_system* gsl() { return &sys_; }
    /// How accelerations are computed, for the summary: folded M^-1, or which mass solver.
    std::string linear_algebra() const;

private:
    struct Work;
    const Model& model_;
    const Motion& motion_;
    int n_;
    int exact_jacobian(double t, const double* y, double* dfdy, double* dfdt);
    /// motion_.at(t), remembered for the last t.
    const HubInput& drive_at(double t);

    double drive_t_ = std::numeric_limits<double>::quiet_NaN();
    HubInput drive_;
    long evaluations_ = 0;
    long jacobian_evaluations_ = 0;
    std::unique_ptr<Work> work_;
    gsl_odeiv2_system sys_;
};

}  // namespace hubbeam
