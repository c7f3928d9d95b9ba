// hubbeam bench: the options, the grid of runs and the run as a whole (references, time estimate, grid, Pareto
// front, figures); the parts are in the bench_*.cpp beside it (bench_parts.hpp).
#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/shortest.hpp>
#include <ostream>

#include "bench_parts.hpp"
#include "dynamics/integrate.hpp"
#include "dynamics/stiffness.hpp"
#include "oscillation.hpp"
#include "plot.hpp"

namespace hubbeam {

using namespace bench_parts;

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& expected, const std::string& got)
{
    bad_option<BenchOptionError>(option, expected, got);
}

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

}  // namespace

std::vector<std::string> bench_parts::steppers_and_auto()
{
    std::vector<std::string> names = stepper_names();
    names.emplace_back(automatic_stepper_word);
    return names;
}

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

}  // namespace hubbeam
