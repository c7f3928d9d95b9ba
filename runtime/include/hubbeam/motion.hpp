// Hub motion of a scene: the paper's spin-up (eq. 58) and torque pulse (eq. 59), a hub held at a fixed angle, and
// a prescribed rotation or a hub torque read from a table.
#pragma once

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

struct Motion {
    /// spin_up, held and table prescribe the rotation; torque and torque_table drive a free hub.
    enum class Kind { spin_up, torque, held, table, torque_table } kind = Kind::spin_up;
    double omega0 = 4.0;        // spin-up: final rate Omega0 (rad/s)
    double spin_time = 15.0;    // spin-up: T_s (s)
    double tau0 = 1.0;          // torque: amplitude tau0 (N m)
    double torque_time = 10.0;  // torque: T_t (s), one full sine period
    double theta0 = 0.0;        // spin-up, table: added to the prescribed angle; torque, torque-table: theta at t = 0
    double angle = 0.0;         // held: the fixed angle (rad)
    std::shared_ptr<const DriveTable> table = nullptr;  // table: theta(t) (rad); torque-table: tau(t) (N m)
    std::string table_file = {};                        // the table's file, for messages and the summary

    /// Prescribed rotation or hub torque: which variant form the scene needs.
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

}  // namespace hubbeam
