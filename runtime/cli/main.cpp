// hubbeam: the command line. A thin layer over the library: each command declares its options (CLI11, so that
// --help comes from the same definitions) and does its work in its own file, cmd_NAME.cpp; this file runs the one
// given.
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
#include <exception>
#include <iostream>
#include <vector>

#include "command.hpp"

int main(int argc, char** argv)
{
    using namespace hubbeam::cli;
    CLI::App app{
        "hubbeam: rotating flexible hub-beam simulator (equations derived by GiNaC, integrated by GSL).\n"
        "Exit codes: 0 success, 1 simulation stopped early (rows so far kept), 2 bad input, 130/143 interrupted\n"
        "by SIGINT/SIGTERM (rows so far kept)."};
    app.require_subcommand(1);
    const std::vector<Command> commands = {
        add_run_command(app),   add_variants_command(app),  add_bench_command(app),
        add_stress_command(app), add_modes_command(app),     add_linearize_command(app),
        add_sweep_command(app), add_kernels_command(app),   add_plot_command(app),
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_bad_input;
    }
    try {
        for (const Command& c : commands)
            if (c.sub->parsed()) return c.run();
    } catch (const std::exception& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_stopped;
    }
    return exit_bad_input;
}
