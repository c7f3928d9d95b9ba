// Output of a run: the CSV file of simulate() rows and the summary the command line prints.
#pragma once

#include <chrono>
#include <cstddef>
#include <hubbeam/config.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <memory>
#include <string>
#include <string_view>

#include <hubbeam/output_file.hpp>

namespace hubbeam {

/// Whether a run's rows to path are a NumPy array rather than CSV: path ends in .npy.
bool is_npy_path(const std::string& path);
/// Where the column names of an .npy output go: DIR/NAME.npy -> DIR/NAME.columns.txt.
std::string npy_columns_path(const std::string& path);

/// CSV writer usable as simulate()'s RowSink: row_header() first, every number in the shortest form that
/// reads back as the same double. Rows are formatted into a memory buffer and written in large chunks, at
/// the latest 0.1 s (wall time) after the previous chunk, so that a long run's progress is on disk without
/// a system call per row.
///
/// A run's rows to a path ending in .npy (is_npy_path) are written as a NumPy array instead: format 1.0, '<f8',
/// C order, shape (rows, columns), the columns and their order the CSV's; the row count in its header is written
/// by finish(), so it is right for a run stopped early too. The column names, the CSV's header line, go to
/// npy_columns_path(path), written and put in place alongside. Each number is the double itself: the same
/// round trip as the CSV's text, without formatting.
///
/// The file is an OutputFile (output_file.hpp): the rows go to a temporary file DIR/.NAME.tmp-PID next to the
/// target, and finish() renames it over the target. A reader of the target sees the old file or the complete new
/// one, never a half-written line; a second hubbeam writing the same path is refused while this one writes; a
/// target that exists and is not a regular file (a FIFO, a device, a directory) is refused, never opened. Made
/// durable, the files are synced to the disk at finish() (OutputFile::set_durable).
class CsvWriter {
public:
    /// Creates the temporary file and writes the header; throws OutputRefused (a FIFO, a device, another hubbeam
    /// writing it) or std::runtime_error "PATH: cannot open for writing: REASON" if it cannot, leaving nothing behind.
    explicit CsvWriter(const std::string& path);
    /// A run's rows with the optional columns of columns (optional_columns_of(scene)) after row_columns: as CSV,
    /// or a NumPy array when is_npy_path(path). durable: synced to the disk at finish().
    CsvWriter(const std::string& path, ColumnSet columns, bool durable = false);
    /// The same for another table: header is its first line (no newline). durable: synced at finish().
    CsvWriter(const std::string& path, const std::string& header, bool durable = false);
    /// finish() if the caller has not, so that a run ended by an exception keeps its rows too.
    ~CsvWriter();
    CsvWriter(const CsvWriter&) = delete;
    CsvWriter& operator=(const CsvWriter&) = delete;

    /// Appends one row. A write error is remembered (see ok()) instead of thrown through the integrator;
    /// rows after it are dropped.
    void write(const Row& row);
    /// Appends one line of another table (no newline; shorter than 32 KB), buffered and flushed as rows are. Not
    /// for an .npy file (std::logic_error).
    void write_line(std::string_view line);
    /// This writer as a RowSink for simulate(); the writer must outlive the returned function.
    RowSink sink();

    /// Writes what is buffered and puts the file in place: renames the temporary file over the target, or
    /// after a write failure removes it and leaves the target as it was. Only the first call acts; returns
    /// ok().
    bool finish();
    /// Drops the rows: the temporary file is removed and the target left as it was (a command refused after its
    /// writer was created). Only the first of finish() and discard() acts.
    void discard();

    /// False once a write, flush or the final rename failed (disk full, ...): error() says what.
    bool ok() const { return ok_; }
    /// Rows accepted after the header and not lost to a failed write; after finish(), the file's data rows.
    long rows() const { return written_rows_ + buffered_rows_; }
    const std::string& path() const { return path_; }
    /// Where the rows are until finish(): the temporary file.
    const std::string& writing_path() const;
    /// One line for the user when !ok(): "PATH: what failed: REASON" and where the rows are.
    const std::string& error() const { return error_; }

private:
    void write_header(const std::string& header);
    void flush();
    void fail(const std::string& what);
    /// Writes the .npy header with the row count (at the start of the file, over the placeholder).
    void write_npy_header();

    std::string path_;   // as given, for messages
    ColumnSet columns_;  // a run's optional columns written by write(Row)
    std::unique_ptr<OutputFile> file_;
    std::unique_ptr<OutputFile> columns_file_;  // an .npy file's column names; null for CSV
    std::size_t width_ = 0;                     // an .npy file's columns
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

/// One CSV line of row (no newline), columns as in row_header(columns): the text CsvWriter writes for it.
std::string csv_line(const Row& row, const ColumnSet& columns = {});

/// A run's rows computed already (a Python Result) written as hubbeam run writes them: CSV with header as its first
/// line, or an .npy file and its column names when is_npy_path(path), and metadata (JSON text) in
/// metadata_path(path); rows x width doubles in C order at data. The outputs are checked as check_outputs does
/// against inputs, the files the rows came from (the run's scene_inputs), with OutputRefused, and put in place
/// together: a failure leaves every target as it was. Returns "" or one line saying what failed.
std::string save_rows(const std::string& path, const double* data, std::size_t rows, std::size_t width,
                      const std::string& header, const std::string& metadata, const std::vector<NamedPath>& inputs);

/// Short multi-line summary of a run for the terminal: scene, variant and whether generated or assembled,
/// stepper and tolerances, max |tip_uy|, steps, RHS evaluations, wall time and, if the run stopped early,
/// where and why. Ends with a newline.
std::string format_summary(const RunSummary& summary, const Scene& scene);

}  // namespace hubbeam
