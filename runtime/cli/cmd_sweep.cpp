// hubbeam sweep: hands its arguments to the Python package's sweep, which runs a scene over parameters on Dask.
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include "command.hpp"
#include "install_layout.hpp"

namespace hubbeam::cli {

namespace {

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

}  // namespace

Command add_sweep_command(CLI::App& app)
{
    CLI::App* sweep_cmd = app.add_subcommand(
        "sweep", "Parameter sweep on Dask: SWEEP.toml [-o FILE] [--scheduler tls://HOST:PORT --tls-ca-file CA "
                 "--tls-cert CERT --tls-key KEY] [--workers N] [--dashboard] [--no-resume] (docs/python.md)");
    sweep_cmd->prefix_command();  // every argument goes to the sweep (hubbeam sweep --help describes them)
    sweep_cmd->set_help_flag();
    return {sweep_cmd, [sweep_cmd] { return sweep(sweep_cmd->remaining()); }};
}

}  // namespace hubbeam::cli
