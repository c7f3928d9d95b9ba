// The steppers' names, apart from the steppers: what the scene reader checks solver.stepper against, without the
// stepper libraries' headers (integrate.cpp defines them beside the GSL step types they name).
#pragma once

#include <string>
#include <vector>

namespace hubbeam {

/// The stepper names the integrator accepts, in table order: GSL odeiv2's step types ("msadams", "rk8pd", ...),
/// then hubbeam's Gauss-Legendre stepper (gauss_stepper) and SUNDIALS CVODE's BDF (cvode_stepper).
std::vector<std::string> stepper_names();
/// The two-stage Gauss-Legendre method (order 4, A-stable, no numerical damping) with the Jacobian and the factored
/// Newton matrix reused across steps and an embedded error estimate.
inline constexpr const char* gauss_stepper = "gauss4";
/// SUNDIALS CVODE's variable-order BDF with Newton iterations that reuse their factored matrix across steps.
inline constexpr const char* cvode_stepper = "cvode";
/// Whether name is one of stepper_names().
bool is_stepper(const std::string& name);

}  // namespace hubbeam
