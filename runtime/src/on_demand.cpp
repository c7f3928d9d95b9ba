// On-demand variants: hubbeam-gen and the C++ compiler run as child processes (argument vectors, no shell),
// each into a private work folder inside the cache; the finished object is renamed into place and opened with
// dlopen. Objects stay loaded for the life of the process.
#include "on_demand.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/file.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "generated_abi.h"

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

/// hubbeam-gen: $HUBBEAM_GEN, else next to this executable (an installed or build tree), else the build's own, else
/// the installed one.
std::string generator_path()
{
    if (const std::string g = env("HUBBEAM_GEN"); !g.empty()) return find_program(g);
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        if (const std::string beside = find_program((self.parent_path() / "hubbeam-gen").string()); !beside.empty())
            return beside;
    }
    if (const std::string built = find_program(HUBBEAM_GEN_PATH); !built.empty()) return built;
    return find_program(HUBBEAM_INSTALLED_GEN);  // a library installed from a build tree that is gone
}

/// Where generated_abi.h is: the source tree's model/, else the installed headers.
std::string abi_dir()
{
    std::error_code ec;
    if (fs::exists(fs::path(HUBBEAM_ABI_DIR) / "generated_abi.h", ec)) return HUBBEAM_ABI_DIR;
    return HUBBEAM_INSTALLED_ABI_DIR;
}

/// Runs argv with stdout and stderr into log; returns the exit status (-1 if it could not start or died).
int run_logged(const std::vector<std::string>& argv, const fs::path& log)
{
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = 0;
    const int started = ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (started != 0) return -1;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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

fs::path object_path(const VariantKey& key) { return variant_cache_dir() / (key.name() + ".so"); }

/// Opens a cached object and checks that it holds key's variant; throws CompileError if it does not.
const generated::Variant* open_object(const VariantKey& key, const fs::path& object)
{
    void* handle = ::dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) throw CompileError("cannot load " + object.string() + ": " + ::dlerror());
    using Entry = const generated::Variant* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "hubbeam_variant"));
    const generated::Variant* v = entry != nullptr ? entry() : nullptr;
    if (v == nullptr || key.name() != v->name || v->nq != key.nq())
        throw CompileError(object.string() + " does not hold variant " + key.name() + "; remove it and run again");
    return v;
}

/// Removes a work folder on every way out of compile_variant.
struct WorkFolder {
    fs::path path;
    ~WorkFolder()
    {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

}  // namespace

fs::path variant_cache_root()
{
    if (const std::string d = env("HUBBEAM_CACHE_DIR"); !d.empty()) return d;
    if (const std::string d = env("XDG_CACHE_HOME"); !d.empty()) return fs::path(d) / "hubbeam";
    if (const std::string d = env("HOME"); !d.empty()) return fs::path(d) / ".cache" / "hubbeam";
    return fs::temp_directory_path() / "hubbeam-cache";
}

fs::path variant_cache_dir() { return variant_cache_root() / HUBBEAM_GENERATOR_VERSION; }

std::string on_demand_compiler()
{
    std::string s;
    for (const std::string& w : compiler_command()) s += (s.empty() ? "" : " ") + w;
    return s;
}

std::string on_demand_problem()
{
    if (compiler_command()[0].empty()) {
        const std::string cxx = env("CXX");
        return cxx.empty() ? "no C++ compiler found (c++ is not on PATH; set CXX)"
                           : "no C++ compiler found (CXX=" + cxx + " is not an executable)";
    }
    if (generator_path().empty()) return "the generator hubbeam-gen was not found (set HUBBEAM_GEN)";
    return {};
}

const generated::Variant* load_cached_variant(const VariantKey& key)
{
    Loaded& l = loaded();
    const std::lock_guard guard(l.lock);
    if (auto it = l.variants.find(key.name()); it != l.variants.end()) return it->second;
    const fs::path object = object_path(key);
    if (!fs::exists(object)) return nullptr;
    return l.variants[key.name()] = open_object(key, object);
}

namespace {

/// Runs the generator and the compiler for key in work (which must exist); returns the object's path. where names
/// the folder in messages.
fs::path build_object(const VariantKey& key, const fs::path& work, const std::vector<std::string>& generator_options,
                      const fs::path& where)
{
    const std::string name = key.name();
    const fs::path log = work / "log.txt";
    std::vector<std::string> gen = {generator_path(), "--module", "--quiet", "--out", work.string()};
    gen.insert(gen.end(), generator_options.begin(), generator_options.end());
    gen.push_back(name);
    if (run_logged(gen, log) != 0)
        throw CompileError("generating " + name + " failed: " + first_error(log) + " (cache: " + where.string() + ")");
    std::vector<std::string> cc = compiler_command();
    cc.insert(cc.end(), compile_flags.begin(), compile_flags.end());
    const fs::path object = work / (name + ".so");
    cc.insert(cc.end(), {"-I", abi_dir(), (work / (name + ".cpp")).string(), "-o", object.string()});
    if (run_logged(cc, log) != 0)
        throw CompileError("compiling " + name + " failed: " + first_error(log) + " (cache: " + where.string() + ")");
    return object;
}

}  // namespace

namespace {

/// An exclusive flock() on path, held for the object's life; without a lock file (read-only cache) it holds nothing
/// and compilations may repeat, as they are safe to.
class FileLock {
public:
    explicit FileLock(const fs::path& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644))
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

}  // namespace

const generated::Variant* compile_variant(const VariantKey& key, const std::function<void(const std::string&)>& note)
{
    if (const generated::Variant* v = load_cached_variant(key)) return v;  // another run may have made it
    if (const std::string why = on_demand_problem(); !why.empty()) throw CompileError(why);
    const fs::path dir = variant_cache_dir();
    const std::string name = key.name();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw CompileError("cannot create the variant cache " + dir.string() + ": " + ec.message());
    // One compilation per machine: processes that want the same variant at once (a sweep's workers) wait for the
    // first one's, then load its object. (Threads of one process each take the lock through their own descriptor.)
    const FileLock lock(dir / ("." + name + ".lock"));
    if (const generated::Variant* v = load_cached_variant(key)) return v;
    if (note) note("compiling variant " + name + " on demand into " + dir.string() + " (once per machine)");

    static std::atomic<int> serial{0};  // two threads of one process get two folders
    const WorkFolder work{dir / ("." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(serial++))};
    fs::remove_all(work.path, ec);
    fs::create_directories(work.path, ec);
    if (ec) throw CompileError("cannot create " + work.path.string() + ": " + ec.message());
    const fs::path object = build_object(key, work.path, {}, dir);
    // rename() replaces atomically: a racing run that finished first is overwritten by an equal object, and a
    // reader opens either whole file.
    fs::rename(object, object_path(key), ec);
    if (ec) throw CompileError("cannot move " + object.string() + " into the cache: " + ec.message());
    return load_cached_variant(key);
}

const generated::Variant* compile_variant_in(const VariantKey& key, const fs::path& dir,
                                             const std::vector<std::string>& generator_options)
{
    if (const std::string why = on_demand_problem(); !why.empty()) throw CompileError(why);
    fs::create_directories(dir);
    return open_object(key, build_object(key, dir, generator_options, dir));
}

std::vector<std::string> cached_variant_names()
{
    std::vector<std::string> names;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(variant_cache_dir(), ec))
        if (e.path().extension() == ".so" && e.path().filename().string()[0] != '.')
            names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace hubbeam
