// Output of a run: the CSV file of simulate() rows and the summary the command line prints.
#pragma once

#include <cstdio>
#include <string>

#include "scene.hpp"
#include "simulate.hpp"

namespace hubbeam {

/// CSV writer usable as simulate()'s RowSink: row_header() first, every number in the shortest form that
/// reads back as the same double, each row flushed so that a run that stops early keeps what it wrote.
class CsvWriter {
public:
    /// Creates (or truncates) path and writes the header; throws std::runtime_error "PATH: cannot open for
    /// writing: REASON" if it cannot.
    explicit CsvWriter(const std::string& path);
    ~CsvWriter();
    CsvWriter(const CsvWriter&) = delete;
    CsvWriter& operator=(const CsvWriter&) = delete;

    /// Appends one row. A write error is remembered (see ok()) instead of thrown through the integrator.
    void write(const Row& row);
    /// This writer as a RowSink for simulate(); the writer must outlive the returned function.
    RowSink sink();

    /// False once a write or flush failed (disk full, ...).
    bool ok() const { return ok_; }
    /// Rows written after the header (a row whose write failed is not counted).
    long rows() const { return rows_; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::FILE* file_ = nullptr;
    long rows_ = 0;
    bool ok_ = true;
};

/// One CSV line of row (no newline), columns as in row_header().
std::string csv_line(const Row& row);

/// Short multi-line summary of a run for the terminal: scene, variant and whether generated or assembled,
/// stepper and tolerances, max |tip_uy|, steps, RHS evaluations, wall time and, if the run stopped early,
/// where and why. Ends with a newline.
std::string format_summary(const RunSummary& summary, const Scene& scene);

}  // namespace hubbeam
