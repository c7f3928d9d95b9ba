// The paper's beam in a scene built in code, and a run of it collected into rows: shared by the tests that
// integrate end to end.
#pragma once

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <hubbeam/simulate.hpp>

namespace hubbeam::test {

/// The paper's beam (docs/model.md section 6, the Scene defaults) with a discretization and a drive, at
/// rtol 1e-10, atol 1e-12.
inline Scene paper_scene(Method method, int nx, int ny, Motion motion)
{
    Scene s;
    s.path = "test";
    s.motion = motion;
    s.variant.method = method;
    s.variant.nx = nx;
    s.variant.ny = ny;
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-12;
    return s;
}

/// Paper eq. 58 to Omega0 in T_s = 15 s, and eq. 59 with tau0 over T_t = 10 s.
inline Motion spin_up(double omega0) { return {Motion::Kind::spin_up, omega0, 15.0, 0.0, 10.0}; }
inline Motion torque(double tau0) { return {Motion::Kind::torque, 0.0, 15.0, tau0, 10.0}; }

/// The paper's beam made 10^4 times stiffer (first bending frequency near 290 rad/s), two transverse coordinates and
/// no axial ones, on a free hub controlled to a step of angle by kp and kd, to t = 20 s: against a closed loop near
/// 1 rad/s it moves as a rigid body of inertia rigid_inertia.
inline Scene stiff_step(double angle, double kp, double kd)
{
    Motion m;
    m.kind = Motion::Kind::step;
    m.angle = angle;
    Scene s = paper_scene(Method::amm, 0, 2, m);
    s.parameters.E *= 1e4;
    s.control = Control{};
    s.control->kp = kp;
    s.control->kd = kd;
    s.output.t_end = 20.0;
    s.output.dt_out = 0.05;
    return s;
}

/// J_oh + J_ob, the whole inertia about the axis of the straight beam: J_ob = int_0^L rho S (a + x)^2 dx.
inline double rigid_inertia(const Parameters& p)
{
    const double m = p.rho * p.S;
    return p.J_oh + m * (std::pow(p.a + p.L, 3) - std::pow(p.a, 3)) / 3.0;
}

/// The rows of a run, complete or not, and its summary.
struct Collected {
    std::vector<Row> rows;
    RunSummary summary;
};
inline Collected collect(const Scene& s)
{
    Collected c;
    c.summary = simulate(s, [&](const Row& r) { c.rows.push_back(r); });
    return c;
}

/// collect() of a run that must complete.
inline Collected completed_run(const Scene& s)
{
    Collected c = collect(s);
    INFO(c.summary.failure);
    REQUIRE(c.summary.completed);
    return c;
}

/// The rows of a run that must complete.
inline std::vector<Row> run(const Scene& s) { return completed_run(s).rows; }

/// The Jacobi integral's largest change from its value at t_steady on, and the largest strain energy U there
/// (the part of the integral the flexible motion exchanges, against which the drift is judged).
struct JacobiDrift {
    double drift = 0.0, vibration = 0.0;
};
inline JacobiDrift jacobi_drift(const std::vector<Row>& rows, double t_steady)
{
    JacobiDrift d;
    double j0 = 0.0;
    bool first = true;
    for (const Row& r : rows) {
        if (r.t < t_steady) continue;
        if (first) j0 = r.jacobi, first = false;
        d.drift = std::max(d.drift, std::abs(r.jacobi - j0));
        d.vibration = std::max(d.vibration, r.potential);
    }
    return d;
}

/// Every row of a run of scene, by column name (the CSV's names: a rotor's blade columns, the hub's columns).
inline std::map<std::string, std::vector<double>> run_columns(const Scene& scene)
{
    Simulation sim(scene);
    const ColumnSet set = optional_columns_of(scene);
    const std::vector<std::string> names = row_column_names(set);
    std::map<std::string, std::vector<double>> out;
    sim.run([&](const Row& r) {
        std::size_t c = 0;
        for_each_value(r, set, [&](double v) { out[names[c++]].push_back(v); });
    });
    return out;
}

}  // namespace hubbeam::test
