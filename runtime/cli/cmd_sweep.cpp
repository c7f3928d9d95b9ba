// hubbeam sweep: hands its arguments to the Python package's sweep, which runs a scene over parameters on Dask.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <hubbeam/install_layout.hpp>
#include <unistd.h>

#include "command.hpp"

namespace hubbeam::cli {

namespace {

/// hubbeam sweep: hands the arguments to the Python package's sweep (it runs on Dask), replacing this process;
/// returns only if that cannot start.
int sweep(const std::vector<std::string>& args)
{
#ifdef HUBBEAM_PYTHON_EXECUTABLE
    // Isolated (-I): neither the current folder, nor PYTHONPATH or any other PYTHON* variable, nor the user's
    // site-packages reach the path, so a csv.py or a hubbeam/ folder where the sweep starts is never imported (and
    // Python's own children, such as multiprocessing's helpers, inherit -I). The package of this build or
    // installation, found relative to this program, is put first on the path by the bootstrap below, which gets it as
    // its first argument (empty: the package installed in Python's own path).
    static constexpr const char* bootstrap =
        "import sys\n"
        "if sys.argv[1]: sys.path.insert(0, sys.argv[1])\n"
        "from hubbeam.sweeps import main\n"
        "sys.exit(main(sys.argv[2:]))\n";
    std::vector<std::string> words = {HUBBEAM_PYTHON_EXECUTABLE, "-I", "-c", bootstrap,
                                      python_package_parent().string()};
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
    Subcommand sweep_cmd(app, "sweep",
                         "Parameter sweep on Dask: SWEEP.toml [-o FILE] [--scheduler tls://HOST:PORT --tls-ca-file CA "
                         "--tls-cert CERT --tls-key KEY] [--workers N] [--dashboard] [--no-resume] (docs/python.md)");
    sweep_cmd.pass_arguments_through();  // hubbeam sweep --help describes them
    return {sweep_cmd.app(), [sweep_cmd] { return sweep(sweep_cmd.remaining()); }};
}

}  // namespace hubbeam::cli
