// hubbeam bench --table1: the paper's Table 1 redone beside the paper's own figures.
#include "bench_parts.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <hubbeam/shortest.hpp>
#include <iterator>
#include <ostream>
#include <stdexcept>

#include "oscillation.hpp"

namespace hubbeam {

using namespace bench_parts;

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

}  // namespace hubbeam
