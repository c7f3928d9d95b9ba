// Output of a run: the CSV file of simulate() rows and the summary the command line prints.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "scene.hpp"
#include "simulate.hpp"

namespace hubbeam {

/// CSV writer usable as simulate()'s RowSink: row_header() first, every number in the shortest form that
/// reads back as the same double. Rows are formatted into a memory buffer and written in large chunks, at
/// the latest 0.1 s (wall time) after the previous chunk, so that a long run's progress is on disk without
/// a system call per row.
///
/// A regular file (or a path that does not exist yet) is replaced atomically: the rows go to a temporary
/// file DIR/.NAME.tmp-PID next to the target, created exclusively, and finish() renames it over the target.
/// A reader of the target sees the old file or the complete new one, never a half-written line, and two
/// runs writing the same path do not mix their rows. A target that exists and is not a regular file (a
/// device such as /dev/null, a pipe) is written directly: there is nothing to replace, and renaming over it
/// would replace the device node itself.
class CsvWriter {
public:
    /// Creates the temporary file (or opens a non-regular target) and writes the header; throws
    /// std::runtime_error "PATH: cannot open for writing: REASON" if it cannot, leaving nothing behind.
    explicit CsvWriter(const std::string& path);
    /// The same for another table: header is its first line (no newline).
    CsvWriter(const std::string& path, const std::string& header);
    /// finish() if the caller has not, so that a run ended by an exception keeps its rows too.
    ~CsvWriter();
    CsvWriter(const CsvWriter&) = delete;
    CsvWriter& operator=(const CsvWriter&) = delete;

    /// Appends one row. A write error is remembered (see ok()) instead of thrown through the integrator;
    /// rows after it are dropped.
    void write(const Row& row);
    /// Appends one line of another table (no newline; shorter than 32 KB), buffered and flushed as rows are.
    void write_line(std::string_view line);
    /// This writer as a RowSink for simulate(); the writer must outlive the returned function.
    RowSink sink();

    /// Writes what is buffered and puts the file in place: renames the temporary file over the target, or
    /// after a write failure removes it and leaves the target as it was. Only the first call acts; returns
    /// ok().
    bool finish();

    /// False once a write, flush or the final rename failed (disk full, ...): error() says what.
    bool ok() const { return ok_; }
    /// Rows accepted after the header and not lost to a failed write; after finish(), the file's data rows.
    long rows() const { return written_rows_ + buffered_rows_; }
    const std::string& path() const { return path_; }
    /// Where the rows are until finish(): the temporary file, or path() when the target is written directly.
    const std::string& writing_path() const { return temp_.empty() ? path_ : temp_; }
    /// One line for the user when !ok(): "PATH: what failed: REASON" and where the rows are.
    const std::string& error() const { return error_; }

private:
    void open_temporary(int existing_mode);
    void flush();
    void fail(const std::string& what);

    std::string path_;    // as given, for messages
    std::string target_;  // path_ with a symbolic link resolved: the file that is replaced
    std::string temp_;    // the temporary file, empty when writing the target directly
    int fd_ = -1;
    std::unique_ptr<char[]> buffer_;
    std::size_t used_ = 0;
    std::chrono::steady_clock::time_point last_flush_;
    long written_rows_ = 0;   // rows whose bytes the kernel has accepted
    long buffered_rows_ = 0;  // rows in buffer_
    bool ok_ = true;
    bool finished_ = false;
    std::string error_;
};

/// A text field of a CSV line: as it is, or quoted (quotes doubled, newlines as spaces) when it holds a comma,
/// a quote or a newline.
std::string csv_field(std::string_view text);

/// One CSV line of row (no newline), columns as in row_header(): the text CsvWriter writes for it.
std::string csv_line(const Row& row);

/// Short multi-line summary of a run for the terminal: scene, variant and whether generated or assembled,
/// stepper and tolerances, max |tip_uy|, steps, RHS evaluations, wall time and, if the run stopped early,
/// where and why. Ends with a newline.
std::string format_summary(const RunSummary& summary, const Scene& scene);

}  // namespace hubbeam
