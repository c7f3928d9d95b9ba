// hubbeam stress: the cases, what each must do, and the table.
#include "stress.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <hubbeam/make_model.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>
#include <ostream>
#include <sstream>

#include "dynamics/stiffness.hpp"

namespace hubbeam {

namespace {

Scene base_scene(Method method, int nx, int ny, Order order)
{
    Scene s;
    s.path = "stress";
    s.variant.method = method;
    s.variant.nx = nx;
    s.variant.ny = ny;
    s.variant.order = order;
    s.output.dt_out = 0.05;
    return s;
}

/// Runs s and fills the row's measures; the expectation decides pass.
StressRow run_case(std::string group, std::string name, const Scene& s, const std::string& expect,
                   const StopRequest& stop)
{
    StressRow row;
    row.group = std::move(group);
    row.name = std::move(name);
    row.expect = expect;
    try {
        Simulation simulation(s);
        const RunSummary summary = simulation.run(
            [&](const Row& r) { row.max_tip = std::max(row.max_tip, std::abs(r.tip_uy)); }, stop);
        row.wall = summary.wall_seconds;
        if (summary.vibration_energy > 0.0) row.drift = summary.jacobi_drift / summary.vibration_energy;
        if (!summary.completed) row.status = summary.failure;
    } catch (const std::exception& e) {
        row.status = std::string("refused: ") + e.what();
    }
    if (expect == "bounded") row.pass = row.status == "ok" && row.max_tip < s.parameters.L;
    else if (expect == "unstable") row.pass = row.status.rfind("unstable", 0) == 0;
    return row;
}

std::string number(double x, const char* format = "%.3g")
{
    if (x < 0.0) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

void print(std::ostream& out, const StressRow& r)
{
    char line[400];
    std::snprintf(line, sizeof line, "%-5s %-8s %-34s %-9s %10s %10s %8s  %s%s%s\n", r.pass ? "pass" : "FAIL",
                  r.group.c_str(), r.name.c_str(), r.expect.c_str(), number(r.max_tip).c_str(), number(r.drift).c_str(),
                  number(r.wall, "%.3f").c_str(), r.status.substr(0, 90).c_str(), r.note.empty() ? "" : "; ",
                  r.note.c_str());
    out << line << std::flush;
}

/// The table as it grows: each row printed when added; the stop request the cases ask between runs.
struct Table {
    std::ostream& out;
    const StopRequest& stop;
    std::vector<StressRow> rows;

    void add(StressRow r)
    {
        print(out, r);
        rows.push_back(std::move(r));
    }
    bool stopped() const { return stop && stop() != nullptr; }
};

/// Spin-up to Omega0: first and full stay bounded; zero must be caught as unstable (it is, above the first bending
/// frequency, 2.911 rad/s, which every Omega0 here passes). Returns false when asked to stop.
bool spin_cases(const StressOptions& o, Table& table)
{
    const std::vector<double> omegas =
        o.quick ? std::vector<double>{4.0, 10.0, 20.0} : std::vector<double>{4.0, 10.0, 20.0, 50.0};
    for (const double omega : omegas)
        for (const Method m : {Method::amm, Method::fem, Method::bim, Method::bsim})
            for (const Order order : {Order::zero, Order::first, Order::full}) {
                if (table.stopped()) return false;
                Scene s = base_scene(m, 0, 4, order);
                s.motion.omega0 = omega;
                s.output.t_end = 25.0;
                table.add(run_case("spin", to_string(m) + " " + to_string(order) + " Omega0 " + shortest(omega), s,
                                   order == Order::zero ? "unstable" : "bounded", table.stop));
            }
    return true;
}

/// DOF counts up to each method's limit: the mass matrix's condition number, and a short bounded run (assembled,
/// so that no large variant is compiled for it). Returns false when asked to stop.
bool dof_cases(const StressOptions& o, Table& table)
{
    for (const Method m : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        std::vector<int> counts = {8, 16};
        if (o.long_runs) counts.push_back(max_dof(m));
        for (const int ny : counts) {
            if (table.stopped()) return false;
            Scene s = base_scene(m, 0, ny, Order::first);
            s.source = ModelSource::assembled;
            s.output.t_end = o.long_runs ? 20.0 : 2.0;
            StressRow r = run_case("dofs", to_string(m) + " Ny " + std::to_string(ny), s, "bounded", table.stop);
            r.note = "cond(M) " + number(mass_condition(*make_model(s.key(), s.parameters, ModelSource::assembled)));
            table.add(r);
        }
    }
    return true;
}

/// Long runs: the Jacobi integral's drift per stepper at steady spin and after the torque. Returns false when asked
/// to stop.
bool long_cases(const StressOptions& o, Table& table)
{
    const double t_long = o.long_runs ? 1000.0 : 100.0;
    for (const char* stepper : {"rk8pd", "rk4imp", "msadams"})
        for (const bool torque : {false, true}) {
            if (table.stopped()) return false;
            Scene s = base_scene(Method::amm, 4, 4, Order::first);
            if (torque) {
                s.motion.kind = Motion::Kind::torque;
                s.motion.tau0 = 10.0;
            }
            s.solver.stepper = stepper;
            s.output.t_end = t_long;
            s.output.dt_out = 0.1;
            table.add(run_case(
                "long",
                std::string(torque ? "torque 10 N m, " : "spin 4 rad/s, ") + stepper + ", " + shortest(t_long) + " s",
                s, "bounded", table.stop));
        }
    return true;
}

/// A beam 100 times more flexible and one 100 times stiffer (E scaled), spin-up to 4 rad/s: first against full.
/// Measured, nothing required: the flexible beam spins 14 times above its first bending frequency. Returns false
/// when asked to stop.
bool beam_cases(Table& table)
{
    for (const double scale : {0.01, 100.0}) {
        StressRow first, full;
        for (const Order order : {Order::first, Order::full}) {
            if (table.stopped()) return false;
            Scene s = base_scene(Method::amm, 0, 4, order);
            s.parameters.E *= scale;
            s.output.t_end = 25.0;
            StressRow r = run_case("beam", std::string(scale < 1 ? "E/100 " : "E*100 ") + to_string(order), s, "report",
                                   table.stop);
            (order == Order::first ? first : full) = r;
        }
        if (first.status == "ok" && full.status == "ok")
            first.note = "max|tip| first / full = " + number(first.max_tip / full.max_tip, "%.4f");
        table.add(first);
        table.add(full);
    }
    return true;
}

/// The table as a CSV at path; throws on a write error.
void write_csv(const std::string& path, const std::vector<StressRow>& rows)
{
    CsvWriter csv(path, "pass,group,case,expect,max_tip,drift,wall,status,note");
    for (const StressRow& r : rows)
        csv.write_line(std::string(r.pass ? "pass" : "FAIL") + "," + r.group + "," + csv_field(r.name) + "," +
                       r.expect + "," + number(r.max_tip, "%.6g") + "," + number(r.drift, "%.3g") + "," +
                       number(r.wall, "%.4f") + "," + csv_field(r.status) + "," + csv_field(r.note));
    csv.finish();
    if (!csv.ok()) throw std::runtime_error(csv.error());
}

}  // namespace

std::vector<StressRow> run_stress(const StressOptions& o, std::ostream& out, const StopRequest& stop)
{
    out << "pass  group    case                               expect      max|tip| J drift/U   wall s  status\n";
    Table table{out, stop, {}};
    // A stopped suite returns the rows it has, without the CSV.
    if (!spin_cases(o, table) || !dof_cases(o, table) || !long_cases(o, table) || !beam_cases(table)) return table.rows;
    if (!o.output.empty()) write_csv(o.output, table.rows);
    return table.rows;
}

}  // namespace hubbeam
