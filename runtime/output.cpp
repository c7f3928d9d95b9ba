// CSV rows (buffered, written to a temporary file that is renamed into place) and the run summary.
#include "output.hpp"

#include "shortest.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hubbeam {

namespace {

// A chunk is written once the buffer cannot take another line: large enough that the default run (about
// 0.5 MB) needs a handful of write calls, small enough to stay in cache.
constexpr std::size_t buffer_size = std::size_t{1} << 16;
// The longest double to_chars writes is 24 characters (-1.7976931348623157e+308): one per column, the commas
// between them and the newline.
constexpr std::size_t max_line = row_width * 24 + row_width;
// Buffered rows reach the file at the latest this long after the previous chunk: a long run's progress is
// visible, and at most this much wall time of rows is lost if the process is killed outright.
constexpr auto flush_interval = std::chrono::milliseconds(100);

/// Formats row's columns into out (room for max_line characters, no newline); returns the end.
char* format_row(char* out, const Row& row)
{
    for (std::size_t i = 0; i < row_width; ++i) {
        if (i) *out++ = ',';
        out = std::to_chars(out, out + 24, row.*row_columns[i].member).ptr;
    }
    return out;
}

std::runtime_error cannot_open(const std::string& path, int error, const std::string& detail = {})
{
    return std::runtime_error(path + ": cannot open for writing: " + std::strerror(error) + detail);
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path) : CsvWriter(path, row_header()) {}

CsvWriter::CsvWriter(const std::string& path, const std::string& header)
    : path_(path), target_(path), buffer_(new char[buffer_size])
{
    struct stat st {};
    const bool exists = ::stat(path.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        // A device or a pipe: written directly (a directory fails here with "Is a directory").
        fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd_ < 0) throw cannot_open(path_, errno);
    } else {
        struct stat link {};
        if (exists && ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
            // Replace the file the link points to, not the link: what writing through it did before.
            std::error_code ec;
            if (const auto real = std::filesystem::canonical(path, ec); !ec) target_ = real.string();
        }
        open_temporary(exists ? static_cast<int>(st.st_mode & 07777) : -1);
    }
    // The header is written at once, so that an output that cannot take anything (a full disk) stops the run
    // at its first row instead of after all the computing.
    if (header.size() >= buffer_size / 2) throw std::logic_error("CsvWriter: a header of " + std::to_string(header.size()) + " bytes");
    std::memcpy(buffer_.get(), header.data(), header.size());
    used_ = header.size();
    buffer_[used_++] = '\n';
    flush();
}

void CsvWriter::write_line(std::string_view line)
{
    if (!ok_ || finished_) return;
    if (line.size() >= buffer_size / 2) throw std::logic_error("CsvWriter: a line of " + std::to_string(line.size()) + " bytes");
    if (buffer_size - used_ <= line.size()) flush();
    std::memcpy(buffer_.get() + used_, line.data(), line.size());
    used_ += line.size();
    buffer_[used_++] = '\n';
    ++buffered_rows_;
    if (std::chrono::steady_clock::now() - last_flush_ >= flush_interval) flush();
}

void CsvWriter::open_temporary(int existing_mode)
{
    const std::filesystem::path target(target_);
    std::string stem = ".";  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + string
    stem += target.filename().string();
    stem += ".tmp-" + std::to_string(::getpid());
    // O_EXCL: never write into a file someone else has; a name left by a killed run whose pid has come round
    // again is skipped with a suffix rather than reused.
    for (int attempt = 0; attempt < 100; ++attempt) {
        temp_ = (target.parent_path() / (attempt ? stem + "-" + std::to_string(attempt) : stem)).string();
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0) break;
        if (errno != EEXIST) throw cannot_open(path_, errno, " (creating its temporary file " + temp_ + ")");
    }
    if (fd_ < 0) throw cannot_open(path_, EEXIST, " (creating its temporary file " + temp_ + ")");
    // The replacement keeps the permissions of the file it replaces (a new file gets the umask's, as before).
    if (existing_mode >= 0) (void)::fchmod(fd_, static_cast<mode_t>(existing_mode));
}

CsvWriter::~CsvWriter()
{
    finish();
}

void CsvWriter::write(const Row& row)
{
    if (!ok_ || finished_) return;
    if (buffer_size - used_ < max_line) flush();
    char* end = format_row(buffer_.get() + used_, row);
    *end++ = '\n';
    used_ = static_cast<std::size_t>(end - buffer_.get());
    ++buffered_rows_;
    // now() is a vDSO call of some tens of nanoseconds, cheap beside formatting ten doubles: checked every row
    // so that the 0.1 s bound holds however slowly rows come.
    if (std::chrono::steady_clock::now() - last_flush_ >= flush_interval) flush();
}

void CsvWriter::flush()
{
    const char* p = buffer_.get();
    std::size_t left = used_;
    while (left > 0 && ok_) {
        const ssize_t n = ::write(fd_, p, left);
        if (n > 0) {
            p += n;
            left -= static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;  // a signal arrived before anything was written
        } else {
            const int error = n < 0 ? errno : EIO;
            fail("write failed after " + std::to_string(written_rows_) + " rows: " + std::strerror(error));
        }
    }
    used_ = 0;
    if (ok_) written_rows_ += buffered_rows_;
    buffered_rows_ = 0;
    last_flush_ = std::chrono::steady_clock::now();
}

void CsvWriter::fail(const std::string& what)
{
    if (!ok_) return;  // the first failure is the one to report
    ok_ = false;
    error_ = path_ + ": " + what;
}

bool CsvWriter::finish()
{
    if (finished_) return ok_;
    finished_ = true;
    if (ok_) flush();
    // On disk before the rename, so that a crash just after it cannot leave an empty file under the target.
    if (!temp_.empty() && ok_ && ::fsync(fd_) != 0) fail(std::string("write failed: ") + std::strerror(errno));
    if (::close(fd_) != 0) fail(std::string("write failed: ") + std::strerror(errno));
    fd_ = -1;
    if (temp_.empty()) return ok_;
    if (!ok_) {
        // What the temporary file holds cannot be trusted (it may end inside a line): the target is left alone.
        ::unlink(temp_.c_str());
        error_ += " (nothing written: " + path_ + " is as it was)";
        return false;
    }
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
        fail(std::string("cannot replace it: ") + std::strerror(errno) + " (the " + std::to_string(rows()) +
             " rows are in " + temp_ + ")");
        return false;
    }
    return true;
}

RowSink CsvWriter::sink()
{
    return [this](const Row& row) { write(row); };
}

std::string csv_line(const Row& row)
{
    char line[max_line];
    return std::string(line, format_row(line, row));
}

std::string csv_field(std::string_view text)
{
    if (text.find_first_of(",\"\n") == std::string_view::npos) return std::string(text);
    std::string q = "\"";
    for (const char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
}

std::string format_summary(const RunSummary& r, const Scene& scene)
{
    std::ostringstream out;
    const Motion& m = scene.motion;
    out << "scene       " << scene.path;
    if (m.kind == Motion::Kind::spin_up)
        out << " (spin-up to Omega0 = " << shortest(m.omega0) << " rad/s in T_s = " << shortest(m.spin_time) << " s)\n";
    else
        out << " (hub torque tau0 = " << shortest(m.tau0) << " N m for T_t = " << shortest(m.torque_time) << " s)\n";
    out << "variant     " << r.variant << " (" << r.source << ")\n";
    out << "algebra     " << r.algebra << "\n";
    out << "stepper     " << r.stepper << (r.stepper_why.empty() ? "" : " (" + r.stepper_why + ")") << ", rtol " << shortest(scene.solver.rtol) << ", atol "
        << shortest(scene.solver.atol) << ", h0 " << shortest(scene.solver.h0) << " s, "
        << (scene.solver.stepping == Stepping::free ? "free steps (rows interpolated)" : "a step ends at every row")
        << "\n";
    out << "time        0 to " << shortest(r.t_reached) << " s of " << shortest(scene.output.t_end) << " s, rows every "
        << shortest(scene.output.dt_out) << " s";
    if (!scene.output.file.empty()) out << " in " << scene.output.file;
    out << "\n";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", r.max_abs_tip_uy);
    out << "max |tip_uy| " << buf << " m\n";
    if (r.vibration_energy > 0.0) {
        char line[160];
        // As the untrustworthy message words it (simulate.cpp), so that the two agree.
        std::snprintf(line, sizeof line, "%.2g J after t = %g s, %.2g of the vibration energy", r.jacobi_drift,
                      r.t_steady, r.jacobi_drift / r.vibration_energy);
        out << "invariant   Jacobi integral drift " << line << "\n";
    }
    if (r.estimated_error >= 0.0) {
        char line[200];
        std::snprintf(line, sizeof line, "%.2g of the largest value (%s), from windows re-run at rtol %g, atol %g",
                      r.estimated_error, r.error_column.c_str(), r.check_rtol, r.check_atol);
        out << "error       " << line << "\n";
    }
    out << "steps       " << r.steps << "\n";
    out << "RHS evals   " << r.rhs_evals << "\n";
    std::snprintf(buf, sizeof buf, "%.3f", r.wall_seconds);
    out << "wall time   " << buf << " s";
    if (r.check_wall_seconds > 0.0) {
        std::snprintf(buf, sizeof buf, "%.3f", r.check_wall_seconds);
        out << " and " << buf << " s for the error check";
    }
    out << "\n";
    if (!r.completed) out << "STOPPED     at t = " << shortest(r.t_reached) << " s: " << r.failure << "\n";
    return out.str();
}

}  // namespace hubbeam
