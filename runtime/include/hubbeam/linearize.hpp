// Linearization about a steady spin, or under gravity about the static equilibrium of the held hub (docs/model.md
// section 10): the steady state, the state-space model a control engineer takes away (hubbeam linearize) and the
// natural modes with their damping (hubbeam modes).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>
#include <hubbeam/motion.hpp>

namespace hubbeam {

/// The frame a rotor's modes and linear model are given in (docs/model.md section 13.2): fixed, in multi-blade
/// coordinates where they apply (multiblade_refusal empty; elsewhere the blades' own frames), or rotating, each
/// blade's coordinates in its own frame.
enum class Frame { fixed, rotating };
/// Words "fixed", "rotating" (option --frame, hubbeam.modes' frame).
std::string to_string(Frame frame);
bool parse(std::string_view word, Frame& frame);

/// The steady spin at omega (rad/s): the beam straight, the axial coordinates at their centrifugal stretch
/// (Newton on Q_A = 0), the hub turning at omega (prescribed: the drive's rate; free hub: theta_dot, no torque).
/// Under gravity, the static equilibrium of the hub held at an angle instead (held_equilibrium).
struct SteadySpin {
    double omega = 0.0;
    HubInput u;
    std::vector<double> q, qd;
    /// The hub held at u.theta (a gravity variant): its angle is not a degree of freedom of the modes; a free hub's
    /// u.tau is the torque that holds it there.
    bool held = false;
};
/// Why a spin at omega is no steady state of variant key at the physical parameters p (Parameters::packed), or empty
/// when it is one: weight in the plane of rotation turns with the beam, so under it only omega = 0 (the hub held) is
/// steady, and the motion at a spin rate is periodic; weight along the spin axis does not turn, and a blade holds its
/// sag at any spin. The one rule steady_spin and the command line's early check of --omega apply.
std::string unsteady_spin(const VariantKey& key, const std::vector<double>& p, double omega);
/// The steady spin at omega; a gravity variant has one at omega = 0 only (held_equilibrium at theta) and throws
/// std::invalid_argument for a spin rate: its motion is then periodic, not steady. theta is read by gravity alone.
SteadySpin steady_spin(const Model& model, double omega, double theta = 0.0);
/// The static equilibrium of a gravity variant with the hub held at theta (rad; 0 is a horizontal beam, at rest):
/// Newton on the elastic rows Q_e(q_e) = 0 with theta fixed, and for a free hub the torque that holds it
/// (u.tau = -Q_theta there). Throws std::runtime_error if Newton does not converge (the beam buckles under its
/// weight). With theta_dot, the hub turning at that rate through theta for an instant (a run's start, initial.state
/// "static"): its centrifugal loads too, an equilibrium of that instant only, the weight in the plane turning on.
SteadySpin held_equilibrium(const Model& model, double theta, double theta_dot = 0.0);

/// x' = A x + B v, y = C x + D v about a steady spin (or a held equilibrium under gravity), in deviations from
/// it. States: theta, the axial and transverse coordinates, then their rates (theta_dot first). Input v: the hub
/// torque tau (free hub; about a held equilibrium, beyond the holding torque) or the hub's angular acceleration
/// theta_ddot (prescribed rotation, where theta and theta_dot are states driven by it; under gravity theta enters
/// the forces through Model::forces_theta). Outputs: tip_uy and theta, then tip_uz and tip_phi where the variant has
/// a flapwise and a twist field.
struct StateSpace {
    Eigen::MatrixXd A, B, C, D;
    std::vector<std::string> states, inputs, outputs;
};
StateSpace state_space(const Model& model, const SteadySpin& steady);

/// One natural mode of the linearized equations: eigenvalue lambda = growth +- i rad_s (rad_s the damped
/// frequency); undamped_rad_s = |lambda| and damping_ratio = -growth / |lambda| (zeta; a real eigenvalue of an
/// overdamped mode has rad_s 0 and zeta 1, each of its two eigenvalues a row); kind "bending" or "axial" (a blade:
/// "edge", "flap", "twist") by where its kinetic energy lies, or "overdamped" for a real decaying eigenvalue, which
/// does not oscillate (a divergent mode, real and growing, keeps the kind of its field).
struct NaturalMode {
    double rad_s = 0.0, growth = 0.0;
    std::string kind;
    double undamped_rad_s = 0.0, damping_ratio = 0.0;
    /// The mode's shape, to follow it from one spin rate to the next: its coordinates' rates weighted by the mass
    /// matrix (U v with M = U^T U over the same coordinates), of unit length, so that mac() is mass-weighted.
    Eigen::VectorXcd shape;
};

/// The modal assurance criterion of two modes' shapes, |a^H b|^2 (both of unit length): 1 for the same shape, 0 for
/// shapes orthogonal in the mass. Throws std::invalid_argument for shapes of different sizes.
double mac(const NaturalMode& a, const NaturalMode& b);

/// The modes of the flexible coordinates about the steady spin, by increasing undamped frequency: the eigenvalues
/// of the state matrix with the hub's own states left out (prescribed or held: theta and theta_dot are the drive's;
/// free hub: theta is cyclic, and the zero eigenvalue of the conserved angular momentum is dropped). A divergent
/// mode (real positive eigenvalue, e.g. order zero above its critical spin) has rad_s 0 and growth > 0, first;
/// without damping a real part within 1e-6 of |lambda| is round-off and reported as growth 0. With damping the
/// first-order (state-space) eigenproblem is the damped one: growth < 0 is the decay rate.
/// With quasi-static axial coordinates (docs/model.md section 9) A leaves the state, as in a run: its rows hold at
/// every instant with A_dot = 0, so there are no axial modes, and the other rows drop A's rates.
std::vector<NaturalMode> natural_modes(const Model& model, const SteadySpin& steady, Axial axial = Axial::dynamic);

/// The closed loop of a controlled hub (scene table [control]) from the open loop of a free hub's state_space
/// about the same state: tau = -kp theta - kd theta_dot - ki z - k_tip tip_uy + v in deviations (the reference is
/// the steady state's own), with z' = theta the angle error's integral as one more state when ki != 0 (named
/// controller_integral). The input v is a torque added to the controller's (a disturbance); the outputs are the
/// open loop's. The law's saturation is left out: it is inactive for small deviations.
StateSpace closed_loop(const StateSpace& open, const Control& control);

/// The modes of a controlled hub about a steady spin: the eigenvalues of closed_loop's A, each pair a row with
/// its damped frequency, growth, |lambda| and damping ratio (a real eigenvalue a row of its own, rad_s 0), kind
/// "hub", "axial" or "bending" by where the mode's kinetic energy lies ("overdamped" for a real decaying
/// eigenvalue); by increasing |lambda|. The hub's angle is a
/// state here: the controller's stiffness turns the free hub's rigid rotation into a mode.
std::vector<NaturalMode> closed_loop_modes(const Model& model, const SteadySpin& steady, const Control& control);

/// The assignment of rows to columns that makes the sum of score(row, column) largest (Kuhn and Munkres' Hungarian
/// method, O(n^3), on the square matrix padded with zeros): for each row, its column, or -1 where the padding took
/// it (more rows than columns). campbell pairs the modes of neighbouring rates with it.
std::vector<int> best_assignment(const Eigen::MatrixXd& score);

/// One row of a Campbell table: a natural mode about the steady spin omega, numbered 1, 2, ... by frequency among
/// all the modes at that rate, and the tracked mode it belongs to: its label ("bending 2", "axial 1", "hub 1"; the
/// kind and order of its shape where the line begins) and the MAC between its shape here and at the line's previous
/// rate (NaN where the line begins).
struct SpinMode {
    double omega = 0.0;
    int number = 0;
    NaturalMode mode;
    std::string label;
    double mac = 0.0;
};
/// natural_modes about the steady spin at each rate of omegas, rate by rate (hubbeam modes, hubbeam.modes); theta
/// is the held angle of a gravity variant (steady_spin); with a control, the closed loop's modes (closed_loop_modes);
/// in the fixed frame, a rotor's multiblade_modes where they apply (no control). Rows in the order of omegas, each
/// rate's by frequency. The modes are tracked from rate to rate in increasing omega: the modes of neighbouring rates
/// are paired so that the sum of their MACs is largest (the assignment problem), and each pair continues a line. A mode left unpaired (the count changes where a mode turns overdamped
/// or divergent) begins a line of its own. A line follows its shape: through a crossing, and through a veering that
/// the rates step over, it keeps its label while the frequency order changes; through a veering the rates resolve,
/// it follows its continuous branch, and its kind shows the exchange of shapes. check, if given, is called before
/// each rate's modes are computed and may throw to stop (the Python module's Ctrl-C).
std::vector<SpinMode> campbell(const Model& model, const std::vector<double>& omegas, Axial axial = Axial::dynamic,
                               double theta = 0.0, const Control* control = nullptr,
                               const std::function<void()>& check = {}, Frame frame = Frame::fixed);

/// Where a tracked mode meets an excitation line omega_mode = n Omega (a critical speed): the spin rate and the
/// mode's frequency there (rad/s, = n omega).
struct CriticalSpeed {
    std::string label;
    int harmonic = 0;
    double omega = 0.0, rad_s = 0.0;
};
/// The critical speeds of campbell's rows for each harmonic n of harmonics (none when it is empty): each place where
/// a line's damped frequency minus n omega changes sign between two of its neighbouring rates, the line following
/// one mode there (the MAC of its modes at the two rates above 1/2) that is not nearly critically damped at both
/// (damping ratio above 0.999: so nearly defective a pair has a damped frequency fixed only to about 1e-5 of
/// |lambda|), refined by regula falsi (Illinois) to 1e-10 of omega. At each rate tried the line's mode is the one whose eigenvalue lies nearest the eigenvalue interpolated
/// between the bracket's ends, found by inverse iteration with one r x r factorization (r coordinates), when its MAC
/// with the line's shape is above 1/2; else (a cluster of nearly equal eigenvalues) and under control, the mode of
/// largest MAC among all the modes there. A mode of frequency 0 (overdamped, divergent) meets no line, at rest
/// either: every critical speed is where a mode that oscillates has the frequency n omega > 0. The same model and
/// arguments as campbell's, check too. By rate, then harmonic.
std::vector<CriticalSpeed> critical_speeds(const Model& model, const std::vector<SpinMode>& rows,
                                           const std::vector<int>& harmonics, Axial axial = Axial::dynamic,
                                           double theta = 0.0, const Control* control = nullptr,
                                           const std::function<void()>& check = {}, Frame frame = Frame::fixed);

/// The periodic steady motion of a spin at omega > 0 (docs/model.md section 10.1): the hub turns at the constant rate
/// omega, theta = omega t (a prescribed drive's rate; a free hub is held at that rate by whatever torque it takes,
/// its angle no degree of freedom), and the elastic coordinates repeat with the period T = 2 pi / omega. Under weight
/// in the plane of rotation (unsteady_spin) it is the response to the once-per-revolution weight; otherwise it is the
/// steady state, constant. Found by harmonic balance: the equations of motion at the 2H + 1 instants
/// t_j = j T / (2H + 1), the rates and accelerations those of the samples' trigonometric interpolant, solved harmonic
/// by harmonic with the period's average coefficients (Newton with all the samples' where that converges slowly),
/// started from the steady state without the weight, with H doubled (from 6, up to 96) until the highest harmonics are
/// round-off of the motion.
struct PeriodicOrbit {
    double omega = 0.0, period = 0.0;
    /// The coordinates that move, indices into q: the elastic ones.
    std::vector<int> coordinates;
    /// The Fourier coefficients of q over coordinates: column k (k = 0 .. H) is c_k in
    /// q(t) = c_0 + 2 Re sum_k c_k exp(i k omega t) (c_0 real).
    Eigen::MatrixXcd coefficients;
    /// The model's size and whether its hub angle is q[0] (torque drive: q[0] = omega t, qd[0] = omega).
    int nq = 0;
    bool torque = false;
    /// The harmonic balance's steps at the last H.
    int newton_steps = 0;
    /// q and qd (nq entries each) and the drive at time t (theta = omega t), and qdd (nq) where given.
    void state(double t, std::vector<double>& q, std::vector<double>& qd, HubInput& u,
               std::vector<double>* qdd = nullptr) const;
};
/// The periodic steady motion at omega. Throws std::invalid_argument for omega <= 0, std::runtime_error where Newton
/// does not converge or 96 harmonics do not resolve the motion.
PeriodicOrbit periodic_orbit(const Model& model, double omega);

/// One Floquet mode of the linearization about a periodic motion: its multiplier mu (an eigenvalue of the monodromy
/// matrix Phi(T)), its exponent ln(mu) / T on the principal branch (imaginary part in (-omega/2, omega/2]), and the
/// harmonic k that dominates its periodic eigenvector p(t) = exp(-exponent t) Phi(t) v: the largest summed |DFT|^2
/// over the displacement coordinates (unweighted) of p sampled at the integration's steps over one period. mode is
/// the mode as natural_modes gives one: frequency rad_s = Im(exponent) + k omega, growth = Re(exponent), its kind
/// and shape those of the rates' k-th harmonic.
struct FloquetMode {
    std::complex<double> multiplier, exponent;
    int harmonic = 0;
    NaturalMode mode;
};
/// floquet's result: the orbit, the monodromy matrix over the state (q, qd) of orbit.coordinates, all its eigenvalues,
/// the modes resolved, the integration's steps over the period, and how many of the eigenvalues no mode stands for
/// (a mode that oscillates stands for two, its own and its conjugate's).
struct FloquetAnalysis {
    PeriodicOrbit orbit;
    Eigen::MatrixXd monodromy;
    Eigen::VectorXcd multipliers;
    std::vector<FloquetMode> modes;
    int steps = 0;
    int left_out = 0;
};
/// The Floquet analysis of the linearization about the periodic motion at omega > 0 (docs/model.md section 10.1):
/// the variational equations x' = J(t) x of the first-order system over the orbit's coordinates and their rates (J
/// the model's exact Jacobian where it has one) integrated from the identity over one period by the fourth-order
/// commutator-free Magnus integrator, exp(h (a2 J1 + a1 J2)) exp(h (a1 J1 + a2 J2)) per step (J1, J2 at the step's
/// Gauss points; exact for a constant J, so that stiff, strongly damped modes decay as they should), in the average
/// system's undamped modal coordinates scaled by their frequencies (where J is well scaled); on N and 2N steps, N
/// doubled until the exponents of every multiplier of size 1e-6 or more agree between the two to 1e-9 of |lambda| (or
/// of omega), and at least the harmonics of the fastest mode one revolution resolves plus 8, so that the 2N samples
/// read its harmonic unaliased (within a budget of steps: beyond it, a mode whose shape is most like an average mode
/// faster than the samples resolve is left out). Reported: the modes whose multipliers are resolved (|mu| >= 1e-10
/// and |mu| T |lambda| >= 1e-6: the round-off of Phi(T) moves the exponent by 1e-9 of |lambda| at most; the others
/// decay too fast in one revolution) and whose exponents agree between N and 2N, each conjugate pair once (frequency
/// > 0; a real multiplier's mode, frequency |Im(exponent) + k omega|, once), sorted as natural_modes sorts. With
/// gravity along the spin axis or none the coefficients are constant, Phi(T) = exp(A T), and the modes are
/// natural_modes' with the same frequencies. Throws std::invalid_argument for omega <= 0 or quasi-static axial
/// coordinates, std::runtime_error where the orbit is not found or the exponents do not converge within the budget.
FloquetAnalysis floquet(const Model& model, double omega, Axial axial = Axial::dynamic);
/// floquet's modes alone: what campbell and hubbeam modes give at a spin rate that has no steady state
/// (unsteady_spin).
std::vector<NaturalMode> floquet_modes(const Model& model, double omega, Axial axial = Axial::dynamic);

/// Why the linearization about a steady spin of a rotor of these blades (each blade's Parameters::packed, in order)
/// has no constant multi-blade form, or empty when it has: N >= 3 identical blades (the same parameters, pitch
/// offset and tip mass included), without weight in the plane of rotation (it turns with each blade).
std::string multiblade_refusal(const VariantKey& key, const std::vector<std::vector<double>>& blades);
/// The same rule for a model: a rotor's blades' parameters, a single blade's own.
std::string multiblade_refusal(const Model& model);

/// The multi-blade (Coleman) state-space model about the steady spin of a rotor whose multiblade_refusal is empty
/// (docs/model.md section 13.2; Bir 2008): the rotating-frame state_space at the rotor's azimuth psi (theta, or
/// the prescribed angle, = azimuth; steady's own azimuth is replaced) transformed to x = T(psi) z, each blade
/// coordinate q_b = q_coll + sum_n (q_cosn cos n psi_b + q_sinn sin n psi_b) + q_diff (-1)^(b-1):
/// A_z = T^-1 (A T - dT/dt), B_z = T^-1 B, constant in psi. The hub's coordinates (theta, x_h, y_h) stay as they
/// are. States: theta, x_h, y_h, then each blade field's coordinates per component, named "B1_coll", "B1_cos1",
/// "B1_sin1", ..., "B1_diff" (N even), then their rates (_dot). Outputs: the components of each tip value
/// (tip_uy_coll, tip_uy_cos1, ...), theta after tip_uy's, then tip_uz's and tip_phi's where the blades have them.
/// Throws std::invalid_argument when multiblade_refusal is not empty.
StateSpace multiblade_state_space(const Model& model, const SteadySpin& steady, double azimuth = 0.0);

/// The modes of multiblade_state_space's system (hubbeam modes' fixed frame), by natural_modes' rules and order, one
/// eigenproblem per harmonic (collective with theta; cyclic n = 1 with x_h, y_h; each cyclic n >= 2; differential:
/// the transformed system couples no two of them). Kinds: "collective K", "differential K", "BW K" and "FW K" for
/// the cyclic n = 1 pair ("BW2 K", "FW2 K" for n = 2, ...), K the blade field's kind (edge, flap, bending, axial,
/// twist), FW where the mode whirls with the spin faster than n Omega (a rotating-frame frequency omega_r appears at
/// omega_r + n Omega), else BW (|omega_r - n Omega|, also when n Omega > omega_r); a mode whose energy is mostly the
/// hub's: "FW hub" or "BW hub" where its whirl is nearly circular (either sense's amplitude more than three times
/// the other's), else "hub x" or "hub y". Throws std::invalid_argument when multiblade_refusal is not empty.
std::vector<NaturalMode> multiblade_modes(const Model& model, const SteadySpin& steady, Axial axial = Axial::dynamic);

/// The CSV header of the modes table (hubbeam modes writes it, hubbeam plot campbell reads it by column name).
const char* modes_header();

/// sqrt(EI / (rho S L^4)) (rad/s): frequencies divided by it are the classical dimensionless ones (the first
/// cantilever bending frequency is 1.8751^2 = 3.5160 of it).
double frequency_unit(const Parameters& p);

}  // namespace hubbeam
