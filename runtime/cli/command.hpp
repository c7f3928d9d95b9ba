// The command line's shared parts: exit codes, the stop signals, one-line refusals, and the entry of each command
// (one file per command: cmd_run.cpp, cmd_modes.cpp, ...; app.cpp adds them to the app and runs the one given).
#pragma once

#include <csignal>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <hubbeam/on_demand.hpp>
#include <hubbeam/option_lists.hpp>

// CLI11's app and option, declared only: the commands' files reach them through Subcommand and Option below, so that
// CLI11's header, whose inline functions took each file that included it about 7 s to compile, is compiled in app.cpp
// alone (docs/performance.md, "Set-up").
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace hubbeam::cli {

constexpr int exit_ok = 0;
constexpr int exit_stopped = 1;        // the simulation stopped early or cannot be trusted (rows so far kept)
constexpr int exit_bad_input = 2;      // one line on stderr, nothing computed
constexpr int exit_signal_base = 128;  // the shell's convention: 128 + the signal's number (130, 143)
/// The exit codes in one sentence, for hubbeam --help and run --help alike (docs/cli.md's table and README.md list
/// the same codes: tests/docs/test_docs.cpp).
inline constexpr const char* exit_codes_help =
    "Exit codes: 0 done, 1 the simulation stopped early or cannot be trusted (rows so far kept), 2 bad input (one line "
    "on stderr naming the file or option, nothing computed), 129/130/131/143 interrupted by SIGHUP/SIGINT/SIGQUIT/"
    "SIGTERM (rows so far kept).";

/// The failure a run stopped by a stop signal (catch_stop_signals) reports.
inline constexpr const char* interrupted = "interrupted by signal";

/// The signal that asked the command to stop, 0 if none.
int stop_signal();
/// Routes SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGXFSZ to a handler that only records them (the work stops between
/// rows and finishes its files; exit 128 + the signal), except a signal the parent set to be ignored.
void catch_stop_signals();
/// A StopRequest that answers `interrupted` once a stop signal has come.
StopRequest signal_stop();

/// Runs a command's work (its exit code) so that what happens to standard output costs no file: a reader that
/// closes it early (hubbeam modes -o FILE | head) no longer ends the process by SIGPIPE, the work goes on, its
/// files are written whole and put in place, and the code is the work's own (0 when done; the rest of the printed
/// text is dropped). Standard output that cannot be written for another reason (a full disk) is reported on
/// standard error: exit 1 if the work succeeded.
int with_standard_output(const std::function<int()>& work);

/// One option of a command, as its file declares it (CLI11's Option; a default one stands for none).
class Option {
public:
    Option() = default;
    explicit Option(CLI::Option* option) : option_(option) {}
    /// The command refuses to run without it.
    Option& required();
    /// Its value's placeholder in --help (FILE, LIST, N).
    Option& type_name(const std::string& name);
    /// The command refuses it together with other.
    Option& excludes(const Option& other);
    /// Whether the command line gave it (after parsing).
    bool given() const;

private:
    CLI::Option* option_ = nullptr;
};

/// A command on the app: its options, flags and help text (CLI11's subcommand).
class Subcommand {
public:
    Subcommand(CLI::App& app, const std::string& name, const std::string& description);
    /// An option (a positional one if name has no leading dash) whose text goes to value, or to values one by one.
    Option add_option(const std::string& name, std::string& value, const std::string& help);
    Option add_option(const std::string& name, std::vector<std::string>& values, const std::string& help);
    /// A flag that sets value.
    Option add_flag(const std::string& name, bool& value, const std::string& help);
    /// The text at the end of the command's --help.
    void footer(const std::string& text);
    /// Every argument after the command's name goes to the command as it is (remaining()), --help among them.
    void pass_arguments_through();
    /// The arguments the command did not take (after parsing).
    std::vector<std::string> remaining() const;
    CLI::App* app() const { return sub_; }

private:
    CLI::App* sub_;
};

/// Declares key's option on sub, its help text from the key table (with note after it), setting value; returns it.
Option add_key_option(Subcommand& sub, const SceneKey& key, std::string& value, const std::string& note = "");

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

/// A command declared on the app: its subcommand, and its work (the exit code), called once the app has parsed.
struct Command {
    CLI::App* sub;
    std::function<int()> run;
};

Command add_run_command(CLI::App& app);
Command add_variants_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_stress_command(CLI::App& app);
Command add_modes_command(CLI::App& app);
Command add_linearize_command(CLI::App& app);
Command add_sweep_command(CLI::App& app);
Command add_kernels_command(CLI::App& app);
Command add_plot_command(CLI::App& app);
Command add_import_command(CLI::App& app);

/// The command line: adds the command argv names to the app (all of them for --help, --version or a word that names
/// none), parses argv and runs the command; its exit code. version: what --version prints.
int run_command_line(int argc, char** argv, const std::string& version);

}  // namespace hubbeam::cli
