// hubbeam bench: the grid of runs, their references, the time estimate, the CSV and the gnuplot figures.
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include "integrate.hpp"
#include "oscillation.hpp"
#include "option_lists.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "shortest.hpp"
#include "stiffness.hpp"

namespace hubbeam {

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& expected, const std::string& got)
{
    bad_option<BenchOptionError>(option, expected, got);
}

constexpr int max_grid_dof = 64;
// The tight reference: the most accurate explicit stepper, a step at every row, tolerances near round-off.
constexpr const char* reference_stepper = "rk8pd";
constexpr double reference_rtol = 1e-12, reference_atol = 1e-14;
// A probe integrates this fraction of the scene to estimate a run's time.
constexpr double probe_fraction = 1.0 / 30.0;
constexpr double refuse_seconds = 3600.0;

/// A run of scene collected into rows, its summary, and the wall time of Simulation::run.
struct Collected {
    std::vector<Row> rows;
    RunSummary summary;
};

Collected collect(const Scene& scene, const StopRequest& stop)
{
    Collected c;
    Simulation simulation(scene);
    simulation.check_error(false);  // the benchmark measures the error against its references, and times the run alone
    c.summary = simulation.run([&](const Row& r) { c.rows.push_back(r); }, stop);
    return c;
}

/// A point's repeated runs: the first run's rows and summary, and every run's wall time, sorted. Repeats stop at
/// the first run that does not complete.
struct Repeated {
    Collected first;
    std::vector<double> walls;
    double median() const
    {
        const std::size_t n = walls.size();
        return n % 2 == 1 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2]);
    }
};

Repeated repeat(const Scene& s, int repeats, const StopRequest& stop)
{
    Repeated r;
    for (int rep = 0; rep < repeats; ++rep) {
        Collected c = collect(s, stop);
        r.walls.push_back(c.summary.wall_seconds);
        if (rep == 0) r.first = std::move(c);
        if (!r.first.summary.completed) break;
    }
    std::sort(r.walls.begin(), r.walls.end());
    return r;
}

double max_difference(const std::vector<Row>& a, const std::vector<Row>& b)
{
    double d = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, std::abs(a[i].tip_uy - b[i].tip_uy));
    return d;
}

Scene variant_scene(const Scene& base, const VariantKey& key, const std::string& stepper, double rtol, double atol,
                    Stepping stepping)
{
    Scene s = base;
    s.variant = key;
    s.solver.stepper = stepper;
    s.solver.rtol = rtol;
    s.solver.atol = atol;
    s.solver.stepping = stepping;
    return s;
}

std::string number(double x) { return x < 0.0 ? std::string() : shortest(x); }

std::string csv_row(const BenchRow& r)
{
    std::ostringstream line;
    line << to_string(r.key.method) << "," << r.key.nx << "," << r.key.ny << "," << to_string(r.key.order) << ","
         << r.stepper << "," << shortest(r.rtol) << "," << shortest(r.atol) << "," << number(r.time_error) << ","
         << number(r.disc_error) << "," << number(r.jacobi_drift) << "," << number(r.wall_median) << ","
         << number(r.wall_min) << "," << number(r.wall_max) << "," << r.repeats << "," << r.steps << "," << r.rhs_evals
         << "," << r.jacobian_evals << "," << csv_field(r.status);
    return line.str();
}

std::string seconds_text(double s)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, s < 1.0 ? "%.1f ms" : s < 120.0 ? "%.1f s" : "%.0f min", s < 1.0 ? s * 1e3 : s < 120.0 ? s : s / 60.0);
    return buf;
}

/// Writes and runs the gnuplot script of the figures; returns what went wrong, or empty.
std::string plot(const std::string& prefix, const std::string& csv, std::ostream& out);

}  // namespace

const char* bench_header()
{
    return "method,nx,ny,order,stepper,rtol,atol,time_error,disc_error,jacobi_drift,wall_median,wall_min,wall_max,"
           "repeats,steps,rhs_evals,jacobian_evals,status";
}

BenchOptions parse_bench_options(const BenchArgs& args, const Scene& scene)
{
    BenchOptions o;
    for (const std::string& s : split_list(args.methods)) {
        Method v{};
        if (!parse(s, v)) bad("--methods", "a comma-separated list of " + joined(words<Method>()), s);
        add_unique(o.methods, v);
    }
    const std::string dofs = "from 1 to " + std::to_string(max_grid_dof);
    for (const std::string& s : split_list(args.ny)) {
        int v = 0;
        if (!parse_int(s, 1, max_grid_dof, v)) bad("--ny", "a comma-separated list of integers " + dofs, s);
        add_unique(o.ny, v);
    }
    if (args.nx.empty()) o.nx = {scene.variant.nx};
    else
        for (const std::string& s : split_list(args.nx)) {
            int v = 0;
            if (!parse_int(s, 0, max_grid_dof, v)) bad("--nx", "a comma-separated list of integers from 0 to 64", s);
            add_unique(o.nx, v);
        }
    const std::vector<std::string> known = stepper_names();
    for (const std::string& s : split_list(args.steppers)) {
        if (std::find(known.begin(), known.end(), s) == known.end())
            bad("--steppers", "a comma-separated list of " + joined(known), s);
        add_unique(o.steppers, s);
    }
    for (const std::string& s : split_list(args.rtols)) {
        double v = 0.0;
        if (!parse_positive(s, v) || v >= 1.0) bad("--rtols", "a comma-separated list of numbers in (0, 1)", s);
        add_unique(o.rtols, v);
    }
    if (!parse_int(args.repeats, 1, 100, o.repeats)) bad("--repeats", "an integer from 1 to 100", args.repeats);
    if (!parse_int(args.ref_ny, 6, max_grid_dof, o.ref_ny)) bad("--ref-ny", "an integer from 6 to 64", args.ref_ny);
    if (!parse(args.ref_method, o.ref_method)) bad("--ref-method", "one of " + joined(words<Method>()), args.ref_method);
    o.output = args.output.empty() ? "bench.csv" : args.output;
    if (args.plot.find_first_of("'\"") != std::string::npos) bad("--plot", "a path prefix without quotes", args.plot);
    o.plot = args.plot;
    o.yes = args.yes;
    o.table1 = args.table1;
    return o;
}

std::vector<BenchRow> run_bench(const Scene& scene, const BenchOptions& o, std::ostream& out, std::ostream& progress,
                                const StopRequest& stop)
{
    const auto now = [] { return std::chrono::steady_clock::now(); };
    const auto since = [&](auto start) { return std::chrono::duration<double>(now() - start).count(); };
    // The grid, without the DOF counts a method cannot take.
    std::vector<VariantKey> keys;
    std::vector<std::string> skipped;
    for (const Method m : o.methods)
        for (const int ny : o.ny)
            for (const int nx : o.nx) {
                VariantKey k = scene.key();
                k.method = m;
                k.ny = ny;
                k.nx = nx;
                if (const std::string why = k.dof_problem(); !why.empty()) skipped.push_back(k.name() + ": " + why);
                else keys.push_back(k);
            }
    for (const std::string& s : skipped) out << "skipped " << s << "\n";

    // The converged reference: ref_method (AMM by default: its high modes are the beam's own, so an explicit
    // stepper integrates it cheaply) at ref_ny, and at ref_ny - 4 to show how far it has converged; axial
    // coordinates as many as bending ones when the grid has any.
    const bool axial = std::any_of(o.nx.begin(), o.nx.end(), [](int nx) { return nx > 0; });
    VariantKey ref_key = scene.key(), coarse_key = scene.key();
    ref_key.method = coarse_key.method = o.ref_method;
    ref_key.ny = o.ref_ny;
    coarse_key.ny = o.ref_ny - 4;
    ref_key.nx = axial ? o.ref_ny : 0;
    coarse_key.nx = axial ? o.ref_ny - 4 : 0;
    const auto tight = [&](const VariantKey& k) {
        return variant_scene(scene, k, reference_stepper, reference_rtol, reference_atol, Stepping::rows);
    };
    out << "references: " << ref_key.name() << " and " << coarse_key.name() << " (converged in DOFs), and each "
        << "variant at " << reference_stepper << " rtol " << shortest(reference_rtol) << " with a step at every row\n"
        << std::flush;
    const auto start = now();
    for (const VariantKey& k : {ref_key, coarse_key})
        if (const std::string why = k.dof_problem(); !why.empty())
            throw BenchOptionError("--ref-ny: the reference " + k.name() + " is not a valid variant: " + why);
    const Collected converged = collect(tight(ref_key), stop);
    const Collected coarse = collect(tight(coarse_key), stop);
    std::string converged_failure;
    for (const Collected* c : {&converged, &coarse})
        if (!c->summary.completed && converged_failure.empty())
            converged_failure = "converged reference stopped at t = " + shortest(c->summary.t_reached) + ": " + c->summary.failure;
    if (converged_failure.empty())
        out << "converged reference: max |tip_uy| change from Ny = " << coarse_key.ny << " to " << ref_key.ny << ": "
            << shortest(max_difference(converged.rows, coarse.rows))
            << " m (discretization errors below this are not resolved)\n";
    else
        out << converged_failure << "; no errors are reported\n";

    // Estimate: a probe of every grid point over a thirtieth of the scene, scaled to the whole. An explicit stepper
    // on stiff equations is held by stability once the stiff modes are excited, which the probe's first moments
    // do not show: its run takes at least t_end omega_max / stability_step_factor steps at the probe's cost each.
    double estimate = 0.0;
    const auto scaled = [&](const Scene& p, double omega) {
        const RunSummary probe = collect(p, stop).summary;
        const double bound_steps = scene.output.t_end * omega / stability_step_factor(p.solver.stepper);
        const double per_step = probe.steps > 0 ? probe.wall_seconds / static_cast<double>(probe.steps) : 0.0;
        return std::max(probe.wall_seconds / probe_fraction, bound_steps * per_step);
    };
    for (const VariantKey& k : keys) {
        Scene t = tight(k);
        t.output.t_end = scene.output.t_end * probe_fraction;
        t.output.dt_out = std::min(t.output.dt_out, t.output.t_end);
        // The grid point's stiffness, once for its steppers and tolerances (the variant is cached by now).
        const double omega = highest_frequency(*make_model(t.key(), t.parameters, t.source), t.axial);
        estimate += scaled(t, omega);
        for (const std::string& stepper : o.steppers)
            for (const double rtol : o.rtols) {
                Scene p = variant_scene(scene, k, stepper, rtol, rtol / 100.0, scene.solver.stepping);
                p.output.t_end = t.output.t_end;
                p.output.dt_out = t.output.dt_out;
                estimate += scaled(p, omega) * o.repeats;
            }
    }
    const std::size_t points = keys.size() * o.steppers.size() * o.rtols.size();
    out << points << " runs x " << o.repeats << " repeats; estimated time " << seconds_text(estimate) << "\n"
        << std::flush;
    if (estimate > refuse_seconds && !o.yes)
        throw BenchOptionError("the grid is estimated at " + seconds_text(estimate) +
                               " (over an hour): make it smaller, or pass --yes to run it anyway");

    CsvWriter csv(o.output, bench_header());
    std::vector<BenchRow> rows;
    std::size_t done = 0;
    for (const VariantKey& k : keys) {
        if (stop && stop()) break;
        const Collected same = collect(tight(k), stop);
        for (const std::string& stepper : o.steppers)
            for (const double rtol : o.rtols) {
                if (stop && stop()) break;
                BenchRow r;
                r.key = k;
                r.stepper = stepper;
                r.rtol = rtol;
                r.atol = rtol / 100.0;
                const Scene s = variant_scene(scene, k, stepper, r.rtol, r.atol, scene.solver.stepping);
                const Repeated runs = repeat(s, o.repeats, stop);
                const Collected& first = runs.first;
                if (!first.summary.completed && first.summary.failure == "interrupted by signal") break;
                r.repeats = static_cast<int>(runs.walls.size());
                r.wall_median = runs.median();
                r.wall_min = runs.walls.front();
                r.wall_max = runs.walls.back();
                r.steps = first.summary.steps;
                r.rhs_evals = first.summary.rhs_evals;
                r.jacobian_evals = first.summary.jacobian_evals;
                if (!first.summary.completed) r.status = "stopped at t = " + shortest(first.summary.t_reached) + ": " + first.summary.failure;
                else if (!same.summary.completed) r.status = "reference stopped: " + same.summary.failure;
                else if (!converged_failure.empty()) r.status = converged_failure;
                if (r.status == "ok") {
                    r.time_error = max_difference(first.rows, same.rows);
                    r.disc_error = max_difference(first.rows, converged.rows);
                    // the run's own invariant monitor; -1 when no row came after the drive
                    r.jacobi_drift = first.summary.vibration_energy < 0.0 ? -1.0 : first.summary.jacobi_drift;
                } else {
                    r.time_error = r.disc_error = r.jacobi_drift = -1.0;  // a failed run is no data point
                }
                csv.write_line(csv_row(r));
                rows.push_back(r);
                ++done;
                progress << "[" << done << "/" << points << "] " << k.name() << " " << stepper << " rtol "
                         << shortest(rtol) << ": " << seconds_text(r.wall_median) << ", error " << number(r.time_error)
                         << " m (time), " << number(r.disc_error) << " m (discretization)"
                         << (r.status == "ok" ? "" : ", " + r.status) << "\n"
                         << std::flush;
            }
    }
    csv.finish();
    if (!csv.ok()) throw std::runtime_error(csv.error());
    out << rows.size() << " of " << points << " runs in " << seconds_text(since(start)) << "; CSV: " << o.output << "\n";
    if (!o.plot.empty())
        if (const std::string problem = plot(o.plot, o.output, out); !problem.empty()) out << "no figures: " << problem << "\n";
    return rows;
}

void run_table1(const Scene& scene, const BenchOptions& o, std::ostream& out, const StopRequest& stop)
{
    // Paper Table 1 (Omega0 = 4 rad/s): relative computation time, error (%), amplitude (m), frequency (Hz);
    // BIM's time is the unit (its cell is blank in the paper's text, the unit by the others' ratios).
    struct Paper {
        Method method;
        const char *time, *error, *amplitude, *frequency;
    };
    const Paper paper[] = {{Method::fem, "24.1", "-", "0.0074", "0.5326"},
                           {Method::amm, "2.1", "0.1", "0.0074", "0.5319"},
                           {Method::bim, "1", "0.15", "0.0074", "0.5324"},
                           {Method::bsim, "1.67", "0.14", "0.0074", "0.5314"}};
    VariantKey ref_key = scene.key();
    ref_key.method = o.ref_method;
    ref_key.ny = o.ref_ny;
    ref_key.nx = scene.variant.nx > 0 ? o.ref_ny : 0;
    const Collected converged =
        collect(variant_scene(scene, ref_key, reference_stepper, reference_rtol, reference_atol, Stepping::rows), stop);
    if (!converged.summary.completed) throw std::runtime_error("the converged reference stopped: " + converged.summary.failure);
    double peak = 0.0;
    for (const Row& r : converged.rows) peak = std::max(peak, std::abs(r.tip_uy));
    const double t_steady = converged.summary.t_steady;  // the drive's last breakpoint
    struct Ours {
        double time_auto, time_msadams, error, amplitude, frequency;
        std::string stepper;
    };
    std::vector<Ours> ours;
    for (const Paper& p : paper) {
        VariantKey k = scene.key();
        k.method = p.method;
        k.ny = 4;
        Scene automatic = scene;
        automatic.variant = k;
        Scene adams = automatic;
        adams.solver.stepper = "msadams";
        const Repeated a = repeat(automatic, o.repeats, stop), m = repeat(adams, o.repeats, stop);
        Ours r;
        r.time_auto = a.median();
        r.time_msadams = m.median();
        if (!a.first.summary.completed) throw std::runtime_error(k.name() + " stopped: " + a.first.summary.failure);
        r.stepper = a.first.summary.stepper;
        r.error = 100.0 * max_difference(a.first.rows, converged.rows) / peak;
        const Oscillation osc = steady_oscillation(a.first.rows, t_steady);
        r.amplitude = osc.amplitude;
        r.frequency = osc.frequency;
        ours.push_back(r);
    }
    const double unit_auto = ours[2].time_auto, unit_adams = ours[2].time_msadams;  // BIM, as in the paper
    char line[512];
    out << "Table 1, redone: spin-up to " << shortest(scene.motion.omega0) << " rad/s, Ny = 4, Nx = "
        << scene.variant.nx << "; times relative to BIM (in process, median of " << o.repeats
        << "); error = max |tip_uy - " << ref_key.name() << "| / max |tip_uy| (" << shortest(peak)
        << " m); steady response after t = " << shortest(t_steady) << " s\n\n";
    std::snprintf(line, sizeof line, "%-6s %-30s %-22s %-18s %-22s %-20s\n", "method", "relative time: ours (stepper)",
                  "ours msadams | paper", "error %: ours | paper", "amplitude m: ours | paper",
                  "frequency Hz: ours | paper");
    out << line;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const Ours& r = ours[i];
        const Paper& p = paper[i];
        char t1[64], t2[64], e[64], a[64], f[64];
        std::snprintf(t1, sizeof t1, "%.2f (%s, %.1f ms)", r.time_auto / unit_auto, r.stepper.c_str(), r.time_auto * 1e3);
        std::snprintf(t2, sizeof t2, "%.2f | %s", r.time_msadams / unit_adams, p.time);
        std::snprintf(e, sizeof e, "%.3f | %s", r.error, p.error);
        std::snprintf(a, sizeof a, "%.4f | %s", r.amplitude, p.amplitude);
        std::snprintf(f, sizeof f, "%.4f | %s", r.frequency, p.frequency);
        std::snprintf(line, sizeof line, "%-6s %-30s %-22s %-18s %-22s %-20s\n", to_string(p.method).c_str(), t1, t2, e,
                      a, f);
        out << line;
    }
}

namespace {

std::string plot(const std::string& prefix, const std::string& csv, std::ostream& out)
{
    // The Pareto front: rows no other row beats in both wall time and error (time and discretization error
    // together: their maximum is the error against the converged solution up to the reference's own).
    const std::string script_path = prefix + ".gp";
    std::ofstream gp(script_path);
    gp << "# gnuplot script written by hubbeam bench: work-precision figures from " << csv << "\n"
       << figure_style()
       << "set logscale xy\n"
          "set format y '10^{%L}'\n"
          "methods = 'amm fem bim bsim'\n"
          "steppers = system(\"tail -n +2 '"
       << csv << "' | cut -d, -f5 | sort -u | tr '\\n' ' '\")\n"
          "ok(s) = (strcol(18) eq 'ok') ? s : NaN\n"
          "err(c1, c2) = (column(c1) > column(c2) ? column(c1) : column(c2))\n"
       << in_png_and_svg(figure_output(prefix + "-work") +
                         "  set title 'Work against precision: tip deflection error against the converged solution'\n"
                         "  set xlabel 'wall time per run (s, in process, median)'\n"
                         "  set ylabel 'max |tip u_y - reference| (m)'\n"
                         "  plot for [m in methods] for [s in steppers] '" +
                         csv +
                         "' using (strcol(1) eq m && strcol(5) eq s ? ok(column(11)) : NaN):(err(8, 9)) with "
                         "linespoints title m.' '.s, \\\n"
                         "       '" +
                         prefix + "-front.dat' using 1:2 with steps lw 3 lc rgb 'black' title 'Pareto front'\n" +
                         figure_output(prefix + "-dofs") +
                         "  set title 'Discretization error against DOF count (tightest tolerance of the grid)'\n"
                         "  set xlabel 'transverse DOFs N_y'\n"
                         "  set ylabel 'max |tip u_y - converged reference| (m)'\n"
                         "  plot for [m in methods] '" +
                         prefix + "-dofs.dat' using (strcol(1) eq m ? column(2) : NaN):3 with linespoints title m\n");
    gp.close();
    // The data the script needs beside the CSV: the front and the DOF convergence, computed here.
    struct Point {
        std::string method, stepper;
        int ny;
        double rtol, wall, error;
    };
    std::vector<Point> points;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
        if (f.size() < 18 || f[17] != "ok") continue;
        points.push_back({f[0], f[4], std::atoi(f[2].c_str()), std::atof(f[5].c_str()), std::atof(f[10].c_str()),
                          std::max(std::atof(f[7].c_str()), std::atof(f[8].c_str()))});
    }
    std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.wall < b.wall; });
    std::ofstream front(prefix + "-front.dat");
    double best = HUGE_VAL;
    for (const Point& p : points)
        if (p.error < best) {
            best = p.error;
            front << p.wall << "," << p.error << "\n";
        }
    std::map<std::pair<std::string, int>, double> dofs;  // the smallest error per method and Ny
    for (const Point& p : points) {
        auto [it, added] = dofs.emplace(std::make_pair(p.method, p.ny), p.error);
        if (!added) it->second = std::min(it->second, p.error);
    }
    std::ofstream d(prefix + "-dofs.dat");
    for (const auto& [k, e] : dofs) d << k.first << "," << k.second << "," << e << "\n";
    front.close();
    d.close();
    if (const std::string problem = run_gnuplot(script_path); !problem.empty()) return problem;
    out << "figures: " << prefix << "-work.{png,svg}, " << prefix << "-dofs.{png,svg} (script " << script_path << ")\n";
    return {};
}

}  // namespace

}  // namespace hubbeam
