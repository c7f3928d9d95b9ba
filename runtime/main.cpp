// hubbeam: the command line. A thin layer over the library: parse the options (CLI11, so that --help comes
// from the same definitions), load the scene, apply the overrides, run simulate() into a CSV file, print the
// summary.
//
//   hubbeam run SCENE.toml [--method M] [--nx N] [--ny N] [--order O] [--spline-basis B] [--source S]
//                          [--stepper NAME] [--rtol X] [--atol X] [--h0 X] [--t-end T] [--dt-out H] [-o FILE]
//   hubbeam variants
//
// Exit codes: 0 success; 1 the simulation stopped early (rows so far kept); 2 bad input (nothing computed).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "generated_model.hpp"
#include "integrate.hpp"
#include "output.hpp"
#include "scene.hpp"
#include "simulate.hpp"

namespace {

using namespace hubbeam;

constexpr int exit_ok = 0;
constexpr int exit_stopped = 1;
constexpr int exit_bad_input = 2;

/// Values of the `run` options; each is applied only if it was given.
struct RunOptions {
    std::string scene;
    std::string method, order, spline_basis, source, stepper, output;
    int nx = 0, ny = 0;
    double rtol = 0, atol = 0, h0 = 0, t_end = 0, dt_out = 0;
};

/// Declares the `run` options on sub; the help text of each is its documentation.
void add_run_options(CLI::App& sub, RunOptions& o)
{
    sub.add_option("scene", o.scene, "Scene file (TOML; format in README.md, examples in cases/)")->required();
    sub.add_option("--method", o.method, "Discretization (overrides discretization.method)")
        ->check(CLI::IsMember(words<Method>()));
    sub.add_option("--nx", o.nx, "Axial DOF count Nx (overrides discretization.nx)");
    sub.add_option("--ny", o.ny, "Transverse DOF count Ny (overrides discretization.ny)");
    sub.add_option("--order", o.order, "Model order of MODEL.md section 3 (overrides model.order)")
        ->check(CLI::IsMember(words<Order>()));
    sub.add_option("--spline-basis", o.spline_basis,
                   "BSIM transverse basis: paper (eq. 41) or open knots (overrides discretization.spline_basis)")
        ->check(CLI::IsMember(words<SplineBasis>()));
    sub.add_option("--source", o.source, "Generated kernels, hand-assembled matrices, or auto (overrides model.source)")
        ->check(CLI::IsMember(words<ModelSource>()));
    sub.add_option("--stepper", o.stepper, "GSL odeiv2 stepper (overrides solver.stepper)")
        ->check(CLI::IsMember(stepper_names()));
    sub.add_option("--rtol", o.rtol, "Relative tolerance, > 0 (overrides solver.rtol)");
    sub.add_option("--atol", o.atol, "Absolute tolerance, > 0 (overrides solver.atol)");
    sub.add_option("--h0", o.h0, "First trial step in s, > 0 (overrides solver.h0)");
    sub.add_option("--t-end", o.t_end, "End time in s, > 0 (overrides output.t_end)");
    sub.add_option("--dt-out", o.dt_out, "Output interval in s: rows at exact multiples (overrides output.dt_out)");
    sub.add_option("-o,--output", o.output,
                   "CSV file to write (overrides output.file; default: the scene's name with .csv, in the current "
                   "directory)");
}

/// Applies the options that were given to scene.
void apply_overrides(const CLI::App& sub, const RunOptions& o, Scene& scene)
{
    const auto given = [&](const char* name) { return sub.get_option(name)->count() > 0; };
    VariantKey& key = scene.variant;
    if (given("--method")) parse(o.method, key.method);
    if (given("--nx")) key.nx = o.nx;
    if (given("--ny")) key.ny = o.ny;
    if (given("--order")) parse(o.order, key.order);
    if (given("--spline-basis")) parse(o.spline_basis, key.spline);
    if (given("--source")) parse(o.source, scene.source);
    if (given("--stepper")) scene.solver.stepper = o.stepper;
    if (given("--rtol")) scene.solver.rtol = o.rtol;
    if (given("--atol")) scene.solver.atol = o.atol;
    if (given("--h0")) scene.solver.h0 = o.h0;
    if (given("--t-end")) scene.output.t_end = o.t_end;
    if (given("--dt-out")) scene.output.dt_out = o.dt_out;
    if (given("-o")) scene.output.file = o.output;
    if (scene.output.file.empty()) scene.output.file = std::filesystem::path(scene.path).stem().string() + ".csv";
}

/// validate() after the overrides; its message names the scene key, which becomes the option that set it
/// ("--ny: FEM needs an even ny ...") or is prefixed by an option it conflicts with ("--method: discretization.ny:
/// ..."); a value from the file alone keeps the file's name.
void validate_overridden(const CLI::App& sub, const Scene& scene)
{
    try {
        validate(scene);
    } catch (const SceneError& e) {
        static const std::vector<std::pair<std::string, std::vector<const char*>>> options_of = {
            {"discretization.ny", {"--ny", "--method", "--spline-basis"}},
            {"discretization.nx", {"--nx", "--method"}},
            {"solver.stepper", {"--stepper"}},
            {"solver.rtol", {"--rtol"}},
            {"solver.atol", {"--atol"}},
            {"solver.h0", {"--h0"}},
            {"output.t_end", {"--t-end"}},
            {"output.dt_out", {"--dt-out", "--t-end"}},
        };
        const std::string message = e.what();
        const std::string prefix = scene.path + ": ";
        if (message.rfind(prefix, 0) != 0) throw;
        const std::string rest = message.substr(prefix.size());
        const std::size_t colon = rest.find(": ");
        if (colon == std::string::npos) throw;
        for (const auto& [key, options] : options_of) {
            if (rest.compare(0, colon, key) != 0) continue;
            for (const char* option : options) {
                if (sub.get_option(option)->count() == 0) continue;
                // The key's own option replaces it; a conflicting option keeps it: "--method: discretization.ny: ...".
                if (option == options.front()) throw SceneError(option + rest.substr(colon));
                throw SceneError(option + (": " + rest));
            }
        }
        throw;
    }
}

/// hubbeam run: returns the exit code.
int run(const CLI::App& sub, const RunOptions& o)
{
    Scene scene;
    try {
        scene = load_scene(o.scene);
        apply_overrides(sub, o, scene);
        validate_overridden(sub, scene);
    } catch (const SceneError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }

    std::unique_ptr<CsvWriter> csv;
    try {
        csv = std::make_unique<CsvWriter>(scene.output.file);
    } catch (const std::runtime_error& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }

    RunSummary summary;
    try {
        summary = simulate(scene, csv->sink());
    } catch (const std::invalid_argument& e) {
        // Model selection refused the variant (e.g. an order this build cannot run): nothing was computed.
        const bool empty = csv->rows() == 0;
        const std::string path = csv->path();
        csv.reset();
        std::error_code ignored;
        if (empty && std::filesystem::is_regular_file(path, ignored)) std::filesystem::remove(path, ignored);
        std::cerr << scene.path << ": " << e.what() << "\n";
        return empty ? exit_bad_input : exit_stopped;
    }

    std::cout << format_summary(summary, scene);
    if (!csv->ok()) {
        std::cerr << csv->path() << ": write failed after " << csv->rows() << " rows\n";
        return exit_stopped;
    }
    if (!summary.completed) {
        std::cerr << "hubbeam: stopped at t = " << summary.t_reached << " s: " << summary.failure << " (" << csv->rows()
                  << " rows kept in " << csv->path() << ")\n";
        return exit_stopped;
    }
    return exit_ok;
}

/// hubbeam variants: the variants generated into this build, one name a line.
int list_variants()
{
    for (const std::string& name : generated_variant_names()) std::cout << name << "\n";
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "hubbeam: rotating flexible hub-beam simulator (equations derived by GiNaC, integrated by GSL).\n"
        "Exit codes: 0 success, 1 simulation stopped early (rows so far kept), 2 bad input."};
    app.require_subcommand(1);

    RunOptions options;
    CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scene file and write its response as CSV");
    run_cmd->footer(
        "Options override the scene's keys. Exit codes: 0 success, 1 simulation stopped early (rows so "
        "far kept), 2 bad input (one line on stderr, nothing computed).");
    add_run_options(*run_cmd, options);
    CLI::App* variants_cmd = app.add_subcommand("variants", "List the variants generated into this build");

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
    } catch (const std::exception& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_stopped;
    }
    return exit_bad_input;
}
