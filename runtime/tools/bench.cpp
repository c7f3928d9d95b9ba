// hubbeam bench: the grid of runs, their references, the time estimate, the CSV and the gnuplot figures.
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>

#include "csv_columns.hpp"
#include "integrate.hpp"
#include "make_model.hpp"
#include "option_lists.hpp"
#include "oscillation.hpp"
#include "output.hpp"
#include "output_file.hpp"
#include "plot.hpp"
#include "shortest.hpp"
#include "stiffness.hpp"

namespace hubbeam {

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& expected, const std::string& got)
{
    bad_option<BenchOptionError>(option, expected, got);
}

// The files of --plot PREFIX: the two figures (each .png and .svg), their script, the data the script reads.
constexpr const char* figure_suffixes[] = {"-work", "-dofs"};
constexpr const char* script_suffix = ".gp";
constexpr const char* data_suffixes[] = {"-front.dat", "-dofs.dat"};  // the Pareto front, the DOF convergence

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

/// The bench CSV's columns: the one definition of its header and of how a row fills each column.
struct BenchColumn {
    const char* name;
    std::string (*text)(const BenchRow&);
};

const std::vector<BenchColumn>& bench_columns()
{
    static const std::vector<BenchColumn> columns{
        {"method", [](const BenchRow& r) { return to_string(r.key.method); }},
        {"nx", [](const BenchRow& r) { return std::to_string(r.key.nx); }},
        {"ny", [](const BenchRow& r) { return std::to_string(r.key.ny); }},
        {"order", [](const BenchRow& r) { return to_string(r.key.order); }},
        {"stepper", [](const BenchRow& r) { return r.stepper; }},
        {"chosen", [](const BenchRow& r) { return r.chosen; }},
        {"rtol", [](const BenchRow& r) { return shortest(r.rtol); }},
        {"atol", [](const BenchRow& r) { return shortest(r.atol); }},
        {"time_error", [](const BenchRow& r) { return number(r.time_error); }},
        {"disc_error", [](const BenchRow& r) { return number(r.disc_error); }},
        {"jacobi_drift", [](const BenchRow& r) { return number(r.jacobi_drift); }},
        {"wall_median", [](const BenchRow& r) { return number(r.wall_median); }},
        {"wall_min", [](const BenchRow& r) { return number(r.wall_min); }},
        {"wall_max", [](const BenchRow& r) { return number(r.wall_max); }},
        {"repeats", [](const BenchRow& r) { return std::to_string(r.repeats); }},
        {"steps", [](const BenchRow& r) { return std::to_string(r.steps); }},
        {"rhs_evals", [](const BenchRow& r) { return std::to_string(r.rhs_evals); }},
        {"jacobian_evals", [](const BenchRow& r) { return std::to_string(r.jacobian_evals); }},
        {"status", [](const BenchRow& r) { return csv_field(r.status); }},
    };
    return columns;
}

std::string csv_row(const BenchRow& r)
{
    std::string line;
    for (const BenchColumn& c : bench_columns()) {
        if (&c != &bench_columns().front()) line += ',';
        line += c.text(r);
    }
    return line;
}

std::string seconds_text(double s)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, s < 1.0 ? "%.1f ms" : s < 120.0 ? "%.1f s" : "%.0f min", s < 1.0 ? s * 1e3 : s < 120.0 ? s : s / 60.0);
    return buf;
}

/// x to three significant digits, for the messages.
std::string three_digits(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

/// Writes and runs the gnuplot script of the figures of the bench CSV csv (of scene `scene`, its converged reference
/// good to `resolution` m); returns what went wrong, or empty.
std::string plot(const std::string& prefix, const std::string& csv, const std::string& scene, double resolution,
                 std::ostream& out);

/// The second converged reference, whose difference from the first (`reference`) is the first's resolution: BIM
/// (it converges fastest in DOFs: at Ny = 6 it is as far from AMM at 12 as at 8), at no more than Ny = 8, where
/// its mass matrix is still well conditioned enough for rtol 1e-12; AMM at the same Ny when the reference is BIM.
VariantKey second_reference(const VariantKey& reference)
{
    VariantKey second = reference;
    second.method = reference.method == Method::bim ? Method::amm : Method::bim;
    if (second.method == Method::bim) {
        second.ny = std::min(reference.ny, 8);
        if (second.nx > 0) second.nx = second.ny;
    }
    return second;
}

/// The scene's name for titles: its file's stem.
std::string scene_name(const Scene& scene)
{
    const std::size_t slash = scene.path.find_last_of('/');
    std::string name = slash == std::string::npos ? scene.path : scene.path.substr(slash + 1);
    if (const std::size_t dot = name.rfind('.'); dot != std::string::npos && dot > 0) name.resize(dot);
    return name;
}

/// A row's error against the converged solution: the larger of its two errors (their maximum is that error up to
/// the reference's own).
double overall_error(const BenchRow& r) { return std::max(r.time_error, r.disc_error); }

/// Prints the rows on the Pareto front, fastest first.
void print_front(const std::vector<BenchRow>& rows, double resolution, std::ostream& out)
{
    std::vector<WorkPoint> points;
    std::vector<const BenchRow*> ok;
    for (const BenchRow& r : rows)
        if (r.status == "ok") {
            points.push_back({r.wall_median, overall_error(r)});
            ok.push_back(&r);
        }
    if (points.empty()) return;
    out << "Pareto front (errors within " << three_digits(resolution) << " m of each other are ties):\n";
    for (const std::size_t i : pareto_front(points, resolution)) {
        const BenchRow& r = *ok[i];
        out << "  " << r.key.name() << " " << r.stepper << " rtol " << shortest(r.rtol) << ": "
            << seconds_text(r.wall_median) << ", error " << three_digits(overall_error(r)) << " m\n";
    }
}

}  // namespace

std::vector<std::size_t> pareto_front(const std::vector<WorkPoint>& points, double resolution)
{
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return points[a].wall != points[b].wall ? points[a].wall < points[b].wall : points[a].error < points[b].error;
    });
    std::vector<std::size_t> front;
    for (const std::size_t i : order)
        // a slower point is on the front only if it beats the front's best error by more than a tie
        if (front.empty() || points[i].error < points[front.back()].error - resolution) front.push_back(i);
    return front;
}

const char* bench_header()
{
    static const std::string header = [] {
        std::string h;
        for (const BenchColumn& c : bench_columns()) h += (h.empty() ? "" : ",") + std::string(c.name);
        return h;
    }();
    return header.c_str();
}

namespace {

/// stepper_names() and the automatic choice: what a figure's series can be.
std::vector<std::string> steppers_and_auto()
{
    std::vector<std::string> names = stepper_names();
    names.emplace_back(automatic_stepper_word);
    return names;
}

}  // namespace

BenchOptions parse_bench_options(const BenchArgs& args, const Scene& scene)
{
    BenchOptions o;
    o.methods = parse_method_list<BenchOptionError>("--methods", args.methods);
    o.ny = parse_dof_list<BenchOptionError>("--ny", args.ny, 1);
    o.nx = args.nx.empty() ? std::vector<int>{scene.variant.nx} : parse_dof_list<BenchOptionError>("--nx", args.nx, 0);
    const std::vector<std::string> known = steppers_and_auto();  // the automatic choice measured against the others
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
    if (!parse_int(args.ref_ny, 6, largest_dof_count(), o.ref_ny))
        bad("--ref-ny", "an integer from 6 to " + std::to_string(largest_dof_count()), args.ref_ny);
    if (!parse(args.ref_method, o.ref_method)) bad("--ref-method", "one of " + joined(words<Method>()), args.ref_method);
    o.output = args.output.empty() ? "bench.csv" : args.output;
    if (args.plot.find_first_of("'\"") != std::string::npos) bad("--plot", "a path prefix without quotes", args.plot);
    o.plot = args.plot;
    o.yes = args.yes;
    o.table1 = args.table1;
    return o;
}

std::vector<NamedPath> bench_outputs(const BenchOptions& o)
{
    if (o.table1) return {};  // the paper's table is printed, not written
    std::vector<NamedPath> outputs = {{o.output, "-o"}};
    if (o.plot.empty()) return outputs;
    for (const char* figure : figure_suffixes)
        for (const char* ext : {".png", ".svg"}) outputs.push_back({o.plot + figure + ext, "--plot"});
    outputs.push_back({o.plot + script_suffix, "--plot"});
    for (const char* data : data_suffixes) outputs.push_back({o.plot + data, "--plot"});
    return outputs;
}

namespace {

/// The grid's variants, without the DOF counts a method cannot take (each skipped one printed to out).
std::vector<VariantKey> grid_keys(const Scene& scene, const BenchOptions& o, std::ostream& out)
{
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
    return keys;
}

/// The converged reference's variant: ref_method (AMM by default: its high modes are the beam's own, so an explicit
/// stepper integrates it cheaply) at ref_ny; axial coordinates as many as bending ones when the grid has any.
VariantKey reference_key(const Scene& scene, const BenchOptions& o)
{
    const bool axial = std::any_of(o.nx.begin(), o.nx.end(), [](int nx) { return nx > 0; });
    VariantKey ref_key = scene.key();
    ref_key.method = o.ref_method;
    ref_key.ny = o.ref_ny;
    ref_key.nx = axial ? o.ref_ny : 0;
    return ref_key;
}

/// scene as variant k at the tight reference tolerance, with a step at every row.
Scene tight_scene(const Scene& scene, const VariantKey& k)
{
    return variant_scene(scene, k, reference_stepper, reference_rtol, reference_atol, Stepping::rows);
}

/// The converged reference's run, why it stopped (empty: it did not), and its resolution in m (0: unknown).
struct References {
    Collected converged;
    std::string failure;
    double resolution = 0.0;
};

/// Runs the converged reference and the second one, and says on out what their difference, the first's
/// resolution, is (or why it is unknown). Throws BenchOptionError when either is not a valid variant.
References collect_references(const Scene& scene, const VariantKey& ref_key, const VariantKey& second_key,
                              std::ostream& out, const StopRequest& stop)
{
    for (const VariantKey& k : {ref_key, second_key})
        if (const std::string why = k.dof_problem(); !why.empty())
            throw BenchOptionError("--ref-ny: the reference " + k.name() + " is not a valid variant: " + why);
    References refs;
    refs.converged = collect(tight_scene(scene, ref_key), stop);
    const Collected second = collect(tight_scene(scene, second_key), stop);
    const RunSummary& converged = refs.converged.summary;
    if (!converged.completed)
        refs.failure = "converged reference stopped at t = " + shortest(converged.t_reached) + ": " + converged.failure;
    if (!refs.failure.empty()) {
        out << refs.failure << "; no errors are reported\n";
    } else if (!second.summary.completed) {
        out << "the second reference " << second_key.name() << " stopped at t = " << shortest(second.summary.t_reached)
            << ": " << second.summary.failure << "; the reference's resolution is unknown, every difference counts\n";
    } else {
        refs.resolution = max_difference(refs.converged.rows, second.rows);
        out << "converged reference: max |tip_uy| difference between " << ref_key.name() << " and " << second_key.name()
            << ": " << three_digits(refs.resolution)
            << " m (its resolution: errors within it of each other are ties on the Pareto front)\n";
    }
    return refs;
}

/// The grid's time in s, a lower bound: a probe of every grid point over a thirtieth of the scene, scaled to the
/// whole. An explicit stepper on stiff equations is held by stability once the stiff modes are excited, which the
/// probe's first moments do not show: its run takes at least t_end omega_max / stability_step_factor steps at the
/// probe's cost each.
double estimate_seconds(const Scene& scene, const BenchOptions& o, const std::vector<VariantKey>& keys,
                        const StopRequest& stop)
{
    double estimate = 0.0;
    const auto scaled = [&](const Scene& p, double omega) {
        const RunSummary probe = collect(p, stop).summary;
        const double bound_steps = scene.output.t_end * omega / stability_step_factor(p.solver.stepper);
        const double per_step = probe.steps > 0 ? probe.wall_seconds / static_cast<double>(probe.steps) : 0.0;
        return std::max(probe.wall_seconds / probe_fraction, bound_steps * per_step);
    };
    for (const VariantKey& k : keys) {
        Scene t = tight_scene(scene, k);
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
    return estimate;
}

/// One grid point: variant k with stepper at rtol (atol rtol / 100), repeated, against its same-discretization
/// reference `same` and the converged one. Empty when a signal interrupted its first run (no row then).
std::optional<BenchRow> measure_point(const Scene& scene, const VariantKey& k, const std::string& stepper, double rtol,
                                      int repeats, const Collected& same, const References& refs,
                                      const StopRequest& stop)
{
    BenchRow r;
    r.key = k;
    r.stepper = stepper;
    r.rtol = rtol;
    r.atol = rtol / 100.0;
    const Scene s = variant_scene(scene, k, stepper, r.rtol, r.atol, scene.solver.stepping);
    const Repeated runs = repeat(s, repeats, stop);
    const Collected& first = runs.first;
    if (!first.summary.completed && first.summary.failure == "interrupted by signal") return std::nullopt;
    r.chosen = first.summary.stepper;
    r.repeats = static_cast<int>(runs.walls.size());
    r.wall_median = runs.median();
    r.wall_min = runs.walls.front();
    r.wall_max = runs.walls.back();
    r.steps = first.summary.steps;
    r.rhs_evals = first.summary.rhs_evals;
    r.jacobian_evals = first.summary.jacobian_evals;
    if (!first.summary.completed)
        r.status = "stopped at t = " + shortest(first.summary.t_reached) + ": " + first.summary.failure;
    else if (!same.summary.completed)
        r.status = "reference stopped: " + same.summary.failure;
    else if (!refs.failure.empty())
        r.status = refs.failure;
    if (r.status == "ok") {
        r.time_error = max_difference(first.rows, same.rows);
        r.disc_error = max_difference(first.rows, refs.converged.rows);
        // the run's own invariant monitor; -1 when no row came after the drive
        r.jacobi_drift = first.summary.vibration_energy < 0.0 ? -1.0 : first.summary.jacobi_drift;
    } else {
        r.time_error = r.disc_error = r.jacobi_drift = -1.0;  // a failed run is no data point
    }
    return r;
}

/// Runs every grid point, each row written to the CSV o.output as it is measured and a line of progress per point
/// (`points` in all); stops between runs when asked, the CSV valid with the finished rows. Returns the rows.
std::vector<BenchRow> run_grid(const Scene& scene, const BenchOptions& o, const std::vector<VariantKey>& keys,
                               const References& refs, std::size_t points, std::ostream& progress,
                               const StopRequest& stop)
{
    CsvWriter csv(o.output, bench_header());
    std::vector<BenchRow> rows;
    for (const VariantKey& k : keys) {
        if (stop && stop()) break;
        const Collected same = collect(tight_scene(scene, k), stop);
        for (const std::string& stepper : o.steppers)
            for (const double rtol : o.rtols) {
                if (stop && stop()) break;
                const std::optional<BenchRow> r = measure_point(scene, k, stepper, rtol, o.repeats, same, refs, stop);
                if (!r) break;
                csv.write_line(csv_row(*r));
                rows.push_back(*r);
                progress << "[" << rows.size() << "/" << points << "] " << k.name() << " " << stepper << " rtol "
                         << shortest(rtol) << ": " << seconds_text(r->wall_median) << ", error "
                         << number(r->time_error) << " m (time), " << number(r->disc_error) << " m (discretization)"
                         << (r->status == "ok" ? "" : ", " + r->status) << "\n"
                         << std::flush;
            }
    }
    csv.finish();
    if (!csv.ok()) throw std::runtime_error(csv.error());
    return rows;
}

}  // namespace

std::vector<BenchRow> run_bench(const Scene& scene, const BenchOptions& o, std::ostream& out, std::ostream& progress,
                                const StopRequest& stop)
{
    const auto now = [] { return std::chrono::steady_clock::now(); };
    const auto since = [&](auto start) { return std::chrono::duration<double>(now() - start).count(); };
    const std::vector<VariantKey> keys = grid_keys(scene, o, out);

    // The converged reference's own resolution is how far a second converged discretization (another method, its
    // basis functions different) lies from it: errors closer to each other than that are ties.
    const VariantKey ref_key = reference_key(scene, o), second_key = second_reference(ref_key);
    out << "references: " << ref_key.name() << " (converged in DOFs; " << second_key.name()
        << " for its resolution), and each variant at " << reference_stepper << " rtol " << shortest(reference_rtol)
        << " with a step at every row\n"
        << std::flush;
    const auto start = now();
    const References refs = collect_references(scene, ref_key, second_key, out, stop);

    const double estimate = estimate_seconds(scene, o, keys, stop);
    const std::size_t points = keys.size() * o.steppers.size() * o.rtols.size();
    // A lower bound: the probes see the cost of a step, not the steps a tolerance needs once the response has
    // grown (an adaptive stepper shortens its steps then), and leave out compiling variants not yet cached.
    out << points << " runs x " << o.repeats << " repeats and " << keys.size()
        << " same-discretization references; estimated time at least " << seconds_text(estimate)
        << " (from probes over the first " << shortest(probe_fraction * scene.output.t_end)
        << " s scaled to the whole, no step longer than an explicit stepper's stability bound; the references and "
           "probes, with compiling the variants not cached yet, took "
        << seconds_text(since(start)) << " so far)\n"
        << std::flush;
    if (estimate > refuse_seconds && !o.yes)
        throw BenchOptionError("the grid is estimated at " + seconds_text(estimate) +
                               " (over an hour): make it smaller, or pass --yes to run it anyway");

    const std::vector<BenchRow> rows = run_grid(scene, o, keys, refs, points, progress, stop);
    out << rows.size() << " of " << points << " runs in " << seconds_text(since(start)) << " with the references"
        << "; CSV: " << o.output << "\n";
    print_front(rows, refs.resolution, out);
    if (!o.plot.empty())
        if (const std::string problem = plot(o.plot, o.output, scene_name(scene), refs.resolution, out);
            !problem.empty())
            out << "no figures: " << problem << "\n";
    return rows;
}

namespace {

/// A row of the paper's Table 1 (Omega0 = 4 rad/s): relative computation time, error (%), amplitude (m),
/// frequency (Hz), as printed there.
struct PaperRow {
    Method method;
    const char *time, *error, *amplitude, *frequency;
};

// BIM's time is the unit (its cell is blank in the paper's text, the unit by the others' ratios).
constexpr PaperRow paper_table1[] = {{Method::fem, "24.1", "-", "0.0074", "0.5326"},
                                     {Method::amm, "2.1", "0.1", "0.0074", "0.5319"},
                                     {Method::bim, "1", "0.15", "0.0074", "0.5324"},
                                     {Method::bsim, "1.67", "0.14", "0.0074", "0.5314"}};
constexpr std::size_t table1_unit = 2;  // BIM's row

/// The converged reference of Table 1 and what the rows are measured against: its largest deflection (m) and the
/// time its steady response starts (s, the drive's last breakpoint).
struct Table1Reference {
    VariantKey key;
    Collected run;
    double peak = 0.0, t_steady = 0.0;
};

/// Runs Table 1's converged reference: o.ref_method at o.ref_ny (axial coordinates as many when the scene has any)
/// at the tight tolerance. Throws when it stops.
Table1Reference table1_reference(const Scene& scene, const BenchOptions& o, const StopRequest& stop)
{
    Table1Reference ref;
    ref.key = scene.key();
    ref.key.method = o.ref_method;
    ref.key.ny = o.ref_ny;
    ref.key.nx = scene.variant.nx > 0 ? o.ref_ny : 0;
    ref.run =
        collect(variant_scene(scene, ref.key, reference_stepper, reference_rtol, reference_atol, Stepping::rows), stop);
    if (!ref.run.summary.completed)
        throw std::runtime_error("the converged reference stopped: " + ref.run.summary.failure);
    for (const Row& r : ref.run.rows) ref.peak = std::max(ref.peak, std::abs(r.tip_uy));
    ref.t_steady = ref.run.summary.t_steady;
    return ref;
}

/// Our measures of a row of Table 1.
struct Table1Row {
    double time_auto, time_msadams, error, amplitude, frequency;  // s, s, % of the peak, m, Hz
    std::string stepper;                                          // the scene's, as the run resolved it
};

/// The variant of method's row of Table 1: the scene's at Ny = 4.
VariantKey table1_key(const Scene& scene, Method method)
{
    VariantKey k = scene.key();
    k.method = method;
    k.ny = 4;
    return k;
}

/// Method `method` at Ny = 4 on scene: its times with the scene's stepper and with msadams (medians of `repeats`),
/// its error against the reference and its steady oscillation. Throws when the run stops.
Table1Row table1_row(const Scene& scene, Method method, int repeats, const Table1Reference& ref,
                     const StopRequest& stop)
{
    const VariantKey k = table1_key(scene, method);
    Scene automatic = scene;
    automatic.variant = k;
    Scene adams = automatic;
    adams.solver.stepper = "msadams";
    const Repeated a = repeat(automatic, repeats, stop), m = repeat(adams, repeats, stop);
    Table1Row r;
    r.time_auto = a.median();
    r.time_msadams = m.median();
    if (!a.first.summary.completed) throw std::runtime_error(k.name() + " stopped: " + a.first.summary.failure);
    r.stepper = a.first.summary.stepper;
    r.error = 100.0 * max_difference(a.first.rows, ref.run.rows) / ref.peak;
    const Oscillation osc = steady_oscillation(a.first.rows, ref.t_steady);
    r.amplitude = osc.amplitude;
    r.frequency = osc.frequency;
    return r;
}

/// Prints Table 1: its heading, then our row beside the paper's for each method, times relative to BIM's.
void print_table1(const Scene& scene, const BenchOptions& o, const Table1Reference& ref,
                  const std::vector<Table1Row>& ours, std::ostream& out)
{
    const double unit_auto = ours[table1_unit].time_auto, unit_adams = ours[table1_unit].time_msadams;
    char line[512];
    out << "Table 1, redone: spin-up to " << shortest(scene.motion.omega0)
        << " rad/s, Ny = 4, Nx = " << scene.variant.nx << "; times relative to BIM (in process, median of " << o.repeats
        << "); error = max |tip_uy - " << ref.key.name() << "| / max |tip_uy| (" << shortest(ref.peak)
        << " m); steady response after t = " << shortest(ref.t_steady) << " s\n\n";
    std::snprintf(line, sizeof line, "%-6s %-30s %-22s %-18s %-22s %-20s\n", "method", "relative time: ours (stepper)",
                  "ours msadams | paper", "error %: ours | paper", "amplitude m: ours | paper",
                  "frequency Hz: ours | paper");
    out << line;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const Table1Row& r = ours[i];
        const PaperRow& p = paper_table1[i];
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

}  // namespace

void run_table1(const Scene& scene, const BenchOptions& o, std::ostream& out, std::ostream& progress,
                const StopRequest& stop)
{
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return seconds_text(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    };
    const Table1Reference ref = table1_reference(scene, o, stop);
    progress << "[reference] " << ref.key.name() << " at " << reference_stepper << " rtol " << shortest(reference_rtol)
             << ": done after " << elapsed() << "\n"
             << std::flush;
    std::vector<Table1Row> ours;
    for (const PaperRow& p : paper_table1) {
        ours.push_back(table1_row(scene, p.method, o.repeats, ref, stop));
        const Table1Row& r = ours.back();
        progress << "[" << ours.size() << "/" << std::size(paper_table1) << "] " << table1_key(scene, p.method).name()
                 << ": " << r.stepper << " " << seconds_text(r.time_auto) << ", msadams "
                 << seconds_text(r.time_msadams) << " (median of " << o.repeats << "); done after " << elapsed() << "\n"
                 << std::flush;
    }
    print_table1(scene, o, ref, ours, out);
}

namespace {

/// The figures' script and the data files beside the CSV that it reads.
struct BenchFigures {
    std::string script, front, dofs;
};

/// A finished run of the bench CSV, as the figures draw it.
struct FigurePoint {
    std::string method, stepper;
    int ny;
    double wall, error;  // s; m, the larger of its two errors
};

/// The bench CSV at csv's finished runs, read back by column name.
std::vector<FigurePoint> read_points(const std::string& csv)
{
    std::vector<FigurePoint> points;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    const CsvColumns columns(csv, line);
    const std::size_t method = columns.at("method"), stepper = columns.at("stepper"), ny = columns.at("ny"),
                      wall = columns.at("wall_median"), time_error = columns.at("time_error"),
                      disc_error = columns.at("disc_error"), status = columns.at("status");
    while (std::getline(in, line)) {
        const std::vector<std::string> f = csv_fields(line);
        if (f.size() != columns.size() || f[status] != "ok") continue;
        points.push_back({f[method], f[stepper], std::atoi(f[ny].c_str()), std::atof(f[wall].c_str()),
                          std::max(std::atof(f[time_error].c_str()), std::atof(f[disc_error].c_str()))});
    }
    return points;
}

/// The series the points make, each sorted: (method, stepper) pairs and methods as indices into words<Method>()
/// and stepper_names(), so that a method keeps its colour and a stepper its marker from one figure to the next.
struct FigureSeries {
    std::vector<std::pair<std::size_t, std::size_t>> lines;  // (method, stepper): a line of the work figure each
    std::vector<std::size_t> methods;                        // a line of the DOF figure each
    std::vector<int> nys;                                    // the DOF figure's ticks
};

FigureSeries figure_series(const std::vector<FigurePoint>& points)
{
    const std::vector<std::string> all_steppers = steppers_and_auto(), method_names = words<Method>();
    const auto index = [](const std::vector<std::string>& names, const std::string& name) {
        return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    FigureSeries s;
    for (const FigurePoint& p : points) {
        add_unique(s.lines, std::make_pair(index(method_names, p.method), index(all_steppers, p.stepper)));
        add_unique(s.methods, index(method_names, p.method));
        add_unique(s.nys, p.ny);
    }
    std::sort(s.lines.begin(), s.lines.end());
    std::sort(s.methods.begin(), s.methods.end());
    std::sort(s.nys.begin(), s.nys.end());
    return s;
}

/// A name of a method or stepper in the script's quotes.
std::string quoted(const std::string& s)
{
    return "'" + s + "'";
}

/// The work figure's plot command: a line per method and stepper read from the CSV (a colour per method, a point
/// type and dash pattern per stepper, so that no two lines look alike), and the Pareto front from PREFIX-front.dat.
std::string work_plot(const std::string& prefix, const std::string& csv, const FigureSeries& series)
{
    const std::vector<std::string> all_steppers = steppers_and_auto(), method_names = words<Method>();
    static const char* const dashes[] = {"1", "2", "3", "4", "5", "(20,6,3,6,3,6)", "(4,8)", "(30,10)"};
    std::string work = "  plot ";
    for (std::size_t i = 0; i < series.lines.size(); ++i) {
        const auto [m, st] = series.lines[i];
        work += (i ? ", \\\n       " : "") + quoted(csv) + " using (strcol('method') eq " + quoted(method_names[m]) +
                " && strcol('stepper') eq " + quoted(all_steppers[st]) +
                " && strcol('status') eq 'ok' ? column('wall_median') : NaN):(larger(column('time_error'), column('disc_error')))"
                " with linespoints lw 1.5 lc " +
                std::to_string(m + 1) + " pt " + std::to_string(st % 13 + 1) + " dt " + dashes[st % 8] +
                " title " + quoted(method_names[m] + " " + all_steppers[st]);
    }
    return work + ", \\\n       '" + prefix +
           "-front.dat' using 'wall':'error' with steps lw 3 lc rgb 'black' title 'Pareto front'";
}

/// The DOF figure's axis settings and plot command: the smallest error per method against Ny from PREFIX-dofs.dat,
/// ticks at the grid's Ny, and the reference's resolution when known.
std::string dofs_plot(const std::string& prefix, const FigureSeries& series, double resolution)
{
    const std::vector<std::string> method_names = words<Method>();
    std::string dofs = "  plot ";
    for (std::size_t i = 0; i < series.methods.size(); ++i)
        dofs += (i ? ", \\\n       " : "") +
                ("'" + prefix + "-dofs.dat' using (strcol('method') eq " + quoted(method_names[series.methods[i]]) +
                 " ? column('ny') : NaN):'error' " + "with linespoints lw 2 pt 7 lc " +
                 std::to_string(series.methods[i] + 1) + " title " + quoted(method_names[series.methods[i]]));
    if (resolution > 0.0)
        dofs += ", \\\n       " + shortest(resolution) +
                " with lines dt 2 lw 2 lc rgb 'gray40' title 'reference resolution'";
    std::string ny_tics, ny_range;
    for (const int n : series.nys) ny_tics += (ny_tics.empty() ? "" : ", ") + std::to_string(n);
    if (!series.nys.empty())  // a little beyond the grid's Ny on either side, not the decades around them
        ny_range =
            "  set xrange [" + shortest(series.nys.front() / 1.15) + ":" + shortest(series.nys.back() * 1.15) + "]\n";
    return "  set xtics (" + ny_tics + ")\n" + ny_range + dofs;
}

/// PREFIX-front.dat: the points on the Pareto front (errors within the reference's resolution are ties).
std::string front_data(const std::vector<FigurePoint>& points, double resolution)
{
    std::vector<WorkPoint> plane;
    for (const FigurePoint& p : points) plane.push_back({p.wall, p.error});
    std::string front = "wall,error\n";
    for (const std::size_t i : pareto_front(plane, resolution))
        front += shortest(points[i].wall) + "," + shortest(points[i].error) + "\n";
    return front;
}

/// PREFIX-dofs.dat: the smallest error per method and Ny.
std::string dofs_data(const std::vector<FigurePoint>& points)
{
    std::map<std::pair<std::string, int>, double> smallest;
    for (const FigurePoint& p : points) {
        auto [it, added] = smallest.emplace(std::make_pair(p.method, p.ny), p.error);
        if (!added) it->second = std::min(it->second, p.error);
    }
    std::string dofs = "method,ny,error\n";
    for (const auto& [k, e] : smallest) dofs += k.first + "," + std::to_string(k.second) + "," + shortest(e) + "\n";
    return dofs;
}

/// The figures of the bench CSV at csv (drawn to figures[0], the work against precision, and figures[1], the error
/// against Ny) and the data files they read beside it, computed here.
BenchFigures bench_figures(const std::string& prefix, const std::vector<std::string>& figures, const std::string& csv,
                           const std::string& scene, double resolution)
{
    const std::vector<FigurePoint> points = read_points(csv);
    const FigureSeries series = figure_series(points);
    BenchFigures f;
    f.script = "# gnuplot script written by hubbeam bench: work-precision figures from " + csv + "\n" + figure_style() +
               "set logscale xy\n"
               "set format y '10^{%L}'\n"
               "larger(a, b) = a > b ? a : b\n" +
               in_png_and_svg(figure_output(figures[0]) + "  set title " +
                              gnuplot_string("Work against precision, " + scene +
                                             ": tip deflection error against the converged solution") +
                              " noenhanced\n"
                              "  set xlabel 'wall time per run (s, in process, median)'\n"
                              "  set ylabel 'max |tip u_y - reference| (m)'\n"
                              "  set xtics autofreq\n"
                              "  set autoscale x\n" +
                              work_plot(prefix, csv, series) + "\n" + figure_output(figures[1]) + "  set title " +
                              gnuplot_string("Discretization error against DOF count, " + scene +
                                             " (the smallest error of each method and Ny)") +
                              " noenhanced\n"
                              "  set xlabel 'transverse DOFs N_y'\n"
                              "  set ylabel 'max |tip u_y - converged reference| (m)'\n" +
                              dofs_plot(prefix, series, resolution) + "\n");
    f.front = front_data(points, resolution);
    f.dofs = dofs_data(points);
    return f;
}

std::string plot(const std::string& prefix, const std::string& csv, const std::string& scene, double resolution,
                 std::ostream& out)
{
    const std::vector<std::string> names = {prefix + figure_suffixes[0], prefix + figure_suffixes[1]};
    const BenchFigures figures = bench_figures(prefix, names, csv, scene, resolution);
    const std::string script_path = prefix + script_suffix;
    // The data the script reads beside the CSV, then the figures (draw_figures draws them into temporary files).
    for (const auto& [path, text] : {std::pair{prefix + data_suffixes[0], figures.front},
                                     std::pair{prefix + data_suffixes[1], figures.dofs}}) {
        OutputFile file(path);
        if (const int error = file.write(text); error != 0) return path + ": write failed: " + std::strerror(error);
        if (const std::string why = file.commit(); !why.empty()) return path + ": " + why;
    }
    if (const std::string problem =
            draw_figures(names, script_path, figures.script,
                         [&](const std::vector<std::string>& temp) {
                             return bench_figures(prefix, temp, csv, scene, resolution).script;
                         });
        !problem.empty())
        return problem;
    out << "figures: " << names[0] << ".{png,svg}, " << names[1] << ".{png,svg} (script " << script_path << ")\n";
    return {};
}

}  // namespace

}  // namespace hubbeam
