// The command line's shared parts: the stop signals and the options declared from the scene key table.
#include "command.hpp"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>

namespace hubbeam::cli {

namespace {

/// The signal that asked the command to stop, 0 if none: the handler only sets it, the work reads it between rows
/// (through the StopRequest), so that files are finished outside the handler.
volatile std::sig_atomic_t stop_signal_number = 0;

/// The stop signals' handler. A second signal while the first is being honoured kills at once (the default
/// action), for a user who does not want to wait for the next row; the temporary file is then left behind (and
/// removed by the next writer of that output). SIGXFSZ never kills: each write beyond the file size limit raises
/// it again, and that write then fails with EFBIG, which the writer reports as it reports a full disk.
extern "C" void on_stop_signal(int sig)
{
    if (sig == SIGXFSZ) {
        if (stop_signal_number == 0) stop_signal_number = sig;
        return;
    }
    if (stop_signal_number != 0) {
        ::signal(sig, SIG_DFL);  // both async-signal-safe; sig is blocked until the handler returns
        ::raise(sig);
        return;
    }
    stop_signal_number = sig;
}

/// SIGPIPE's handler: nothing to do. A write to a pipe without a reader then fails with EPIPE instead of ending
/// the process, which would lose the output files not yet put in place. A handler rather than SIG_IGN: a program
/// hubbeam starts (gnuplot, the compiler, the sweep's Python) gets the default action back at exec.
extern "C" void on_broken_pipe(int) {}

/// Whether standard output is a pipe or socket whose reader has gone (poll's POLLERR or POLLHUP on the writing
/// end), as opposed to a file that failed (a full disk).
bool reader_gone()
{
    pollfd out{};
    out.fd = STDOUT_FILENO;
    out.events = POLLOUT;
    return ::poll(&out, 1, 0) == 1 && (out.revents & (POLLERR | POLLHUP)) != 0;
}

}  // namespace

int with_standard_output(const std::function<int()>& work)
{
    struct sigaction action {};
    action.sa_handler = on_broken_pipe;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    ::sigaction(SIGPIPE, &action, nullptr);
    const int code = work();
    std::cout.flush();
    const bool written = !std::cout.fail() && std::fflush(stdout) == 0 && std::ferror(stdout) == 0;
    if (written || code != exit_ok || reader_gone()) return code;
    std::cerr << "hubbeam: standard output could not be written: the printed text is incomplete\n";
    return exit_stopped;
}

int stop_signal() { return stop_signal_number; }

void catch_stop_signals()
{
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    // SIGHUP (the terminal closed), SIGQUIT (Ctrl-\) and SIGXFSZ (a file size limit) would otherwise end the
    // process at once, losing the rows and leaving the temporary and lock files.
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXFSZ}) {
        struct sigaction previous {};
        // A shell's background job ignores SIGINT, and should go on doing so.
        if (::sigaction(sig, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
        ::sigaction(sig, &action, nullptr);
    }
}

StopRequest signal_stop()
{
    return []() -> const char* { return stop_signal_number != 0 ? interrupted : nullptr; };
}

Option add_key_option(Subcommand& sub, const SceneKey& key, std::string& value, const std::string& note)
{
    static const char* const type_names[] = {"X", "N", "WORD", "FILE", "FILE"};  // by SceneKey::Kind
    // A text key is a file name, or (output.sensitivities) a list of names: the placeholder says which.
    const bool list = key.kind == SceneKey::Kind::text && key.expected.find("separated by commas") != std::string::npos;
    return sub.add_option(key.option, value, std::string("Sets ") + key.name + ": " + key.expected + note)
        .type_name(list ? "LIST" : type_names[static_cast<int>(key.kind)]);
}

}  // namespace hubbeam::cli
