// Integrator adapter: the equations of a Model as a first-order system y = (q, qd) for GSL odeiv2, with
// the mass matrix factored once when it is constant.
#pragma once

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
    /// Central-difference Jacobian (row-major, as GSL wants) for the implicit steppers.
    int jacobian(double t, const double* y, double* dfdy, double* dfdt);
    long evaluations() const { return evaluations_; }
    gsl_odeiv2_system* gsl() { return &sys_; }

private:
    struct Work;
    const Model& model_;
    const Motion& motion_;
    int n_;
    long evaluations_ = 0;
    std::unique_ptr<Work> work_;
    gsl_odeiv2_system sys_;
};

}  // namespace hubbeam
