// hubbeam run: a scene's response as CSV (and, asked for, the fields along the beam), the summary on standard
// output. Options: one per scene key that has one (scene_keys()), plus the fields'.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/fields.hpp>
#include <hubbeam/metadata.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene_print.hpp>
#include <hubbeam/shortest.hpp>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "command.hpp"
#include "modes.hpp"

namespace hubbeam::cli {

namespace {

/// The `run` options: one per scene key that has an option (scene_keys()), plus the scene file.
struct RunOptions {
    std::string scene;
    std::vector<std::string> values = std::vector<std::string>(scene_keys().size());
    // Each key's option (null for a key without one): asked whether it was given, without a search by name.
    std::vector<Option> given = std::vector<Option>(scene_keys().size());
    std::string fields_at, fields_points = "81", fields_file;  // the fields along the beam (not scene keys)
    // Not a scene key: whether the output must survive a power loss depends on the machine and the job, not on
    // what is simulated (the same scene runs on a laptop and in a batch queue).
    bool durable = false;
    bool print_scene = false;  // print the effective scene as TOML instead of running it
};

/// Declares the `run` options on sub from the scene key table; the help text of each is its documentation.
void add_run_options(Subcommand& sub, RunOptions& o)
{
    sub.add_option("scene", o.scene, "Scene file (TOML; format in docs/scene.md, examples in cases/)").required();
    const std::vector<SceneKey>& keys = scene_keys();
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (keys[i].option) o.given[i] = add_key_option(sub, keys[i], o.values[i]);
    sub.add_option("--fields-at", o.fields_at,
                   "Also write the fields along the beam (u_y, u_x, slope, curvature, bending moment, axial force) at "
                   "these times (s, comma-separated; the first row at or after each)")
        .type_name("LIST");
    sub.add_option("--fields-points", o.fields_points,
                   "Equally spaced points along the beam for --fields-at (default 81)")
        .type_name("N");
    sub.add_option("--fields", o.fields_file, "CSV of the fields (default: the output's name with -fields.csv)")
        .type_name("FILE");
    sub.add_flag("--durable", o.durable,
                 "Sync the output to the disk before it replaces the old one, so that it survives a power loss (off: "
                 "the output still appears whole or not at all, but the last seconds of a run may be lost with the "
                 "machine)");
    sub.add_flag("--print-scene", o.print_scene,
                 "Print the effective scene as TOML (every key, defaults filled, the options applied) and exit without "
                 "running; the printed scene runs as this one does");
}

/// The --fields-at times and --fields-points count checked against the scene; throws ModesOptionError naming the
/// option.
std::pair<std::vector<double>, int> field_request(const RunOptions& o, const Scene& scene)
{
    std::vector<double> times;
    const std::string expected =
        "a comma-separated list of times from 0 to t_end = " + shortest(scene.output.t_end) + " s";
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
        bad_option<ModesOptionError>("--fields-at",
                                     "at most " + std::to_string(max_output_rows) + " field rows (times x points)",
                                     std::to_string(times.size()) + " times x " + std::to_string(points) + " points");
    return {times, points};
}

/// The options that were given, as overrides of their scene keys.
Overrides given_overrides(const RunOptions& o)
{
    Overrides overrides;
    const std::vector<SceneKey>& keys = scene_keys();
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (o.given[i].given()) overrides.emplace_back(keys[i].name, o.values[i]);
    return overrides;
}

/// A long run's progress on a terminal: after the first second, at most twice a second, one line on standard
/// error rewritten in place (simulated time, rate, time left, and a faster stepper if there is one); erased at the
/// end.
class Progress {
public:
    Progress(double t_end, std::string hint)
        : t_end_(t_end),
          hint_(std::move(hint)),
          enabled_(::isatty(STDERR_FILENO) != 0),
          start_(std::chrono::steady_clock::now()),
          last_(start_)
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
        std::fprintf(stderr,
                     "\rhubbeam: t = %.4g of %.4g s (%.0f %%), %.3g s simulated per s, about %.0f s left%s%s\033[K", t,
                     t_end_, 100.0 * t / t_end_, rate, (t_end_ - t) / rate, hint_.empty() ? "" : "; ", hint_.c_str());
        std::fflush(stderr);
        shown_ = true;
    }

private:
    double t_end_;
    std::string hint_;
    bool enabled_, shown_ = false;
    std::chrono::steady_clock::time_point start_, last_;
};

/// What a run writes where, checked before anything is computed.
struct RunPlan {
    Scene scene;
    std::pair<std::vector<double>, int> fields;  // --fields-at times and --fields-points
    std::string fields_file;                     // empty: no fields
};

/// The scene with the options, its outputs named and checked against it and each other (as files: ./x/../scene.toml,
/// a hard link); prints the refusal and returns false when there is one.
bool plan_run(const RunOptions& o, RunPlan& plan)
{
    const Overrides overrides = given_overrides(o);
    try {
        plan.scene = load_scene(o.scene, overrides);
    } catch (const SceneError& e) {
        std::cerr << message_for(e, overrides) << "\n";
        return false;
    }
    Scene& scene = plan.scene;
    if (scene.output.file.empty()) scene.output.file = std::filesystem::path(scene.path).stem().string() + ".csv";
    if (o.print_scene) return true;  // nothing is written: the outputs need no check
    plan.fields_file = o.fields_file;
    if (!o.fields_at.empty() || !plan.fields_file.empty()) {
        try {
            plan.fields = field_request(o, scene);
        } catch (const ModesOptionError& e) {
            std::cerr << e.what() << "\n";
            return false;
        }
        if (plan.fields_file.empty()) {
            const std::filesystem::path out(scene.output.file);
            plan.fields_file = (out.parent_path() / (out.stem().string() + "-fields.csv")).string();
        }
    }
    const bool output_option =
        std::any_of(overrides.begin(), overrides.end(), [](const auto& kv) { return kv.first == "output.file"; });
    const std::string output_name = output_option ? "-o" : scene.path + ": output.file";
    try {
        check_outputs(scene_inputs(scene), {{scene.output.file, output_name},
                                            {is_npy_path(scene.output.file) ? npy_columns_path(scene.output.file) : "",
                                             output_name + "'s column names"},
                                            {metadata_path(scene.output.file), output_name + "'s metadata"},
                                            {plan.fields_file, "--fields"}});
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return false;
    }
    // Named by what it is, not only by where: a file called x.npz holding CSV text misleads whoever opens it.
    const auto extension = [](const std::string& path) { return std::filesystem::path(path).extension().string(); };
    if (const std::string ext = extension(scene.output.file); ext != ".csv" && ext != ".npy") {
        std::cerr << output_name << ": expected a file name ending in .csv (CSV text) or .npy (a NumPy array), got "
                  << "\"" << printable(scene.output.file, 400) << "\"\n";
        return false;
    }
    if (!plan.fields_file.empty() && extension(plan.fields_file) != ".csv") {
        std::cerr << "--fields: expected a file name ending in .csv, got \"" << printable(plan.fields_file, 400)
                  << "\"\n";
        return false;
    }
    return true;
}

/// The model chosen and the output files opened, or the refusal printed and nullptr: everything that can refuse the
/// run does so before the output is touched.
std::unique_ptr<Simulation> prepare(const RunPlan& plan, bool durable, std::unique_ptr<CsvWriter>& csv,
                                    std::unique_ptr<MetadataFile>& metadata, std::unique_ptr<FieldRecorder>& recorder)
{
    const Scene& scene = plan.scene;
    std::unique_ptr<Simulation> simulation;
    try {
        simulation = std::make_unique<Simulation>(
            scene, [](const std::string& note) { std::cerr << "hubbeam: " << note << "\n"; });
    } catch (const std::invalid_argument& e) {
        std::cerr << scene.path << ": " << e.what() << "\n";
        return nullptr;
    } catch (const CompileError& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return nullptr;
    }
    // Caught before the temporary file exists: from here on a signal ends the run on a whole row and the file
    // is still put in place. (Before, the default action ends the process with nothing created.)
    catch_stop_signals();
    try {
        csv = std::make_unique<CsvWriter>(scene.output.file, optional_columns_of(scene), durable);
        metadata = std::make_unique<MetadataFile>(scene.output.file);
    } catch (const std::exception& e) {  // OutputRefused (another hubbeam writes it, a planted lock), or cannot create
        if (csv) csv->discard();         // refused before any row: the old output stays as it was
        std::cerr << e.what() << "\n";
        return nullptr;
    }
    if (plan.fields_file.empty()) return simulation;
    try {
        recorder = std::make_unique<FieldRecorder>(scene.key(), scene.parameters, plan.fields.first, plan.fields.second,
                                                   plan.fields_file, scene.rotor);
    } catch (const std::exception& e) {
        csv->discard();  // refused before any row: the old output stays as it was
        std::cerr << e.what() << "\n";
        return nullptr;
    }
    simulation->observe_states([r = recorder.get()](double t, const double* q) { r->state(t, q); });
    return simulation;
}

/// hubbeam run: returns the exit code.
int run(const RunOptions& o)
{
    RunPlan plan;
    if (!plan_run(o, plan)) return exit_bad_input;
    if (o.print_scene) {
        std::cout << effective_scene_toml(plan.scene);
        return exit_ok;
    }
    std::unique_ptr<CsvWriter> csv;
    std::unique_ptr<MetadataFile> sidecar;
    std::unique_ptr<FieldRecorder> recorder;
    const std::unique_ptr<Simulation> simulation = prepare(plan, o.durable, csv, sidecar, recorder);
    if (!simulation) return exit_bad_input;

    // An exception out of run() unwinds through ~CsvWriter, which finishes the file the same way.
    const StopRequest stop = [&csv]() -> const char* {
        if (stop_signal() != 0) return interrupted;
        if (!csv->ok()) return "the output could not be written";  // no use computing rows that cannot be kept
        return nullptr;
    };
    RunSummary summary;
    {
        Progress progress(plan.scene.output.t_end, ::isatty(STDERR_FILENO) ? simulation->faster_stepper_hint() : "");
        CsvWriter& writer = *csv;
        summary = simulation->run(
            [&](const Row& r) {
                writer.write(r);
                progress.row(r.t);
            },
            stop);
    }
    csv->finish();
    std::cout << format_summary(summary, plan.scene);
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
    // Beside the rows once they (and the fields) are in place, whatever the run's end: a run stopped early says so
    // in it too.
    if (const std::string why =
            sidecar->write(run_metadata(plan.scene, summary, csv->path(), row_header(optional_columns_of(plan.scene)),
                                        csv->rows(), recorder ? recorder->path() : ""));
        !why.empty()) {
        std::cerr << why << "\n";
        return exit_stopped;
    }
    std::cout << "metadata    " << sidecar->path() << "\n";
    if (!summary.completed) {
        std::cerr << "hubbeam: stopped at t = " << summary.t_reached << " s: " << summary.failure << " (" << csv->rows()
                  << " rows kept in " << csv->path() << ")\n";
        return summary.failure == interrupted ? exit_signal_base + stop_signal() : exit_stopped;
    }
    return exit_ok;
}

}  // namespace

Command add_run_command(CLI::App& app)
{
    auto options = std::make_shared<RunOptions>();
    Subcommand run_cmd(app, "run", "Simulate a scene file and write its response as CSV");
    run_cmd.footer(
        "Options override the scene's keys. The CSV goes to -o FILE, else to the scene's output.file, else to "
        "NAME.csv in the current folder (NAME.toml's name); a FILE ending in .npy gets the rows as a NumPy array "
        "(float64, rows x columns) and the column names in FILE's name with .columns.txt; FILE must end in .csv or "
        ".npy. An output that is the scene, a table it reads or the other output, a FIFO, device, directory, "
        "symbolic link or read-only file, or a file another hubbeam is writing, is bad input. " +
        std::string(exit_codes_help) +
        " The output is written to "
        "DIR/.NAME.tmp-PID and renamed over FILE when the run ends; FILE.hubbeam.json beside it says where it came "
        "from (version, variant, effective scene, stepper, summary).");
    add_run_options(run_cmd, *options);
    return {run_cmd.app(), [options] { return run(*options); }};
}

}  // namespace hubbeam::cli
