// hubbeam: the command line. A thin layer over the library: parse the options (CLI11, so that --help comes
// from the same definitions), load the scene with the overrides, run a Simulation into a CSV file, print the
// summary.
//
//   hubbeam run SCENE.toml [--method M] [--nx N] [--ny N] ... [-o FILE]   (options: scene_keys() in scene.cpp)
//   hubbeam variants                                   (built in, cached, and how others run)
//   hubbeam bench SCENE.toml [--methods LIST] [--ny LIST] [--steppers LIST] [--rtols LIST] [-o FILE] [--plot PREFIX]
//   hubbeam modes SCENE.toml [--omega LIST] [--methods LIST] [--ny LIST] [--count N] [-o FILE [--plot PREFIX]]
//   hubbeam linearize SCENE.toml --omega W -o PREFIX
//   hubbeam sweep SWEEP.toml [-o FILE] [--scheduler tls://HOST:PORT --tls-ca-file --tls-cert --tls-key]
//                 [--workers N] [--dashboard] [--no-resume]                                (runtime/python: Dask)
//   hubbeam kernels [--ny LIST] [--methods LIST] [--drives LIST] [--orders LIST] [--nx LIST] [--samples N] [-o FILE]
//
// Every file is written through OutputFile (output_file.hpp); outputs are checked against the command's inputs and
// each other before anything is computed. run writes NAME.csv into the current folder unless -o; modes writes a CSV
// only with -o. Exit codes: 0 success; 1 the simulation stopped early (rows so far kept); 2 bad input (nothing
// computed); 130 / 143 interrupted by SIGINT / SIGTERM (rows so far kept).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench.hpp"
#include "stress.hpp"
#include "generated_model.hpp"
#include "integrate.hpp"
#include "kernel_bench.hpp"
#include "fields.hpp"
#include "install_layout.hpp"
#include "modes.hpp"
#include "option_lists.hpp"
#include "shortest.hpp"
#include "on_demand.hpp"
#include "output.hpp"
#include "output_file.hpp"
#include "plot.hpp"
#include "scene.hpp"
#include "simulate.hpp"

#include <signal.h>
#include <unistd.h>

namespace {

using namespace hubbeam;

constexpr int exit_ok = 0;
constexpr int exit_stopped = 1;
constexpr int exit_bad_input = 2;
constexpr int exit_signal_base = 128;  // the shell's convention: 128 + the signal's number (130, 143)

constexpr const char* interrupted = "interrupted by signal";

/// The signal that asked the run to stop, 0 if none: the handler only sets it, the integration loop reads it
/// between rows (through the StopRequest), so the file is finished outside the handler.
volatile std::sig_atomic_t stop_signal = 0;

/// SIGINT / SIGTERM handler. A second signal while the first is being honoured kills at once (the default
/// action), for a user who does not want to wait for the next row; the temporary file is then left behind.
extern "C" void on_stop_signal(int sig)
{
    if (stop_signal != 0) {
        ::signal(sig, SIG_DFL);  // both async-signal-safe; sig is blocked until the handler returns
        ::raise(sig);
        return;
    }
    stop_signal = sig;
}

/// Routes SIGINT and SIGTERM to on_stop_signal, except a signal the parent set to be ignored (a shell's
/// background job ignores SIGINT, and should go on doing so).
void catch_stop_signals()
{
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    for (const int sig : {SIGINT, SIGTERM}) {
        struct sigaction previous {};
        if (::sigaction(sig, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
        ::sigaction(sig, &action, nullptr);
    }
}

/// The `run` options: one per scene key that has an option (scene_keys()), plus the scene file.
struct RunOptions {
    std::string scene;
    std::vector<std::string> values = std::vector<std::string>(scene_keys().size());
    std::string fields_at, fields_points = "81", fields_file;  // the fields along the beam (not scene keys)
};


/// Declares key's option on sub, its help text from the key table (with note after it), setting value.
void add_key_option(CLI::App& sub, const SceneKey& key, std::string& value, const std::string& note = "")
{
    static const char* const type_names[] = {"X", "N", "WORD", "FILE"};  // by SceneKey::Kind
    sub.add_option(key.option, value, std::string("Sets ") + key.name + ": " + key.expected + note)
        ->type_name(type_names[static_cast<int>(key.kind)]);
}

/// Declares the `run` options on sub from the scene key table; the help text of each is its documentation.
void add_run_options(CLI::App& sub, RunOptions& o)
{
    sub.add_option("scene", o.scene, "Scene file (TOML; format in docs/scene.md, examples in cases/)")->required();
    const std::vector<SceneKey>& keys = scene_keys();
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (keys[i].option) add_key_option(sub, keys[i], o.values[i]);
    sub.add_option("--fields-at", o.fields_at,
                   "Also write the fields along the beam (u_y, u_x, slope, curvature, bending moment, axial force) at "
                   "these times (s, comma-separated; the first row at or after each)")->type_name("LIST");
    sub.add_option("--fields-points", o.fields_points, "Equally spaced points along the beam for --fields-at (default 81)")
        ->type_name("N");
    sub.add_option("--fields", o.fields_file, "CSV of the fields (default: the output's name with -fields.csv)")
        ->type_name("FILE");
}

/// The --fields-at times and --fields-points count checked against the scene; throws ModesOptionError naming the
/// option.
std::pair<std::vector<double>, int> field_request(const RunOptions& o, const Scene& scene)
{
    std::vector<double> times;
    const std::string expected = "a comma-separated list of times from 0 to t_end = " + shortest(scene.output.t_end) + " s";
    for (const std::string& item : split_list(o.fields_at)) {
        double t = 0.0;
        if (!parse_non_negative(item, t) || t > scene.output.t_end)
            bad_option<ModesOptionError>("--fields-at", expected, printable(item));
        add_unique(times, t);
    }
    int points = 0;
    if (!parse_int(o.fields_points, 2, 100000, points))
        bad_option<ModesOptionError>("--fields-points", "an integer from 2 to 100000", printable(o.fields_points));
    if (static_cast<double>(times.size()) * points > static_cast<double>(max_output_rows))
        bad_option<ModesOptionError>("--fields-at", "at most " + std::to_string(max_output_rows) +
                                                        " field rows (times x points)",
                                     std::to_string(times.size()) + " times x " + std::to_string(points) + " points");
    return {times, points};
}

/// The options that were given, as overrides of their scene keys.
Overrides given_overrides(const CLI::App& sub, const RunOptions& o)
{
    Overrides overrides;
    const std::vector<SceneKey>& keys = scene_keys();
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (keys[i].option && sub.get_option(option_name(keys[i]))->count() > 0)
            overrides.emplace_back(keys[i].name, o.values[i]);
    return overrides;
}


/// A long run's progress on a terminal: after the first second, at most twice a second, one line on standard
/// error rewritten in place (simulated time, rate, time left, and a faster stepper if there is one); erased at the
/// end.
class Progress {
public:
    Progress(double t_end, std::string hint)
        : t_end_(t_end), hint_(std::move(hint)), enabled_(::isatty(STDERR_FILENO) != 0),
          start_(std::chrono::steady_clock::now()), last_(start_)
    {
    }
    ~Progress()
    {
        if (shown_) std::fputs("\r\033[K", stderr);
    }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void row(double t)
    {
        if (!enabled_) return;
        const auto now = std::chrono::steady_clock::now();
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        if (elapsed < 1.0 || std::chrono::duration<double>(now - last_).count() < 0.5 || t <= 0.0) return;
        last_ = now;
        const double rate = t / elapsed;
        std::fprintf(stderr, "\rhubbeam: t = %.4g of %.4g s (%.0f %%), %.3g s simulated per s, about %.0f s left%s%s\033[K",
                     t, t_end_, 100.0 * t / t_end_, rate, (t_end_ - t) / rate, hint_.empty() ? "" : "; ",
                     hint_.c_str());
        std::fflush(stderr);
        shown_ = true;
    }

private:
    double t_end_;
    std::string hint_;
    bool enabled_, shown_ = false;
    std::chrono::steady_clock::time_point start_, last_;
};

/// hubbeam run: returns the exit code.
int run(const CLI::App& sub, const RunOptions& o)
{
    const Overrides overrides = given_overrides(sub, o);
    Scene scene;
    try {
        scene = load_scene(o.scene, overrides);
    } catch (const SceneError& e) {
        std::cerr << message_for(e, overrides) << "\n";
        return exit_bad_input;
    }
    if (scene.output.file.empty()) scene.output.file = std::filesystem::path(scene.path).stem().string() + ".csv";

    std::pair<std::vector<double>, int> fields;
    std::string fields_file = o.fields_file;
    if (!o.fields_at.empty() || !fields_file.empty()) {
        try {
            fields = field_request(o, scene);
        } catch (const ModesOptionError& e) {
            std::cerr << e.what() << "\n";
            return exit_bad_input;
        }
        if (fields_file.empty()) {
            const std::filesystem::path out(scene.output.file);
            fields_file = (out.parent_path() / (out.stem().string() + "-fields.csv")).string();
        }
    }
    // Neither output may replace the scene or the other one (compared as files: ./x/../scene.toml, a hard link).
    const bool output_option = std::any_of(overrides.begin(), overrides.end(),
                                           [](const auto& kv) { return kv.first == "output.file"; });
    try {
        check_outputs({{scene.path, "the scene itself"}},
                      {{scene.output.file, output_option ? "-o" : scene.path + ": output.file"},
                       {fields_file, "--fields"}});
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }

    // Everything that can refuse the run does so before the output file is touched.
    std::unique_ptr<Simulation> simulation;
    try {
        simulation = std::make_unique<Simulation>(scene, [](const std::string& note) {
            std::cerr << "hubbeam: " << note << "\n";
        });
    } catch (const std::invalid_argument& e) {
        std::cerr << scene.path << ": " << e.what() << "\n";
        return exit_bad_input;
    } catch (const CompileError& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_bad_input;
    }
    // Caught before the temporary file exists: from here on a signal ends the run on a whole row and the file
    // is still put in place. (Before, the default action ends the process with nothing created.)
    catch_stop_signals();
    std::unique_ptr<CsvWriter> csv;
    try {
        csv = std::make_unique<CsvWriter>(scene.output.file);
    } catch (const std::exception& e) {  // OutputRefused (another hubbeam writes it), or cannot create
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }

    std::unique_ptr<FieldRecorder> recorder;
    if (!fields_file.empty()) {
        try {
            recorder = std::make_unique<FieldRecorder>(scene.key(), scene.parameters, fields.first, fields.second,
                                                       fields_file);
        } catch (const std::exception& e) {
            csv->discard();  // refused before any row: the old output stays as it was
            std::cerr << e.what() << "\n";
            return exit_bad_input;
        }
        simulation->observe_states([&recorder](double t, const double* q) { recorder->state(t, q); });
    }

    // An exception out of run() unwinds through ~CsvWriter, which finishes the file the same way.
    const StopRequest stop = [&csv]() -> const char* {
        if (stop_signal != 0) return interrupted;
        if (!csv->ok()) return "the output could not be written";  // no use computing rows that cannot be kept
        return nullptr;
    };
    RunSummary summary;
    {
        Progress progress(scene.output.t_end, ::isatty(STDERR_FILENO) ? simulation->faster_stepper_hint() : "");
        CsvWriter& writer = *csv;
        summary = simulation->run([&](const Row& r) { writer.write(r); progress.row(r.t); }, stop);
    }
    csv->finish();
    std::cout << format_summary(summary, scene);
    if (!csv->ok()) {
        std::cerr << csv->error() << "\n";
        return exit_stopped;
    }
    if (recorder) {
        if (!recorder->finish()) {
            std::cerr << recorder->error() << "\n";
            return exit_stopped;
        }
        std::cout << "fields      " << recorder->path() << "\n";
    }
    if (!summary.completed) {
        std::cerr << "hubbeam: stopped at t = " << summary.t_reached << " s: " << summary.failure << " (" << csv->rows()
                  << " rows kept in " << csv->path() << ")\n";
        return summary.failure == interrupted ? exit_signal_base + stop_signal : exit_stopped;
    }
    return exit_ok;
}

/// hubbeam variants: the variants built in and cached, one a line with where it comes from, then how any other
/// variant would run.
int list_variants()
{
    for (const std::string& name : generated_variant_names()) std::cout << "built in  " << name << "\n";
    for (const std::string& name : cached_variant_names()) std::cout << "cached    " << name << "\n";
    std::cout << "cache: " << variant_cache_dir().string() << " (clear with: rm -r " << variant_cache_root().string()
              << ")\n";
    if (const std::string why = on_demand_problem(); why.empty())
        std::cout << "other variants: generated and compiled on first use with " << on_demand_compiler() << "\n";
    else
        std::cout << "other variants: hand-assembled (" << why << "); order full cannot run\n";
    return exit_ok;
}

/// Declares the `bench` options; all are taken as text and checked by parse_bench_options.
void add_bench_options(CLI::App& sub, std::string& scene, BenchArgs& a)
{
    sub.add_option("scene", scene, "Scene file: the grid varies its discretization and solver")->required();
    sub.add_option("--methods", a.methods, "Methods, comma-separated (default " + a.methods + ")")->type_name("LIST");
    sub.add_option("--ny", a.ny, "Ny values, comma-separated (default " + a.ny + ")")->type_name("LIST");
    sub.add_option("--nx", a.nx, "Nx values, comma-separated (default: the scene's)")->type_name("LIST");
    sub.add_option("--steppers", a.steppers, "Steppers, comma-separated (default " + a.steppers + ")")->type_name("LIST");
    sub.add_option("--rtols", a.rtols, "Relative tolerances, comma-separated; atol = rtol/100 (default " + a.rtols + ")")
        ->type_name("LIST");
    sub.add_option("--repeats", a.repeats, "Timed runs per point, median reported (default " + a.repeats + ")")
        ->type_name("N");
    sub.add_option("--ref-ny", a.ref_ny, "Ny of the converged reference (default " + a.ref_ny + ")")->type_name("N");
    sub.add_option("--ref-method", a.ref_method, "Method of the converged reference (default " + a.ref_method + ")")
        ->type_name("M");
    sub.add_option("-o,--output", a.output, "CSV of the rows (default bench.csv)")->type_name("FILE");
    sub.add_option("--plot", a.plot, "Also draw PREFIX-work and PREFIX-dofs (PNG and SVG) with gnuplot")
        ->type_name("PREFIX");
    sub.add_flag("--yes", a.yes, "Run a grid estimated at over an hour");
    sub.add_flag("--table1", a.table1,
                 "Instead of a grid: the paper's Table 1 (four methods at Ny = 4) beside the paper's values");
}

/// Runs a command's work; its refusals become one line and exit 2: a bad option value, a scene that no model can
/// serve (named by scene_path), an on-demand variant that failed to compile.
template <class Work>
int refusing(const std::string& scene_path, const Work& work)
{
    try {
        return work();
    } catch (const OptionError& e) {
        std::cerr << e.what() << "\n";
    } catch (const std::invalid_argument& e) {
        std::cerr << scene_path << ": " << e.what() << "\n";
    } catch (const CompileError& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
    }
    return exit_bad_input;
}

/// hubbeam bench: returns the exit code.
int bench(const std::string& scene_path, const BenchArgs& args)
{
    Scene scene;
    BenchOptions options;
    try {
        scene = load_scene(scene_path, {});
        options = parse_bench_options(args, scene);
        std::vector<NamedPath> outputs = {{options.table1 ? std::string() : options.output, "-o"}};
        if (!options.table1 && !options.plot.empty())
            for (const char* end :
                 {"-work.png", "-work.svg", "-dofs.png", "-dofs.svg", ".gp", "-front.dat", "-dofs.dat"})
                outputs.push_back({options.plot + end, "--plot"});
        check_outputs({{scene.path, "the scene itself"}}, outputs);
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const SceneError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const BenchOptionError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    catch_stop_signals();
    const StopRequest stop = []() -> const char* { return stop_signal != 0 ? interrupted : nullptr; };
    std::ostringstream quiet;
    std::ostream& progress = ::isatty(STDERR_FILENO) ? std::cerr : quiet;  // progress lines on a terminal only
    const int refused = refusing(scene.path, [&] {
        if (options.table1) run_table1(scene, options, std::cout, std::cerr, stop);  // a minute: progress always
        else run_bench(scene, options, std::cout, progress, stop);
        return exit_ok;
    });
    if (refused != exit_ok) return refused;
    if (stop_signal != 0) {
        std::cerr << "hubbeam: bench interrupted by signal; the finished rows are in " << options.output << "\n";
        return exit_signal_base + stop_signal;
    }
    return exit_ok;
}

/// The scene keys that `modes` and `linearize` take as options ("--nx", "--order", "--source"), as overrides; the
/// options, their help and their checks are the key table's.
struct LinearOverrides {
    std::vector<std::string> keys, values;  // scene key names, and the values typed (empty: not given)
    Overrides overrides() const
    {
        Overrides o;
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (!values[i].empty()) o.emplace_back(keys[i], values[i]);
        return o;
    }
};

void add_linear_overrides(CLI::App& sub, LinearOverrides& o, bool single_variant)
{
    o.keys = {"discretization.nx", "model.order", "model.source"};
    if (single_variant) o.keys.insert(o.keys.end(), {"discretization.method", "discretization.ny"});
    o.values.assign(o.keys.size(), "");  // sized before the options hold references into it
    for (std::size_t i = 0; i < o.keys.size(); ++i)
        add_key_option(sub, scene_key(o.keys[i]), o.values[i], " (default: the scene's)");
}

/// hubbeam modes and hubbeam linearize: load the scene with the overrides, then act; returns the exit code.
template <class Act>
int linear_command(const std::string& scene_path, const LinearOverrides& lo, const Act& act)
{
    const Overrides overrides = lo.overrides();
    Scene scene;
    try {
        scene = load_scene(scene_path, overrides);
    } catch (const SceneError& e) {
        std::cerr << message_for(e, overrides) << "\n";
        return exit_bad_input;
    }
    return refusing(scene.path, [&] {
        act(scene);
        return exit_ok;
    });
}

/// hubbeam sweep: hands the arguments to the Python package's sweep (it runs on Dask), replacing this process;
/// returns only if that cannot start.
int sweep(const std::vector<std::string>& args)
{
#ifdef HUBBEAM_PYTHON_EXECUTABLE
    // The package of this build or installation, found relative to this program (none: Python's own path).
    const char* old = std::getenv("PYTHONPATH");
    if (const std::filesystem::path package = python_package_parent(); !package.empty()) {
        const std::string path = package.string() + (old != nullptr && *old != '\0' ? ":" + std::string(old) : "");
        ::setenv("PYTHONPATH", path.c_str(), 1);
    }
    std::vector<std::string> words = {HUBBEAM_PYTHON_EXECUTABLE, "-m", "hubbeam.sweeps"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::cerr << "hubbeam: cannot start " << HUBBEAM_PYTHON_EXECUTABLE << " for the sweep: " << std::strerror(errno) << "\n";
#else
    (void)args;
    std::cerr << "hubbeam: sweep needs the Python module: configure with -DHUBBEAM_PYTHON=ON (docs/python.md)\n";
#endif
    return exit_bad_input;
}

/// hubbeam stress: returns 0 when every case did what it must, 1 otherwise.
int stress(const StressOptions& options)
{
    try {
        check_outputs({}, {{options.output, "-o"}});  // checked now, not after the suite has run
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    catch_stop_signals();
    const StopRequest stop = []() -> const char* { return stop_signal != 0 ? interrupted : nullptr; };
    const std::vector<StressRow> rows = run_stress(options, std::cout, stop);
    int failed = 0;
    for (const StressRow& r : rows) failed += r.pass ? 0 : 1;
    std::cout << rows.size() << " cases, " << failed << " failed\n";
    if (stop_signal != 0) return exit_signal_base + stop_signal;
    return failed == 0 ? exit_ok : exit_stopped;
}

/// Declares the `kernels` options; all are taken as text and checked by parse_kernel_options, so that every bad
/// value is reported as "--option: expected ..., got ...".
void add_kernel_options(CLI::App& sub, KernelArgs& a)
{
    sub.add_option("--ny", a.ny, "Ny values, comma-separated (default " + a.ny + ")")->type_name("LIST");
    sub.add_option("--methods", a.methods, "Methods, comma-separated (default " + a.methods + ")")->type_name("LIST");
    sub.add_option("--drives", a.drives, "Drives, comma-separated (default " + a.drives + ")")->type_name("LIST");
    sub.add_option("--orders", a.orders, "Model orders, comma-separated (default " + a.orders + ")")->type_name("LIST");
    CLI::Option* nx = sub.add_option("--nx", a.nx, "Nx values, comma-separated; 'ny' is Nx = Ny (default " + a.nx + ")")
                          ->type_name("LIST");
    CLI::Option* equal = sub.add_flag("--nx-equal-ny", a.nx_equal_ny, "Only Nx = Ny (same as --nx ny)");
    CLI::Option* zero = sub.add_flag("--nx0", a.nx0, "Only Nx = 0 (same as --nx 0)");
    nx->excludes(equal)->excludes(zero);
    equal->excludes(zero);
    sub.add_option("--samples", a.samples, "Timed samples per measurement, median reported (default 7)")
        ->type_name("N");
    sub.add_option("-o,--output", a.output, "Also write the results as CSV to FILE")->type_name("FILE");
}

/// hubbeam kernels: returns the exit code.
int kernels(const KernelArgs& args)
{
    try {
        const KernelBenchOptions options = parse_kernel_options(args);
        check_outputs({}, {{options.output, "-o"}});
        run_kernel_bench(options, std::cout);
    } catch (const OptionError& e) {  // KernelOptionError, OutputRefused
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    return exit_ok;
}

/// Declares the `plot` arguments; all are taken as text and checked by plot_script, so that a bad one is one line
/// naming it.
void add_plot_options(CLI::App& sub, PlotArgs& a)
{
    sub.add_option("KIND", a.kind, "tip, axial (run CSVs), campbell (modes CSVs) or moment (field CSVs)")->required();
    sub.add_option("FILE", a.files, "CSV files in the kind's format (docs/cli.md)")->required();
    sub.add_option("-o,--output", a.prefix, "Writes PREFIX.png, PREFIX.svg and the gnuplot script PREFIX.gp")
        ->type_name("PREFIX")
        ->required();
    sub.add_option("--labels", a.labels, "Legend labels, comma-separated, one per file (default: the files' stems)")
        ->type_name("LIST");
    sub.add_option("--title", a.title, "Title (default: the kind's)")->type_name("TEXT");
    sub.add_option("--time", a.time, "moment: the rows at the t closest to T (default: each file's last t)")
        ->type_name("T");
}

/// hubbeam plot: returns the exit code.
int plot(const PlotArgs& args)
{
    try {
        if (const std::string problem = draw_plot(args); !problem.empty()) {
            std::cerr << "hubbeam: " << problem << "\n";
            return exit_stopped;
        }
    } catch (const PlotInputError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    std::cout << "figure: " << args.prefix << ".{png,svg}\n";
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "hubbeam: rotating flexible hub-beam simulator (equations derived by GiNaC, integrated by GSL).\n"
        "Exit codes: 0 success, 1 simulation stopped early (rows so far kept), 2 bad input, 130/143 interrupted\n"
        "by SIGINT/SIGTERM (rows so far kept)."};
    app.require_subcommand(1);

    RunOptions options;
    CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scene file and write its response as CSV");
    run_cmd->footer(
        "Options override the scene's keys. The CSV goes to -o FILE, else to the scene's output.file, else to "
        "NAME.csv in the current folder (NAME.toml's name). Exit codes: 0 success, 1 simulation stopped early (rows "
        "so far kept), 2 bad input (one line on stderr, nothing computed; also an output that is the scene or the "
        "other output, a FIFO, device or directory, or a file another hubbeam is writing), 130/143 interrupted by "
        "SIGINT/SIGTERM (rows so far kept). The CSV is written to DIR/.NAME.tmp-PID and renamed over FILE when the "
        "run ends.");
    add_run_options(*run_cmd, options);
    CLI::App* variants_cmd =
        app.add_subcommand("variants", "List the variants built in and cached, and how any other variant runs");
    std::string bench_scene;
    BenchArgs bench_args;
    CLI::App* bench_cmd = app.add_subcommand(
        "bench", "Work against precision: time and error of a grid of methods, DOF counts, steppers and tolerances");
    bench_cmd->footer("Writes a CSV (columns in docs/cli.md); exit code 2 for a bad option value or a grid "
                      "estimated at over an hour without --yes, 130/143 when interrupted (finished rows kept).");
    add_bench_options(*bench_cmd, bench_scene, bench_args);
    StressOptions stress_options;
    CLI::App* stress_cmd = app.add_subcommand(
        "stress", "Stability stress suite: high spin, many DOFs, long runs, extreme beams");
    stress_cmd->add_flag("--long", stress_options.long_runs, "1000 s runs and every method's largest DOF count");
    stress_cmd->add_flag("--quick", stress_options.quick, "Spin rates up to 20 rad/s only (what the tests run)");
    stress_cmd->add_option("-o,--output", stress_options.output, "Also write the table as CSV")->type_name("FILE");
    stress_cmd->footer("Exit code 0 when every case did what it must, 1 otherwise.");
    std::string modes_scene;
    ModesArgs modes_args;
    LinearOverrides modes_overrides;
    CLI::App* modes_cmd = app.add_subcommand(
        "modes", "Natural frequencies about a steady spin, per method, Ny and spin rate (a Campbell table)");
    modes_cmd->add_option("scene", modes_scene, "Scene file (TOML)")->required()->type_name("SCENE.toml");
    modes_cmd->add_option("--omega", modes_args.omega,
                          "Spin rates (rad/s): a comma-separated list, items may be ranges FIRST:LAST:STEP "
                          "(default: 0 and the scene's steady rate)")->type_name("LIST");
    modes_cmd->add_option("--methods", modes_args.methods, "Methods, comma-separated (default: the scene's)")->type_name("LIST");
    modes_cmd->add_option("--ny", modes_args.ny, "Ny values, comma-separated (default: the scene's)")->type_name("LIST");
    modes_cmd->add_option("--count", modes_args.count, "Bending modes printed per line group (default 4; the CSV has all)")
        ->type_name("N");
    modes_cmd->add_option("-o,--output", modes_args.output, "Also write every mode as CSV to FILE (default: no file)")
        ->type_name("FILE");
    modes_cmd
        ->add_option("--plot", modes_args.plot, "Also draw the Campbell diagram PREFIX.png and PREFIX.svg (needs -o)")
        ->type_name("PREFIX");
    modes_cmd->add_flag("-q,--quiet", modes_args.quiet,
                        "Print only how many modes were written, not the table (the CSV has every mode)");
    add_linear_overrides(*modes_cmd, modes_overrides, false);
    modes_cmd->footer("Prints the table; writes a file only when asked (-o, --plot). docs/cli.md. "
                      "Exit code 2 for a bad option value or an output that is the scene, another output, not a "
                      "regular file, or being written by another hubbeam.");
    std::string linearize_scene, linearize_omega, linearize_prefix;
    LinearOverrides linearize_overrides;
    CLI::App* linearize_cmd = app.add_subcommand(
        "linearize", "State-space matrices A, B, C, D about a steady spin (input hub torque or acceleration)");
    linearize_cmd->add_option("scene", linearize_scene, "Scene file (TOML)")->required()->type_name("SCENE.toml");
    linearize_cmd->add_option("--omega", linearize_omega, "Steady spin rate (rad/s), >= 0")->required()->type_name("W");
    linearize_cmd
        ->add_option("-o,--output", linearize_prefix, "Writes PREFIX-A.csv, PREFIX-B.csv, PREFIX-C.csv, PREFIX-D.csv")
        ->type_name("PREFIX")
        ->required();
    add_linear_overrides(*linearize_cmd, linearize_overrides, true);
    linearize_cmd->footer("docs/cli.md. Exit code 2 for a bad option value.");
    CLI::App* sweep_cmd = app.add_subcommand(
        "sweep", "Parameter sweep on Dask: SWEEP.toml [-o FILE] [--scheduler tls://HOST:PORT --tls-ca-file CA "
                 "--tls-cert CERT --tls-key KEY] [--workers N] [--dashboard] [--no-resume] (docs/python.md)");
    sweep_cmd->prefix_command();  // every argument goes to the sweep (hubbeam sweep --help describes them)
    sweep_cmd->set_help_flag();
    KernelArgs kernel_args;
    CLI::App* kernels_cmd = app.add_subcommand(
        "kernels", "Time the right-hand side and Jacobian per call, generated kernels against the assembled path");
    kernels_cmd->footer("Prints a table (ns per call); exit code 2 for a bad option value.");
    add_kernel_options(*kernels_cmd, kernel_args);
    PlotArgs plot_args;
    CLI::App* plot_cmd = app.add_subcommand(
        "plot", "Figures from CSV files with gnuplot: tip deflection, axial tip, Campbell diagram, bending moment");
    plot_cmd->footer("docs/cli.md. gnuplot draws into temporary files that replace the figures only when complete. "
                     "Exit codes: 0 figure written, 1 gnuplot or the disk failed (old figures kept), 2 bad input (one "
                     "line on stderr, nothing written).");
    add_plot_options(*plot_cmd, plot_args);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_bad_input;
    }

    try {
        if (run_cmd->parsed()) return run(*run_cmd, options);
        if (variants_cmd->parsed()) return list_variants();
        if (kernels_cmd->parsed()) return kernels(kernel_args);
        if (bench_cmd->parsed()) return bench(bench_scene, bench_args);
        if (stress_cmd->parsed()) return stress(stress_options);
        if (sweep_cmd->parsed()) return sweep(sweep_cmd->remaining());
        if (modes_cmd->parsed())
            return linear_command(modes_scene, modes_overrides, [&](const Scene& scene) {
                run_modes(scene, parse_modes_options(modes_args, scene), std::cout);
            });
        if (linearize_cmd->parsed())
            return linear_command(linearize_scene, linearize_overrides, [&](const Scene& scene) {
                const std::vector<double> omega = parse_spin_rates("--omega", linearize_omega);
                if (omega.size() != 1) throw ModesOptionError("--omega: expected one spin rate >= 0, got " + linearize_omega);
                run_linearize(scene, omega[0], linearize_prefix, std::cout);
            });
        if (plot_cmd->parsed()) return plot(plot_args);
    } catch (const std::exception& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_stopped;
    }
    return exit_bad_input;
}
