// Hub motion of a scene: the paper's spin-up (eq. 58) and torque pulse (eq. 59), a hub held at a fixed angle, and
// a prescribed rotation or a hub torque read from a table, a step of the angle; and the feedback law that makes a
// motion the reference of a torque-driven hub (Control).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

/// A drive value against time from a table's rows, immutable once built: the copies of a Motion share one, and
/// a sweep's threads evaluate it at once (it keeps no lookup state between calls).
class DriveTable {
public:
    /// cubic_spline: GSL's natural cubic spline (C2: a prescribed angle whose rate and acceleration the equations
    /// need); linear: straight between rows (a torque as a test rig records it, every row a breakpoint).
    enum class Interpolation { cubic_spline, linear };

    /// The value and its first three time derivatives at one time.
    struct Values {
        double value = 0.0, d1 = 0.0, d2 = 0.0, d3 = 0.0;
    };

    /// Throws std::invalid_argument for times not strictly increasing, a value not finite, or too few rows
    /// (min_rows); the scene reader checks all of these first, with the file's line.
    DriveTable(std::vector<double> t, std::vector<double> v, Interpolation interpolation);
    ~DriveTable();
    DriveTable(const DriveTable&) = delete;
    DriveTable& operator=(const DriveTable&) = delete;

    /// The fewest rows an interpolation takes: 3 for the spline (GSL's cspline), 2 for linear.
    static std::size_t min_rows(Interpolation interpolation);

    /// The value and its derivatives at t; outside the rows, the end piece continued (only a finite-difference
    /// Jacobian's offsets reach there: a scene's run stays inside the rows, validate() checks).
    Values at(double t) const;
    /// The integral of the interpolant from 0 to t.
    double integral(double t) const;

    Interpolation interpolation() const { return interpolation_; }
    const std::vector<double>& times() const { return t_; }
    double first_time() const { return t_.front(); }
    double last_time() const { return t_.back(); }

private:
    struct Gsl;
    std::vector<double> t_, v_;
    std::vector<double> d3_;  // the spline's third derivative on each piece (constant there)
    Interpolation interpolation_;
    std::unique_ptr<Gsl> gsl_;
    /// The integral from the first row to t inside the rows.
    double integral_from_start(double t) const;
};

/// The largest hub angle in size (rad) a scene may give and a run may reach. Double precision resolves an angle of
/// this size to 1.2e-10 rad; far beyond it a slow hub's steps vanish in round-off (at 1e17 rad theta does not move
/// at a rate of 2 rad/s while gravity, through sin and cos of it, acts on a frozen angle).
inline constexpr double max_hub_angle = 1e6;

struct Motion {
    /// spin_up, held and table prescribe the rotation; torque and torque_table drive a free hub; step (theta = angle
    /// from t = 0 on) is a reference only, of a controlled hub (docs/model.md section 11).
    enum class Kind { spin_up, torque, held, table, torque_table, step } kind = Kind::spin_up;
    double omega0 = 4.0;        // spin-up: final rate Omega0 (rad/s)
    double spin_time = 15.0;    // spin-up: T_s (s)
    double tau0 = 1.0;          // torque: amplitude tau0 (N m)
    double torque_time = 10.0;  // torque: T_t (s), one full sine period
    double theta0 = 0.0;        // spin-up, table: added to the prescribed angle; torque, torque-table: theta at t = 0
    double angle = 0.0;         // held: the fixed angle; step: the reference's angle (rad)
    std::shared_ptr<const DriveTable> table = nullptr;  // table: theta(t) (rad); torque-table: tau(t) (N m)
    std::string table_file = {};                        // the table's file, for messages and the summary

    /// Prescribed rotation or hub torque: which variant form the motion alone needs; a controlled scene's drive is
    /// torque whatever its motion (Scene::key()).
    Drive drive() const { return kind == Kind::torque || kind == Kind::torque_table ? Drive::torque : Drive::prescribed; }
    /// u = (tau, theta_dot, theta_ddot, theta) at t; theta only for a prescribed rotation.
    HubInput at(double t) const;
    /// du/dt = (dtau/dt, theta_ddot, dtheta_ddot/dt) at t, for the time derivative of the implicit steppers'
    /// Jacobian (dfdt); differentiated by hand from docs/model.md section 6, eqs. 58 and 59, for the paper's drives.
    HubInput rate(double t) const;
    /// Prescribed theta(t), theta0 included (0 for the torque drives, where theta is a coordinate).
    double theta(double t) const;
    /// theta at t = 0: where a run starts (the torque drives' initial coordinate).
    double initial_theta() const;
    /// int_0^t tau dt (torque drives only; 0 for the prescribed ones).
    double torque_impulse(double t) const;
    /// Times where the drive is not smooth: the integrator stops and restarts there.
    std::vector<double> breakpoints() const;
};

/// What a hub's torque law sees of the state: the hub's angle and rate, the tip deflection u_y(L) and its rate.
struct HubState {
    double theta = 0.0, theta_dot = 0.0, tip_uy = 0.0, tip_uy_dot = 0.0;
};

/// A torque law given as code, tau(t, state) in N m (the Python module's hubbeam.run(..., torque=f)). A non-finite
/// result stops the run as the equations failing there.
using TorqueLaw = std::function<double(double t, const HubState& state)>;

/// Feedback control of a free hub (scene table [control], docs/model.md section 11): the scene's motion is the
/// reference and the hub is torque-driven,
///     tau = -kp (theta - theta_ref) - kd (theta_dot - theta_dot_ref) - ki int (theta - theta_ref) dt - k_tip u_y(L),
/// clipped to [-tau_max, tau_max]. With law set, law(t, state) is the torque instead and the gains are unused.
struct Control {
    double kp = 0.0;     // N m/rad
    double kd = 0.0;     // N m s/rad
    double ki = 0.0;     // N m/(rad s); nonzero adds the integral of the angle error as a state
    double tau_max = std::numeric_limits<double>::infinity();  // N m, symmetric saturation
    double k_tip = 0.0;  // N m/m, feedback of u_y(L)
    TorqueLaw law;

    /// The PD(I) law's torque before saturation, from the state, the angle error's integral and the reference.
    double unclipped(const HubState& s, double integral, const HubInput& reference) const
    {
        return -kp * (s.theta - reference.theta) - kd * (s.theta_dot - reference.theta_dot) - ki * integral -
               k_tip * s.tip_uy;
    }
};

}  // namespace hubbeam
