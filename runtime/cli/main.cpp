// hubbeam: the command line. A thin layer over the library: each command declares its options (CLI11, so that
// --help comes from the same definitions) and does its work in its own file, cmd_NAME.cpp; app.cpp runs the one
// given.
//
//   hubbeam run SCENE.toml [--method M] [--nx N] [--ny N] ... [-o FILE]   (options: scene_keys() in scene.cpp)
//   hubbeam variants                                   (built in, cached, and how others run)
//   hubbeam bench SCENE.toml [--methods LIST] [--ny LIST] [--steppers LIST] [--rtols LIST] [-o FILE] [--plot PREFIX]
//   hubbeam modes SCENE.toml [--omega LIST] [--methods LIST] [--ny LIST] [--count N] [-o FILE [--plot PREFIX]]
//   hubbeam linearize SCENE.toml --omega W -o PREFIX
//   hubbeam sweep SWEEP.toml [-o FILE] [--scheduler tls://HOST:PORT --tls-ca-file --tls-cert --tls-key]
//                 [--workers N] [--dashboard] [--no-resume]                                (runtime/python: Dask)
//   hubbeam import FILE -o SCENE.toml                  (a BModes .bmi or ElastoDyn main file into a scene)
//   hubbeam kernels [--ny LIST] [--methods LIST] [--drives LIST] [--orders LIST] [--nx LIST] [--samples N] [-o FILE]
//
// Every file is written through OutputFile (output_file.hpp); outputs are checked against the command's inputs and
// each other before anything is computed. run writes NAME.csv into the current folder unless -o; modes writes a CSV
// only with -o. Exit codes: command.hpp's exit_codes_help.
#include "command.hpp"

#ifndef HUBBEAM_VERSION
#define HUBBEAM_VERSION "dev"
#endif

int main(int argc, char** argv) { return hubbeam::cli::run_command_line(argc, argv, "hubbeam " HUBBEAM_VERSION); }
