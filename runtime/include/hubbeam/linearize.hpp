// Linearization about a steady spin (docs/model.md section 10): the steady state with its axial stretch, the
// state-space model a control engineer takes away (hubbeam linearize) and the natural modes (hubbeam modes).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "integrate.hpp"
#include "model.hpp"

namespace hubbeam {

/// dQ/dq (nq x nq), dQ/dqd (nq x nq) and dQ/du (nq x 3, u indexed by DriveValue) at (u, q, qd): the model's
/// derivative kernels when it has them, else central differences of Q.
struct ForceJacobians {
    Eigen::MatrixXd q, qd, u;
};
ForceJacobians force_jacobians(const Model& model, const HubInput& u, const std::vector<double>& q,
                               const std::vector<double>& qd);
/// dQ/dq alone, the same way (without differences in the rates and the drive where there are no kernels).
Eigen::MatrixXd force_q_jacobian(const Model& model, const HubInput& u, const std::vector<double>& q,
                                 const std::vector<double>& qd);

/// The steady spin at omega (rad/s): the beam straight, the axial coordinates at their centrifugal stretch
/// (Newton on Q_A = 0), the hub turning at omega (prescribed: the drive's rate; free hub: theta_dot, no torque).
struct SteadySpin {
    double omega = 0.0;
    HubInput u;
    std::vector<double> q, qd;
};
SteadySpin steady_spin(const Model& model, double omega);

/// x' = A x + B v, y = C x + D v about a steady spin, in deviations from it. States: theta, the axial and
/// transverse coordinates, then their rates (theta_dot first). Input v: the hub torque tau (free hub) or the hub's
/// angular acceleration theta_ddot (prescribed rotation, where theta and theta_dot are states driven by it).
/// Outputs: tip_uy and theta.
struct StateSpace {
    Eigen::MatrixXd A, B, C, D;
    std::vector<std::string> states, inputs, outputs;
};
StateSpace state_space(const Model& model, const SteadySpin& steady);

/// One natural mode of the linearized equations: eigenvalue growth +- i rad_s; kind "bending" or "axial" by
/// where its kinetic energy lies.
struct NaturalMode {
    double rad_s = 0.0, growth = 0.0;
    std::string kind;
};

/// The modes of the flexible coordinates about the steady spin, by increasing frequency: the eigenvalues of the
/// state matrix with the hub's own states left out (prescribed: theta and theta_dot are the drive's; free hub:
/// theta is cyclic, and the zero eigenvalue of the conserved angular momentum is dropped). A divergent mode (real
/// positive eigenvalue, e.g. order zero above its critical spin) has rad_s 0 and growth > 0; a real part within
/// 1e-6 of |lambda| is round-off and reported as growth 0.
/// With quasi-static axial coordinates (docs/model.md section 9) A leaves the state, as in a run: its rows hold at
/// every instant with A_dot = 0, so there are no axial modes, and the other rows drop A's rates.
std::vector<NaturalMode> natural_modes(const Model& model, const SteadySpin& steady, Axial axial = Axial::dynamic);

/// One row of a Campbell table: a natural mode about the steady spin omega, numbered 1, 2, ... by frequency among
/// all the modes at that rate.
struct SpinMode {
    double omega = 0.0;
    int number = 0;
    NaturalMode mode;
};
/// natural_modes about the steady spin at each rate of omegas, rate by rate (hubbeam modes, hubbeam.modes).
std::vector<SpinMode> campbell(const Model& model, const std::vector<double>& omegas, Axial axial = Axial::dynamic);

/// The CSV header of the modes table (hubbeam modes writes it, hubbeam plot campbell reads it by column name).
const char* modes_header();

/// sqrt(EI / (rho S L^4)) (rad/s): frequencies divided by it are the classical dimensionless ones (the first
/// cantilever bending frequency is 1.8751^2 = 3.5160 of it).
double frequency_unit(const Parameters& p);

}  // namespace hubbeam
