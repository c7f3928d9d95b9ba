// OutputFile and the checks of a command's outputs: file identity, file type, the lock against a second writer.
#include <hubbeam/output_file.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hubbeam/config.hpp>
#include <hubbeam/scene.hpp>  // printable
#include <hubbeam/printable.hpp>

namespace hubbeam {

namespace {

std::string kind_of(mode_t mode)
{
    if (S_ISREG(mode)) return {};
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

/// A file's place for comparisons: its device and inode, or its folder's and its name while it does not exist.
struct Identity {
    bool known = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string name;  // empty for an existing file
};

Identity identify(const std::string& path)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) return {true, st.st_dev, st.st_ino, {}};
    if (errno != ENOENT) return {};
    // The kernel resolves DIR as open() will (x/.. through x, links): so the folder, not the spelling, is compared.
    const std::filesystem::path p(path);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return {};
    return {true, st.st_dev, st.st_ino, p.filename().string()};
}

std::string quoted(const std::string& path) { return "\"" + printable(path, 400) + "\""; }

std::runtime_error cannot_open(const std::string& path, int error, const std::string& detail = {})
{
    return std::runtime_error(printable(path, 400) + ": cannot open for writing: " + std::strerror(error) + detail);
}

/// Why path may not be replaced although it is a regular file or a new name, or empty: a symbolic link (in a folder
/// others may write, such as /tmp, an attacker's link would make hubbeam replace a file of the attacker's choosing,
/// with hubbeam's rights), or a file its owner made read-only (the owner's way of saying "keep this").
std::string protected_output(const std::string& path)
{
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return {};
    if (S_ISLNK(st.st_mode))
        return printable(path, 400) + " is a symbolic link: hubbeam does not write through a link; name the file " +
               "itself or choose another output";
    if (S_ISREG(st.st_mode) && (st.st_mode & S_IWUSR) == 0) {
        char mode[8];
        std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
        return printable(path, 400) + " is read-only (mode " + mode + "): hubbeam does not replace a file you " +
               "protected; chmod u+w it or choose another output";
    }
    return {};
}

/// Whether name is a temporary file OutputFile makes for `target`: .TARGET.tmp-PID or .TARGET.tmp-PID-N; pid set.
bool temp_name_of(const std::string& name, const std::string& target, long& pid)
{
    std::string stem = ".";  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + string
    stem += target;
    stem += ".tmp-";
    if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) return false;
    const std::string rest = name.substr(stem.size());
    const std::size_t dash = rest.find('-');
    const std::string digits = rest.substr(0, dash);
    const auto number = [](const std::string& t, std::size_t most) {
        return !t.empty() && t.size() <= most && t.find_first_not_of("0123456789") == std::string::npos;
    };
    if (!number(digits, 9)) return false;
    if (dash != std::string::npos && !number(rest.substr(dash + 1), 3)) return false;
    pid = std::stol(digits);
    return pid > 0;
}

}  // namespace

std::string not_a_regular_file(const std::string& path)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return {};
    return kind_of(st.st_mode);
}

bool same_file(const std::string& a, const std::string& b)
{
    const Identity x = identify(a), y = identify(b);
    return x.known && y.known && x.dev == y.dev && x.ino == y.ino && x.name == y.name;
}

std::vector<NamedPath> scene_inputs(const Scene& scene)
{
    // The key table's file keys say what a scene reads (scene.hpp's scene_files fills Scene::tables from them): a
    // file held under any other name would be one no writer knows to leave alone.
    std::vector<NamedPath> inputs = {{scene.path, "the scene itself"}};
    const std::vector<const SceneKey*> keys = file_keys();
    for (const auto& [key, file] : scene.tables) {
        if (std::none_of(keys.begin(), keys.end(), [&](const SceneKey* k) { return key == k->name; }))
            throw std::logic_error("the scene read " + key + ", which the key table does not name as a file key");
        inputs.push_back({file, "the scene's " + key});
    }
    return inputs;
}

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs)
{
    for (std::size_t k = 0; k < outputs.size(); ++k) {
        const NamedPath& o = outputs[k];
        if (o.path.empty()) continue;
        // The one check of text handed on (printable.hpp), for every writer: a name with a newline becomes a line
        // of its own in a gnuplot script (one that starts with '!' runs in the shell), and a name in a message or a
        // listing must show what it is.
        check_handed_text<OutputRefused>(o.name, o.path, "a file name");
        if (const std::string kind = not_a_regular_file(o.path); !kind.empty())
            throw OutputRefused(o.name + ": expected a regular file or the name of a new one, got " + quoted(o.path) +
                                ", " + kind);
        const std::filesystem::path p(o.path);
        if (const std::string name = p.filename().string(); name.empty() || name == "." || name == "..")
            throw OutputRefused(o.name + ": expected a file name, got " + quoted(o.path));
        if (const std::string why = protected_output(o.path); !why.empty()) throw OutputRefused(o.name + ": " + why);
        if (struct stat st {}; ::stat(o.path.c_str(), &st) != 0) {
            // A new file: its folder must exist (checked now, not after the computing).
            int error = errno;
            const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
            if (error == ENOENT) error = ::stat(dir.c_str(), &st) != 0 ? errno : S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
            if (error != 0)
                throw OutputRefused(printable(o.path, 400) + ": cannot open for writing: " + std::strerror(error));
        }
        for (const NamedPath& i : inputs)
            if (!i.path.empty() && same_file(o.path, i.path))
                throw OutputRefused(o.name + ": expected a file other than " + i.name + ", got " + quoted(o.path));
        for (std::size_t j = 0; j < k; ++j)
            if (!outputs[j].path.empty() && same_file(o.path, outputs[j].path))
                throw OutputRefused(o.name + ": expected a file other than " + outputs[j].name + "'s " +
                                    quoted(outputs[j].path) + ", got " + quoted(o.path));
    }
}

OutputFile::OutputFile(const std::string& path, const std::string& temp) : path_(path)
{
    resolve_target();
    const std::filesystem::path target(path_);
    const std::string name = target.filename().string();
    if (name.empty() || name == "." || name == "..") throw cannot_open(path_, EISDIR);
    const std::filesystem::path dir = target.parent_path();

    take_lock(dir, name);
    create_temp(dir, name, temp);
    // The replacement keeps the permissions of the file it replaces (a new file gets the umask's).
    if (mode_ >= 0) (void)::fchmod(fd_, static_cast<mode_t>(mode_));
}

void OutputFile::resolve_target()
{
    struct stat st {};
    const bool exists = ::stat(path_.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode))
        // Never opened: open() on a FIFO blocks until a reader comes, and renaming over a device replaces the node.
        throw OutputRefused(printable(path_, 400) + ": expected a regular file or the name of a new one, got " +
                            kind_of(st.st_mode));
    if (const std::string why = protected_output(path_); !why.empty()) throw OutputRefused(why);
    if (exists) mode_ = static_cast<int>(st.st_mode & 07777);
}

void OutputFile::take_lock(const std::filesystem::path& dir, const std::string& name)
{
    // The lock first: a second writer is refused before it creates anything. The lock file is removed when
    // released, so after taking the lock it must still be the file at that path (else its holder removed it
    // between this open and this flock, and the lock is taken again on the new one).
    // A lock file that was there already is a killed writer's (a writer removes its own as it finishes), and only
    // then may its temporary files be left: the folder is read for them then alone, not at every write (a folder of
    // 600 files cost a tenth of a 5 ms run, twice, and a sweep's folder grows by a file a point).
    lock_ = (dir / ("." + name + ".lock")).string();
    bool existed = false;
    for (int attempt = 0; lock_fd_ < 0; ++attempt) {
        constexpr int flags = O_RDONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC;
        int fd = ::open(lock_.c_str(), flags | O_EXCL, 0666);
        existed = fd < 0 && errno == EEXIST;
        if (existed) fd = ::open(lock_.c_str(), flags, 0666);
        if (fd < 0) throw cannot_open(path_, errno, " (creating its lock file " + printable(lock_, 400) + ")");
        struct stat held {}, now {};
        if (::fstat(fd, &held) != 0 || !S_ISREG(held.st_mode)) {
            ::close(fd);
            throw cannot_open(path_, EEXIST, " (its lock file " + printable(lock_, 400) + " is not a regular file)");
        }
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int error = errno;
            ::close(fd);
            if (error == EWOULDBLOCK)
                throw OutputRefused("another hubbeam is writing " + printable(path_, 400) + " (it holds " +
                                    printable(lock_, 400) + "): wait for it to finish, or write to another file");
            throw cannot_open(path_, error, " (locking " + printable(lock_, 400) + ")");
        }
        if (::stat(lock_.c_str(), &now) == 0 && now.st_dev == held.st_dev && now.st_ino == held.st_ino)
            lock_fd_ = fd;
        else
            ::close(fd);
        if (lock_fd_ < 0 && attempt >= 100) throw cannot_open(path_, EAGAIN, " (its lock file keeps changing)");
    }
    if (existed) remove_stale_temps(dir, name);
}

void OutputFile::remove_stale_temps(const std::filesystem::path& dir, const std::string& name) const
{
    // Called with the lock held, so no hubbeam is writing this target now: a temporary file of it is what a
    // writer killed outright (kill -9, a crash of the process) left. Removed only when its process is gone too, so
    // that a file of the same pattern that a live process holds (whatever it is) is never touched.
    DIR* folder = ::opendir(dir.empty() ? "." : dir.c_str());
    if (folder == nullptr) return;
    while (const dirent* entry = ::readdir(folder)) {
        long pid = 0;
        if (!temp_name_of(entry->d_name, name, pid)) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to ask
        struct stat st {};
        if (::fstatat(::dirfd(folder), entry->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode))
            (void)::unlinkat(::dirfd(folder), entry->d_name, 0);
    }
    ::closedir(folder);
}

void OutputFile::create_temp(const std::filesystem::path& dir, const std::string& name, const std::string& temp)
{
    // O_EXCL: never write into a file someone else has; a name left by a killed run whose pid has come round again is
    // skipped with a suffix rather than reused.
    std::string stem = ".";  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + string
    stem += name;
    stem += ".tmp-" + std::to_string(::getpid());
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
        temp_ = temp.empty() ? (dir / (attempt ? stem + "-" + std::to_string(attempt) : stem)).string() : temp;
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd_ >= 0) break;
        const int error = errno;
        if (error == EEXIST && !temp.empty()) {
            release_lock();
            throw TempExists(temp + " exists");
        }
        if (error != EEXIST) {
            release_lock();
            throw cannot_open(path_, error, " (creating its temporary file " + printable(temp_, 400) + ")");
        }
    }
    if (fd_ < 0) {
        release_lock();
        throw cannot_open(path_, EEXIST, " (creating its temporary file " + printable(temp_, 400) + ")");
    }
}

OutputFile::~OutputFile() { discard(); }

int OutputFile::write(std::string_view bytes)
{
    if (done_ || error_ != 0 || !failure_.empty()) return error_ != 0 ? error_ : EIO;
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd_, p, left);
        if (n > 0) {
            p += n;
            left -= static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;  // a signal arrived before anything was written
        } else {
            return error_ = n < 0 ? errno : EIO;
        }
    }
    return 0;
}

int OutputFile::write_at(std::uint64_t offset, std::string_view bytes)
{
    if (done_ || error_ != 0 || !failure_.empty()) return error_ != 0 ? error_ : EIO;
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::pwrite(fd_, p, left, static_cast<off_t>(offset));
        if (n > 0) {
            p += n;
            offset += static_cast<std::uint64_t>(n);
            left -= static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;
        } else {
            return error_ = n < 0 ? errno : EIO;
        }
    }
    return 0;
}

void OutputFile::fail(const std::string& why)
{
    if (failure_.empty()) failure_ = why;
}

std::string OutputFile::close_checked()
{
    if (done_) return "already finished";
    if (fd_ < 0) return {};  // closed and checked already
    std::string problem;
    if (error_ != 0) problem = std::string("write failed: ") + std::strerror(error_);
    else if (!failure_.empty()) problem = failure_;
    // Durable: on disk before the rename, so that a crash of the machine just after it cannot leave an empty file
    // under the target. (Without it a reader still never sees a half-written file: the rename is atomic.)
    else if (durable_ && ::fsync(fd_) != 0) problem = std::string("write failed: ") + std::strerror(errno);
    if (::close(fd_) != 0 && problem.empty()) problem = std::string("write failed: ") + std::strerror(errno);
    fd_ = -1;
    if (!problem.empty()) {
        done_ = true;
        ::unlink(temp_.c_str());  // what it holds cannot be trusted (it may end inside a line)
        release_lock();
    }
    return problem;
}

std::string OutputFile::commit()
{
    if (done_) return "already finished";
    std::string problem = close_checked();
    if (!problem.empty()) return problem;
    done_ = true;
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
        problem = std::string("cannot replace it: ") + std::strerror(errno) + " (the complete file is " +
                  printable(temp_, 400) + ")";
    else if (durable_)
        problem = sync_folder();
    release_lock();
    return problem;
}

std::string commit_together(const std::vector<OutputFile*>& files)
{
    // Every file whole and closed first: a full disk shows itself here, while all the old files are still there.
    for (OutputFile* f : files)
        if (const std::string problem = f->close_checked(); !problem.empty()) {
            for (OutputFile* g : files) g->discard();
            return printable(f->path(), 400) + ": " + problem + " (nothing written: the old files are as they were)";
        }
    // Then the renames, which need no space: each replaces an entry of the folder by another already there.
    std::string placed;
    for (std::size_t k = 0; k < files.size(); ++k)
        if (const std::string problem = files[k]->commit(); !problem.empty()) {
            for (std::size_t j = k + 1; j < files.size(); ++j) files[j]->discard();
            return printable(files[k]->path(), 400) + ": " + problem +
                   (placed.empty() ? " (nothing replaced: the old files are as they were)"
                                   : " (replaced already: " + placed + "; the others are as they were)");
        } else {
            placed += (placed.empty() ? "" : ", ") + printable(files[k]->path(), 400);
        }
    return {};
}

std::string OutputFile::sync_folder() const
{
    // The rename is an entry of the folder: durable only once the folder itself is on disk.
    const std::filesystem::path dir = std::filesystem::path(path_).parent_path();
    const std::string name = dir.empty() ? std::string(".") : dir.string();
    const int fd = ::open(name.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    int error = fd < 0 ? errno : ::fsync(fd) != 0 ? errno : 0;
    if (fd >= 0 && ::close(fd) != 0 && error == 0) error = errno;
    if (error == 0) return {};
    return std::string("cannot sync its folder: ") + std::strerror(error) + " (the file is in place, but may not " +
           "survive a power loss)";
}

void OutputFile::discard()
{
    if (done_) return;
    done_ = true;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    ::unlink(temp_.c_str());
    release_lock();
}

void OutputFile::release_lock()
{
    if (lock_fd_ < 0) return;
    ::unlink(lock_.c_str());  // while still held: see the constructor
    ::close(lock_fd_);
    lock_fd_ = -1;
}

}  // namespace hubbeam
