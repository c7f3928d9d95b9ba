// hubbeam bench: work against precision over a grid of methods, DOF counts, steppers and tolerances, or the
// paper's Table 1.
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <hubbeam/output_file.hpp>
#include <unistd.h>

#include "bench.hpp"
#include "command.hpp"
#include "plot.hpp"

namespace hubbeam::cli {

namespace {

/// Declares the `bench` options; all are taken as text and checked by parse_bench_options.
void add_bench_options(Subcommand& sub, std::string& scene, BenchArgs& a)
{
    sub.add_option("scene", scene, "Scene file: the grid varies its discretization and solver").required();
    sub.add_option("--methods", a.methods, "Methods, comma-separated (default " + a.methods + ")").type_name("LIST");
    sub.add_option("--ny", a.ny, "Ny values, comma-separated (default " + a.ny + ")").type_name("LIST");
    sub.add_option("--nx", a.nx, "Nx values, comma-separated (default: the scene's)").type_name("LIST");
    sub.add_option("--steppers", a.steppers, "Steppers, comma-separated (default " + a.steppers + ")")
        .type_name("LIST");
    sub.add_option("--rtols", a.rtols,
                   "Relative tolerances, comma-separated; atol = rtol/100 (default " + a.rtols + ")")
        .type_name("LIST");
    sub.add_option("--repeats", a.repeats, "Timed runs per point, median reported (default " + a.repeats + ")")
        .type_name("N");
    sub.add_option("--ref-ny", a.ref_ny, "Ny of the converged reference (default " + a.ref_ny + ")").type_name("N");
    sub.add_option("--ref-method", a.ref_method, "Method of the converged reference (default " + a.ref_method + ")")
        .type_name("M");
    sub.add_option("-o,--output", a.output, "CSV of the rows (default bench.csv)").type_name("FILE");
    sub.add_option("--plot", a.plot, "Also draw PREFIX-work and PREFIX-dofs (PNG and SVG) with gnuplot")
        .type_name("PREFIX");
    sub.add_flag("--yes", a.yes, "Run a grid estimated at over an hour");
    sub.add_flag("--table1", a.table1,
                 "Instead of a grid: the paper's Table 1 (four methods at Ny = 4) beside the paper's values");
}

/// hubbeam bench: returns the exit code.
int bench(const std::string& scene_path, const BenchArgs& args)
{
    Scene scene;
    BenchOptions options;
    try {
        scene = load_scene(scene_path, {});
        options = parse_bench_options(args, scene);
        if (!options.plot.empty()) check_prefix("--plot", options.plot);  // before the bench runs, not at drawing
        check_outputs(scene_inputs(scene), bench_outputs(options));
    } catch (const OptionError& e) {  // BenchOptionError, OutputRefused
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const SceneError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    catch_stop_signals();
    const StopRequest stop = signal_stop();
    std::ostringstream quiet;
    std::ostream& progress = ::isatty(STDERR_FILENO) ? std::cerr : quiet;  // progress lines on a terminal only
    const int refused = refusing(scene.path, [&] {
        if (options.table1) run_table1(scene, options, std::cout, std::cerr, stop);  // a minute: progress always
        else run_bench(scene, options, std::cout, progress, stop);
        return exit_ok;
    });
    if (refused != exit_ok) return refused;
    if (stop_signal() != 0) {
        std::cerr << "hubbeam: bench interrupted by signal; the finished rows are in " << options.output << "\n";
        return exit_signal_base + stop_signal();
    }
    return exit_ok;
}

}  // namespace

Command add_bench_command(CLI::App& app)
{
    struct Options {
        std::string scene;
        BenchArgs args;
    };
    auto o = std::make_shared<Options>();
    Subcommand bench_cmd(
        app, "bench",
        "Work against precision: time and error of a grid of methods, DOF counts, steppers and tolerances");
    bench_cmd.footer(
        "Writes a CSV (columns in docs/cli.md); exit code 2 for a bad option value or a grid "
        "estimated at over an hour without --yes, 130/143 when interrupted (finished rows kept).");
    add_bench_options(bench_cmd, o->scene, o->args);
    return {bench_cmd.app(), [o] { return bench(o->scene, o->args); }};
}

}  // namespace hubbeam::cli
