// On-demand variants: hubbeam-gen and the C++ compiler run as child processes (argument vectors, no shell) in their
// own process group, each into a private work folder inside the cache; the finished object is recorded with its
// SHA-256 in a manifest beside it, and no object is opened with dlopen before its file matches that record. Objects
// stay loaded for the life of the process. docs/security.md, "The on-demand cache", states the rules.
#include <hubbeam/on_demand.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>
#include <thread>

#include <dlfcn.h>
#include <fcntl.h>
#include <hubbeam/install_layout.hpp>
#include <pwd.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "generated_abi.h"
#include "on_demand/sha256.hpp"
#include "on_demand/variant_rows.hpp"
#include "words.hpp"

extern char** environ;

#ifndef HUBBEAM_GENERATOR_VERSION
#error "HUBBEAM_GENERATOR_VERSION must name the generator's version (set by CMakeLists.txt)"
#endif

namespace hubbeam {

namespace fs = std::filesystem;

namespace {

/// Flags for on-demand objects: the same language as the build, optimised, position-independent.
/// (Hidden symbols: the object exports its entry point only, so two objects never bind to each other's kernels.)
const std::vector<std::string> compile_flags = {"-std=c++20", "-O2", "-fPIC", "-shared", "-fvisibility=hidden"};

std::string env(const char* name)
{
    const char* v = std::getenv(name);
    return v != nullptr ? v : "";
}

/// An executable file named by path, or found on $PATH when the name has no '/'; empty if none.
std::string find_program(const std::string& name)
{
    if (name.empty()) return {};
    const auto runnable = [](const fs::path& p) { return ::access(p.c_str(), X_OK) == 0 && !fs::is_directory(p); };
    if (name.find('/') != std::string::npos) return runnable(name) ? name : std::string();
    std::stringstream path(env("PATH"));
    for (std::string dir; std::getline(path, dir, ':');)
        if (!dir.empty() && runnable(fs::path(dir) / name)) return (fs::path(dir) / name).string();
    return {};
}

/// The words of a command held in one variable ("ccache g++" is two).
std::vector<std::string> split_words(const std::string& s)
{
    std::vector<std::string> words;
    std::stringstream in(s);
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

/// The options a user adds to every on-demand compile ($HUBBEAM_CXXFLAGS), after hubbeam's own so that an -O or
/// -march of theirs wins. Each word must be an option, its value joined to it (-march=native, -DNAME=1): a bare word
/// would be compiled in as a second source, and -o, -c, -E, -S would leave no object where the cache expects one.
std::vector<std::string> user_compile_flags()
{
    std::vector<std::string> words = split_words(env("HUBBEAM_CXXFLAGS"));
    for (const std::string& w : words)
        if (w.size() < 2 || w[0] != '-' || w == "-c" || w == "-E" || w == "-S" || w.rfind("-o", 0) == 0)
            throw CompileError("HUBBEAM_CXXFLAGS: expected compiler options other than -o, -c, -E, -S, each with "
                               "its value joined to it (for example -O1 or -march=native), got '" + w + "'");
    return words;
}

/// The compiler command as words; the first is resolved to a file, empty if it is not found.
std::vector<std::string> compiler_command()
{
    std::vector<std::string> words = split_words(env("CXX"));
    if (words.empty()) {
        words = {HUBBEAM_CXX};
        if (find_program(words[0]).empty()) words = {"c++"};
    }
    words[0] = find_program(words[0]);
    return words;
}

/// hubbeam-gen: $HUBBEAM_GEN, else the one of this build or installation (install_layout.hpp); empty if none, and
/// then, for a $HUBBEAM_GEN that is not run, why in *why. $HUBBEAM_GEN passes the checks of the built-in one
/// (untrusted_program): a generator writes code that hubbeam loads, so it must be as safe as hubbeam itself.
std::string generator_path(std::string* why = nullptr)
{
    const std::string g = env("HUBBEAM_GEN");
    if (g.empty()) return find_generator();
    const std::string found = find_program(g);
    const std::string problem = found.empty() ? std::string() : untrusted_program(found);
    if (problem.empty()) return found;
    if (why != nullptr)
        *why = "HUBBEAM_GEN: " + problem + ": hubbeam runs a generator only if it belongs to root or to you and " +
               "nobody else can change it";
    return {};
}

// --- the cache's folders and files: private to the user, never followed through a symbolic link -------------------

/// A refusal that names the path and what to do; it ends the command with exit code 2.
[[noreturn]] void refuse(const std::string& why) { throw CompileError(why); }

std::string octal_mode(mode_t mode)
{
    char s[8];
    std::snprintf(s, sizeof s, "%04o", static_cast<unsigned>(mode & 07777));
    return s;
}

std::string user_name(uid_t uid)
{
    const passwd* pw = ::getpwuid(uid);
    return (pw != nullptr ? std::string(pw->pw_name) + ", " : std::string()) + "uid " + std::to_string(uid);
}

/// Refuses a cache entry (folder or file) that another user could have written: not owned by this process's
/// effective user, or writable by group or others. what says which entry, e.g. "the variant cache folder".
void check_private(const fs::path& path, const struct stat& st, const std::string& what)
{
    if (st.st_uid != ::geteuid())
        refuse(what + " " + path.string() + " belongs to " + user_name(st.st_uid) + ", not to you (" +
               user_name(::geteuid()) + "): hubbeam loads only code it compiled itself; remove it, or set " +
               "HUBBEAM_CACHE_DIR to a folder of your own");
    if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0)
        refuse(what + " " + path.string() + " is writable by other users (mode " + octal_mode(st.st_mode) +
               "): run chmod go-w " + path.string() + ", or set HUBBEAM_CACHE_DIR to a private folder");
}

/// Checks a cache folder that exists: a real folder (not a symbolic link), private to the user. Returns false if it
/// does not exist.
bool check_cache_folder(const fs::path& dir)
{
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0) {
        if (errno == ENOENT) return false;
        refuse("cannot read the variant cache folder " + dir.string() + ": " + std::strerror(errno));
    }
    if (S_ISLNK(st.st_mode))
        refuse("the variant cache folder " + dir.string() + " is a symbolic link, which hubbeam does not follow: " +
               "set HUBBEAM_CACHE_DIR to the folder it points to");
    if (!S_ISDIR(st.st_mode))
        refuse("the variant cache folder " + dir.string() + " is not a folder: remove it, or set HUBBEAM_CACHE_DIR");
    check_private(dir, st, "the variant cache folder");
    return true;
}

/// Checks the folders above the cache's root: another user who can rename entries of one of them could put a folder
/// of theirs in the cache's place, unless it is sticky (as /tmp is).
void check_ancestors(const fs::path& root)
{
    for (fs::path p = root.parent_path(); !p.empty(); p = p.parent_path()) {
        struct stat st {};
        if (::stat(p.c_str(), &st) == 0) {
            if (st.st_uid != 0 && st.st_uid != ::geteuid())
                refuse("the folder " + p.string() + " above the variant cache " + root.string() + " belongs to " +
                       user_name(st.st_uid) + ", who could replace the cache: set HUBBEAM_CACHE_DIR to a folder " +
                       "in one of your own");
            if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 && (st.st_mode & S_ISVTX) == 0)
                refuse("the folder " + p.string() + " above the variant cache " + root.string() +
                       " is writable by other users (mode " + octal_mode(st.st_mode) + ") without the sticky bit: " +
                       "set HUBBEAM_CACHE_DIR to a folder in a private one");
        }
        if (p == p.root_path()) break;
    }
}

/// Creates dir and its missing parents, each private (0700), then checks dir.
void make_private_folders(const fs::path& dir)
{
    std::vector<fs::path> missing;
    struct stat st {};
    for (fs::path p = dir; !p.empty() && ::lstat(p.c_str(), &st) != 0 && errno == ENOENT; p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.root_path()) break;
    }
    std::reverse(missing.begin(), missing.end());
    for (const fs::path& p : missing)
        if (::mkdir(p.c_str(), 0700) != 0 && errno != EEXIST)
            refuse("cannot create the variant cache folder " + p.string() + ": " + std::strerror(errno) +
                   " (set HUBBEAM_CACHE_DIR to a folder you can write)");
    check_cache_folder(dir);
}

/// The root and this version's folder, checked: false if the version's folder does not exist yet.
bool checked_cache_dir(fs::path& dir)
{
    const fs::path root = variant_cache_root();
    dir = variant_cache_dir();
    check_ancestors(root);
    if (!check_cache_folder(root)) return false;
    return check_cache_folder(dir);
}

/// A file descriptor closed on every way out.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    ~Fd()
    {
        if (fd >= 0) ::close(fd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
};

/// Opens a cache file for reading without following a symbolic link or blocking on a FIFO, and checks that it is a
/// private regular file. Returns -1 if it does not exist.
int open_cache_file(const fs::path& path, const std::string& what, struct stat& st)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return -1;
        if (errno == ELOOP)
            refuse(what + " " + path.string() + " is a symbolic link, which hubbeam does not load: remove it");
        refuse("cannot open " + what + " " + path.string() + ": " + std::strerror(errno));
    }
    Fd guard(fd);
    if (::fstat(fd, &st) != 0) refuse("cannot read " + what + " " + path.string() + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) refuse(what + " " + path.string() + " is not a regular file: remove it");
    check_private(path, st, what);
    guard.fd = -1;
    return fd;
}

/// SHA-256 of everything readable from fd, and how many bytes that was.
std::string digest(int fd, std::uint64_t& size)
{
    Sha256 sha;
    size = 0;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return {};
        if (n == 0) break;
        sha.add(buffer, static_cast<std::size_t>(n));
        size += static_cast<std::uint64_t>(n);
    }
    return sha.hex();
}

fs::path object_path(const fs::path& dir, const VariantKey& key) { return dir / (key.name() + ".so"); }
/// The record of an object: "sha256 HEX size N", written when this user's hubbeam compiled it.
fs::path manifest_path(const fs::path& object) { return object.string() + ".sha256"; }

std::string manifest_text(const std::string& hex, std::uint64_t size)
{
    return "sha256 " + hex + " size " + std::to_string(size) + "\n";
}

/// Writes text to path atomically: a private temporary file beside it, written and synced, renamed over it.
void write_atomically(const fs::path& path, const std::string& text)
{
    std::string temp = path.string() + ".tmp-XXXXXX";
    const int fd = ::mkostemp(temp.data(), O_CLOEXEC);  // 0600
    if (fd < 0) refuse("cannot write " + path.string() + ": " + std::strerror(errno));
    bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
    ok = ::close(fd) == 0 && ok;
    if (!ok || ::rename(temp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        ::unlink(temp.c_str());
        refuse("cannot write " + path.string() + ": " + std::strerror(e));
    }
}

/// Loaded objects by variant name: dlopen once per process, never closed (their kernels may be in use).
struct Loaded {
    std::mutex lock;
    std::map<std::string, const generated::Variant*> variants;
};
Loaded& loaded()
{
    static Loaded l;
    return l;
}

/// The row of an object that was verified (fd is open on it): loaded, and checked to be key's of this interface
/// version before any kernel is called. Throws CompileError.
const generated::Variant* open_verified(const VariantKey& key, const fs::path& object, int fd)
{
    // By path: glibc knows loaded objects by name, so a /proc/self/fd/N name would return whichever object had that
    // descriptor number before. The file loaded must still be the one verified (only this user can replace it, in a
    // folder private to them; the check makes a race with another process of theirs visible).
    void* handle = ::dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) refuse("cannot load " + object.string() + ": " + ::dlerror() + "; remove it and run again");
    struct stat verified {}, now {};
    if (::fstat(fd, &verified) != 0 || ::stat(object.c_str(), &now) != 0 || verified.st_dev != now.st_dev ||
        verified.st_ino != now.st_ino)
        refuse(object.string() + " was replaced while it was loaded: run again");
    using Entry = const generated::Variant* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "hubbeam_variant"));
    const generated::Variant* v = entry != nullptr ? entry() : nullptr;
    if (v == nullptr) refuse(object.string() + " has no hubbeam variant: delete it and hubbeam compiles it again");
    if (const std::string why = row_problem(*v, key); !why.empty())
        refuse(object.string() + " " + why + ": delete " + object.string() + " and hubbeam compiles it again");
    return v;
}

/// Why the cached object of key cannot be loaded as it is (stale == true: recompiling it fixes that).
struct CacheMiss {
    bool stale = false;
    std::string why;
};

/// key's object from the checked folder dir if its file matches its manifest; nullptr (and why) if not. Must be
/// called with loaded().lock held.
const generated::Variant* load_verified(const VariantKey& key, const fs::path& dir, CacheMiss* miss)
{
    const fs::path object = object_path(dir, key), manifest = manifest_path(object);
    struct stat st {};
    const int fd = open_cache_file(object, "the cached object", st);
    if (fd < 0) return nullptr;
    const Fd object_fd(fd);
    std::uint64_t size = 0;
    const std::string hex = digest(fd, size);
    std::string recorded;
    struct stat mst {};
    if (const int mfd = open_cache_file(manifest, "the checksum record", mst); mfd >= 0) {
        const Fd manifest_fd(mfd);
        char text[256];
        const ssize_t n = ::read(mfd, text, sizeof text - 1);
        if (n > 0) recorded.assign(text, static_cast<std::size_t>(n));
    }
    if (hex.empty() || static_cast<std::uint64_t>(st.st_size) != size || recorded != manifest_text(hex, size)) {
        if (miss != nullptr)
            *miss = {true, object.string() + (recorded.empty() ? " has no checksum record"
                                                               : " does not match the checksum recorded when it was "
                                                                 "compiled (cut short or changed)")};
        return nullptr;
    }
    return open_verified(key, object, fd);
}

// --- running the generator and the compiler ------------------------------------------------------------------------

/// The signal that asked hubbeam to stop while a tool ran (0: none).
std::atomic<int> tool_stop_signal{0};
extern "C" void note_tool_stop(int sig) { tool_stop_signal = sig; }

/// While a compilation runs, SIGINT, SIGTERM and SIGHUP are noted instead of ending hubbeam at once, so that the
/// tools' process group is killed and the work folder removed first; when the last compilation ends, the earlier
/// handlers come back and a noted signal is raised again (its default action then ends hubbeam as it would have).
class StopSignalsNoted {
public:
    StopSignalsNoted()
    {
        const std::lock_guard guard(mutex_);
        if (depth_++ > 0) return;
        tool_stop_signal = 0;
        struct sigaction a {};
        a.sa_handler = note_tool_stop;
        sigemptyset(&a.sa_mask);
        for (std::size_t i = 0; i < std::size(signals_); ++i) ::sigaction(signals_[i], &a, &old_[i]);
    }
    ~StopSignalsNoted()
    {
        const std::lock_guard guard(mutex_);
        if (--depth_ > 0) return;
        for (std::size_t i = 0; i < std::size(signals_); ++i) ::sigaction(signals_[i], &old_[i], nullptr);
        if (const int sig = tool_stop_signal.exchange(0); sig != 0) ::raise(sig);
    }
    StopSignalsNoted(const StopSignalsNoted&) = delete;
    StopSignalsNoted& operator=(const StopSignalsNoted&) = delete;

private:
    static constexpr int signals_[3] = {SIGINT, SIGTERM, SIGHUP};
    static inline std::mutex mutex_;
    static inline int depth_ = 0;
    static inline struct sigaction old_[3];
};

/// How a tool ended.
struct ToolResult {
    int status = -1;        // exit status; -1 if it could not start or died by a signal
    bool timed_out = false;
    int stopped_by = 0;     // the signal that asked hubbeam to stop, if that ended it
};

/// The child side of run_tool, between fork and exec: only async-signal-safe calls. The child becomes a process
/// group's leader and a supervisor that dies with hubbeam: its parent-death signal (even after a SIGKILL of
/// hubbeam) makes it kill its whole group, the tool's own children (cc1plus, as, ld) included.
[[noreturn]] void supervise(pid_t hubbeam, char* const* argv, char* const* envp, int log)
{
    ::setpgid(0, 0);
    sigset_t wait_for;
    sigemptyset(&wait_for);
    sigaddset(&wait_for, SIGTERM);
    sigaddset(&wait_for, SIGCHLD);
    ::sigprocmask(SIG_BLOCK, &wait_for, nullptr);
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    ::sigaction(SIGCHLD, &dfl, nullptr);  // an ignored SIGCHLD would never be seen
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != hubbeam) ::_exit(127);  // hubbeam is already gone
    const pid_t supervisor = ::getpid();
    const pid_t tool = ::fork();
    if (tool == 0) {
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        ::sigaction(SIGTERM, &dfl, nullptr);
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != supervisor) ::_exit(127);
        ::dup2(log, STDOUT_FILENO);
        ::dup2(log, STDERR_FILENO);
        ::execve(argv[0], argv, envp);
        ::_exit(127);
    }
    if (tool < 0) ::_exit(127);
    for (;;) {
        int sig = 0;
        if (::sigwait(&wait_for, &sig) != 0) continue;
        if (sig == SIGTERM) ::kill(0, SIGKILL);  // hubbeam died: the whole group, this process included
        int status = 0;
        if (::waitpid(tool, &status, WNOHANG) == tool)
            ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0));
    }
}

/// Runs argv with stdout and stderr into log, TMPDIR set to work (so that the compiler's temporary files are in the
/// work folder too), for at most limit seconds.
ToolResult run_tool(const std::vector<std::string>& argv, const fs::path& log, const fs::path& work, double limit)
{
    // Everything the child needs is built before fork: it may not allocate.
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> env_strings;
    for (char** e = environ; *e != nullptr; ++e)
        if (std::strncmp(*e, "TMPDIR=", 7) != 0) env_strings.emplace_back(*e);
    env_strings.push_back("TMPDIR=" + work.string());
    std::vector<char*> envp;
    for (std::string& e : env_strings) envp.push_back(e.data());
    envp.push_back(nullptr);
    const Fd log_fd(::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600));
    ToolResult result;
    if (log_fd.fd < 0) return result;

    const pid_t hubbeam = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) supervise(hubbeam, args.data(), envp.data(), log_fd.fd);
    if (pid < 0) return result;
    ::setpgid(pid, pid);  // also here: the group must exist before this side may kill it
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    for (;;) {
        const pid_t r = ::waitpid(pid, &status, WNOHANG);
        if (r == pid) break;
        if (r < 0 && errno != EINTR) return result;
        result.stopped_by = tool_stop_signal;
        result.timed_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limit;
        if (result.stopped_by != 0 || result.timed_out) {
            ::kill(-pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            return result;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// The first line of a tool's log that reports an error (else its first line), for a one-line message.
std::string first_error(const fs::path& log)
{
    std::ifstream in(log);
    std::string line, first;
    while (std::getline(in, line)) {
        if (first.empty() && !line.empty()) first = line;
        if (line.find("error") != std::string::npos) return line;
    }
    return first.empty() ? "no output" : first;
}

/// Seconds a generation or a compilation of key may take: $HUBBEAM_COMPILE_TIMEOUT, else generous for its size (the
/// symbolic work grows with the square of the coordinates, order full's several times over).
double time_limit(const VariantKey& key)
{
    if (const std::string s = env("HUBBEAM_COMPILE_TIMEOUT"); !s.empty()) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0' || !(v > 0))
            refuse("HUBBEAM_COMPILE_TIMEOUT: expected a number of seconds > 0, got '" + s + "'");
        return v;
    }
    const double n = key.nq();
    return (600 + 2 * n * n) * (key.order == Order::full ? 10 : 1);
}

/// Runs one tool of a compilation and turns every way it can fail into one CompileError line.
void run_step(const std::string& doing, const std::vector<std::string>& argv, const fs::path& work, double limit,
              const fs::path& where)
{
    const fs::path log = work / "log.txt";
    const ToolResult r = run_tool(argv, log, work, limit);
    if (r.stopped_by != 0)
        refuse(doing + " was interrupted by signal " + std::to_string(r.stopped_by) + " (cache: " + where.string() + ")");
    if (r.timed_out) {
        char s[32];
        std::snprintf(s, sizeof s, "%g", limit);
        refuse(doing + " was stopped after " + s + " s, the limit for its size: set HUBBEAM_COMPILE_TIMEOUT to " +
               "more seconds if it needs longer (cache: " + where.string() + ")");
    }
    if (r.status != 0)
        refuse(doing + " failed: " + first_error(log) + " (cache: " + where.string() + ")");
}

/// Runs the generator and the compiler for key in work (which must exist); returns the object's path. where names
/// the folder in messages.
fs::path build_object(const VariantKey& key, const fs::path& work, const std::vector<std::string>& generator_options,
                      const fs::path& where)
{
    const std::string name = key.name();
    const double limit = time_limit(key);
    // The generator writes the interface header beside the source, so no other include folder is needed.
    std::vector<std::string> gen = {generator_path(), "--module", "--quiet", "--out", work.string()};
    gen.insert(gen.end(), generator_options.begin(), generator_options.end());
    gen.push_back(name);
    run_step("generating " + name, gen, work, limit, where);
    std::vector<std::string> cc = compiler_command();
    cc.insert(cc.end(), compile_flags.begin(), compile_flags.end());
    const std::vector<std::string> user = user_compile_flags();
    cc.insert(cc.end(), user.begin(), user.end());
    const fs::path object = work / (name + ".so");
    cc.insert(cc.end(), {(work / (name + ".cpp")).string(), "-o", object.string()});
    run_step("compiling " + name, cc, work, limit, where);
    return object;
}

/// Removes a work folder on every way out of compile_variant.
struct WorkFolder {
    fs::path path;
    ~WorkFolder()
    {
        std::error_code ec;
        if (!path.empty()) fs::remove_all(path, ec);
    }
};

/// An exclusive flock() on path, held for the object's life; without a lock file (read-only cache) it holds nothing
/// and compilations may repeat, as they are safe to. The file stays (removing it would let a third process lock a
/// new file while a second still waits on the old one).
class FileLock {
public:
    explicit FileLock(const fs::path& path)
        : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600))
    {
        if (fd_ >= 0)
            while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
            }
    }
    ~FileLock()
    {
        if (fd_ >= 0) ::close(fd_);  // closing releases the lock
    }
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;

private:
    int fd_;
};

std::string work_prefix(const std::string& name) { return "." + name + ".work-"; }

/// Removes the work folders an earlier compilation of name left when it was killed outright (SIGKILL gives no chance
/// to clean up). Called with name's lock held, so no live compilation of name owns one.
void remove_stale_work(const fs::path& dir, const std::string& name)
{
    std::error_code ec;
    const std::string prefix = work_prefix(name);
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.path().filename().string().rfind(prefix, 0) == 0) fs::remove_all(e.path(), ec);
}

}  // namespace

fs::path variant_cache_root()
{
    if (const std::string d = env("HUBBEAM_CACHE_DIR"); !d.empty()) return fs::absolute(d);
    // The XDG base directory rule: a relative XDG_CACHE_HOME is ignored.
    if (const std::string d = env("XDG_CACHE_HOME"); !d.empty() && d[0] == '/') return fs::path(d) / "hubbeam";
    if (const std::string d = env("HOME"); !d.empty() && d[0] == '/') return fs::path(d) / ".cache" / "hubbeam";
    // Never a shared temporary folder: another user could have put objects there.
    refuse("no folder for the variant cache: set HUBBEAM_CACHE_DIR (or HOME) to a folder of your own");
}

std::string on_demand_flags() { return joined(user_compile_flags(), "", " "); }

fs::path variant_cache_dir()
{
    // Objects compiled with other options (another -O, -march=native) are other objects: a folder of their own.
    const std::string options = on_demand_flags();
    if (options.empty()) return variant_cache_root() / generator_version();
    Sha256 h;
    h.add(options);
    return variant_cache_root() / (generator_version() + "-flags-" + h.hex().substr(0, 16));
}

std::string generator_version() { return HUBBEAM_GENERATOR_VERSION; }

std::string on_demand_compiler() { return joined(compiler_command(), "", " "); }

std::string on_demand_problem()
{
    if (compiler_command()[0].empty()) {
        const std::string cxx = env("CXX");
        return cxx.empty() ? "no C++ compiler found (c++ is not on PATH; set CXX)"
                           : "no C++ compiler found (CXX=" + cxx + " is not an executable)";
    }
    if (std::string why; generator_path(&why).empty())
        return why.empty() ? "the generator hubbeam-gen was not found (set HUBBEAM_GEN)" : why;
    return {};
}

const generated::Variant* load_cached_variant(const VariantKey& key)
{
    Loaded& l = loaded();
    const std::lock_guard guard(l.lock);
    if (auto it = l.variants.find(key.name()); it != l.variants.end()) return it->second;
    fs::path dir;
    if (!checked_cache_dir(dir)) return nullptr;
    const generated::Variant* v = load_verified(key, dir, nullptr);
    if (v != nullptr) l.variants[key.name()] = v;
    return v;
}

const generated::Variant* compile_variant(const VariantKey& key, const std::function<void(const std::string&)>& note)
{
    if (const generated::Variant* v = load_cached_variant(key)) return v;  // another run may have made it
    if (const std::string why = on_demand_problem(); !why.empty()) throw CompileError(why);
    const fs::path dir = variant_cache_dir();
    const std::string name = key.name();
    check_ancestors(variant_cache_root());
    make_private_folders(variant_cache_root());
    make_private_folders(dir);
    // One compilation per machine: processes that want the same variant at once (a sweep's workers) wait for the
    // first one's, then load its object. (Threads of one process each take the lock through their own descriptor.)
    const FileLock lock(dir / ("." + name + ".lock"));
    CacheMiss miss;
    {
        Loaded& l = loaded();
        const std::lock_guard guard(l.lock);
        if (auto it = l.variants.find(name); it != l.variants.end()) return it->second;
        if (const generated::Variant* v = load_verified(key, dir, &miss)) return l.variants[name] = v;
    }
    remove_stale_work(dir, name);
    if (note) {
        if (miss.stale) note(miss.why + ": compiling it again");
        note("compiling variant " + name + " on demand into " + dir.string() + " (once per machine)");
    }

    // Declared before the work folder, so that a noted stop signal is raised again only once the folder is gone.
    const StopSignalsNoted signals;
    static std::atomic<int> serial{0};  // two threads of one process get two folders
    const WorkFolder work{dir / (work_prefix(name) + std::to_string(::getpid()) + "-" + std::to_string(serial++))};
    if (::mkdir(work.path.c_str(), 0700) != 0)
        refuse("cannot create " + work.path.string() + ": " + std::strerror(errno));
    const fs::path built = build_object(key, work.path, {}, dir);
    // The checksum of the object as the compiler left it in the private work folder, recorded before the object is
    // moved into place: a reader that finds the new object with the old record (or none) compiles it again.
    const Fd built_fd(::open(built.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
    std::uint64_t size = 0;
    const std::string hex = built_fd.fd >= 0 ? digest(built_fd.fd, size) : std::string();
    if (hex.empty()) refuse("cannot read the compiled object " + built.string());
    const fs::path object = object_path(dir, key);
    write_atomically(manifest_path(object), manifest_text(hex, size));
    // rename() replaces atomically: a reader opens either whole file.
    if (::rename(built.c_str(), object.c_str()) != 0)
        refuse("cannot move " + built.string() + " into the cache: " + std::strerror(errno));
    Loaded& l = loaded();
    const std::lock_guard guard(l.lock);
    const generated::Variant* v = load_verified(key, dir, &miss);
    if (v == nullptr) refuse(miss.why.empty() ? object.string() + " vanished after it was compiled" : miss.why);
    return l.variants[name] = v;
}

const generated::Variant* compile_variant_in(const VariantKey& key, const fs::path& dir,
                                             const std::vector<std::string>& generator_options)
{
    if (const std::string why = on_demand_problem(); !why.empty()) throw CompileError(why);
    fs::create_directories(dir);
    const fs::path object = build_object(key, dir, generator_options, dir);
    const Fd fd(::open(object.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
    if (fd.fd < 0) refuse("cannot open the compiled object " + object.string() + ": " + std::strerror(errno));
    return open_verified(key, object, fd.fd);
}

std::vector<std::string> cached_variant_names()
{
    std::vector<std::string> names;
    std::error_code ec;
    fs::path dir;
    try {
        if (!checked_cache_dir(dir)) return names;
    } catch (const CompileError&) {
        return names;  // nothing of a refused cache is listed (loading from it says why)
    }
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.path().extension() == ".so" && e.path().filename().string()[0] != '.')
            names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace hubbeam
