// hubbeam bench's runs: a scene collected into rows and timed, repeated, its references, the grid's time
// estimate and the grid itself.
#include "bench_parts.hpp"

#include <algorithm>
#include <hubbeam/make_model.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/shortest.hpp>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "dynamics/integrate.hpp"
#include "dynamics/stiffness.hpp"

namespace hubbeam {

using namespace bench_parts;

Collected bench_parts::collect(const Scene& scene, const StopRequest& stop)
{
    Collected c;
    Simulation simulation(scene);
    simulation.check_error(false);  // the benchmark measures the error against its references, and times the run alone
    c.summary = simulation.run([&](const Row& r) { c.rows.push_back(r); }, stop);
    return c;
}

Repeated bench_parts::repeat(const Scene& s, int repeats, const StopRequest& stop)
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

Scene bench_parts::variant_scene(const Scene& base, const VariantKey& key, const std::string& stepper, double rtol,
                                 double atol, Stepping stepping)
{
    Scene s = base;
    s.variant = key;
    s.solver.stepper = stepper;
    s.solver.rtol = rtol;
    s.solver.atol = atol;
    s.solver.stepping = stepping;
    return s;
}

Scene bench_parts::tight_scene(const Scene& scene, const VariantKey& k)
{
    return variant_scene(scene, k, reference_stepper, reference_rtol, reference_atol, Stepping::rows);
}

/// Runs the converged reference and the second one, and says on out what their difference, the first's
/// resolution, is (or why it is unknown). Throws BenchOptionError when either is not a valid variant.
References bench_parts::collect_references(const Scene& scene, const VariantKey& ref_key, const VariantKey& second_key,
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
double bench_parts::estimate_seconds(const Scene& scene, const BenchOptions& o, const std::vector<VariantKey>& keys,
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

namespace {

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

}  // namespace

/// Runs every grid point, each row written to the CSV o.output as it is measured and a line of progress per point
/// (`points` in all); stops between runs when asked, the CSV valid with the finished rows. Returns the rows.
std::vector<BenchRow> bench_parts::run_grid(const Scene& scene, const BenchOptions& o,
                                            const std::vector<VariantKey>& keys, const References& refs,
                                            std::size_t points, std::ostream& progress, const StopRequest& stop)
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

}  // namespace hubbeam
