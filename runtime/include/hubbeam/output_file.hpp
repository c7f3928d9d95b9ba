// How hubbeam writes every file (CSV tables, matrices, figures, scripts): checked before anything is written,
// written beside the target and renamed over it whole, and never by two hubbeam processes at once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/option_lists.hpp>

namespace hubbeam {

/// An output refused before anything is written: the message is the whole line to print (exit code 2).
struct OutputRefused : OptionError {
    using OptionError::OptionError;
};

/// What path is when it exists and is not a regular file ("a directory", "a FIFO", "a character device", "a block
/// device", "a socket"); empty for a regular file or a path that does not exist. Uses stat, which follows links and,
/// unlike open(), never blocks on a FIFO: so a command checks its inputs with it before opening them.
std::string not_a_regular_file(const std::string& path);

/// Whether a and b name the same file: the same device and inode, or, for a file that does not exist yet, the same
/// folder (device and inode) and the same name. False when either cannot be resolved (a missing folder).
bool same_file(const std::string& a, const std::string& b);

/// A file a command reads or writes, with the name its messages give it: "-o", "--fields", "the scene itself".
struct NamedPath {
    std::string path;
    std::string name;
};

struct Scene;
/// Every file a scene was read from, named for check_outputs: the scene file ("the scene itself") and its tables
/// ("the scene's motion.file", "the scene's beam.profile").
std::vector<NamedPath> scene_inputs(const Scene& scene);

/// Checks a command's outputs before anything is computed or written: each must be a name without control or format
/// characters (check_handed_text, the one check of text handed to another program such as gnuplot), a regular file
/// or a new file in a folder that exists, neither a symbolic link nor a file without its owner's write bit, and none
/// may be one of the inputs or another of the outputs (compared by same_file, so ./x/../scene.toml and a hard link
/// are the scene).
/// Throws OutputRefused: "OPTION: expected ..., got ..." or "OPTION: PATH is ...".
/// Outputs with an empty path are skipped (an output not asked for).
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

/// One output file written atomically. The constructor refuses a target that exists and is not a regular file, is
/// a symbolic link or has no owner write bit, takes an advisory lock (flock on DIR/.NAME.lock, removed again when
/// released) so that a second hubbeam writing the same file is refused, removes the temporary files of writers that
/// died (killed outright), and creates the temporary file DIR/.NAME.tmp-PID beside the target exclusively
/// (O_CREAT | O_EXCL, permissions from the umask, or the replaced file's). write() checks every write; commit()
/// checks the temporary file's close and renames it over the target, so that a reader sees the old file or the
/// complete new one. Until commit() succeeds the target is untouched; a failed or abandoned file is removed.
/// Made durable (set_durable), commit() also syncs the file to the disk before the rename and the folder after
/// it, so that the new file survives a power loss or a crash of the machine; without it the rename alone keeps a
/// reader from a half-written file, and the kernel writes the data back when it likes.
class OutputFile {
public:
    /// Throws OutputRefused for a target that is not a regular file, a symbolic link, read-only to its owner, or
    /// that another hubbeam is writing, and
    /// std::runtime_error "PATH: cannot open for writing: REASON" when the temporary file cannot be created. With
    /// temp given, that exact temporary path is created instead (for a program such as gnuplot that derives its
    /// output names from one prefix); TempExists if it is there already.
    explicit OutputFile(const std::string& path, const std::string& temp = {});
    /// Discards the file unless commit() succeeded.
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    /// A temporary path given to the constructor that already exists.
    struct TempExists : std::runtime_error {
        using std::runtime_error::runtime_error;
    };

    /// Appends bytes (retrying short writes and EINTR); returns 0, or the errno of the write that failed. After a
    /// failure nothing more is written and commit() refuses.
    int write(std::string_view bytes);
    /// Overwrites bytes already written, at offset from the start (a header whose counts are known at the end);
    /// returns 0 or the errno of the failed write, as write() does.
    int write_at(std::uint64_t offset, std::string_view bytes);
    /// Marks the file as failed (for a caller whose own check failed, e.g. of what another program wrote).
    void fail(const std::string& why);
    /// With on, commit() syncs the file before the rename and its folder after it (fsync): the file then survives
    /// a power loss. Off by default: a sync costs a disk round trip (milliseconds to seconds) per file.
    void set_durable(bool on) { durable_ = on; }
    /// Puts the file in place: close, rename over the target (durable: fsync before, and of the folder after),
    /// release the lock. Returns an empty string, or
    /// what failed ("write failed: REASON"); then the temporary file is removed and the target is as it was (except
    /// when only the rename failed: the complete file is then kept at temp_path(), and the message says so; or, durable,
    /// when only the folder's sync failed: the file is then in place, and the message says so).
    std::string commit();
    /// The first half of commit(): closes the file and checks every write (durable: syncs it). Returns "" (then
    /// commit() or discard() follows), or what failed, and then the temporary file is removed as by discard().
    std::string close_checked();
    /// Removes the temporary file and releases the lock; the target stays as it was. Only the first of commit() and
    /// discard() acts.
    void discard();

    const std::string& path() const { return path_; }
    /// Where the bytes are until commit().
    const std::string& temp_path() const { return temp_; }

private:
    /// Refuses a target that is not a regular file, a symbolic link or read-only; notes the permissions to keep.
    void resolve_target();
    /// Takes the lock beside the target (DIR/.NAME.lock), refusing while another hubbeam holds it.
    void take_lock(const std::filesystem::path& dir, const std::string& name);
    /// With the lock held, where a killed writer left it: removes DIR/.NAME.tmp-PID[-N] files whose process no
    /// longer exists.
    void remove_stale_temps(const std::filesystem::path& dir, const std::string& name) const;
    /// Creates the temporary file (temp, or DIR/.NAME.tmp-PID[-N]) with O_EXCL.
    void create_temp(const std::filesystem::path& dir, const std::string& name, const std::string& temp);
    void release_lock();
    /// fsync of the target's folder after the rename: "" or what failed.
    std::string sync_folder() const;

    std::string path_;    // as given, for messages; the name renamed over (never through a link)
    std::string temp_;
    std::string lock_;    // the lock file's path
    int fd_ = -1;
    int lock_fd_ = -1;
    int mode_ = -1;       // the replaced file's permissions, -1 for a new file
    int error_ = 0;       // errno of the first failed write
    std::string failure_; // fail()'s reason
    bool done_ = false;
    bool durable_ = false;
};

/// Puts a set of files in place together (a linearization's matrices): each is closed and checked first, and only
/// when every one is whole are they renamed over their targets, so that a full disk leaves the old set whole. Returns
/// "" or one line: "PATH: what failed (what is in place)".
std::string commit_together(const std::vector<OutputFile*>& files);

}  // namespace hubbeam
