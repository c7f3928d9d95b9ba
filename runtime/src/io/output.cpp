// CSV rows (buffered, written through an OutputFile: a temporary file renamed into place) and the run summary.
#include <hubbeam/output.hpp>

#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <hubbeam/metadata.hpp>
#include <hubbeam/npz.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>

namespace hubbeam {

namespace {

// A chunk is written once the buffer cannot take another line: large enough that the default run (about
// 0.5 MB) needs a handful of write calls, small enough to stay in cache.
constexpr std::size_t buffer_size = std::size_t{1} << 16;
// The longest number is max_shortest_chars (-1.7976931348623157e+308): one per column, the commas between them
// and the newline, and the scratch write_shortest may leave past the last number.
constexpr std::size_t max_line =
    (row_width + optional_width + max_derived_columns + max_blades * (5 + root_load_width)) * (max_shortest_chars + 1) +
    shortest_room;
// Buffered rows reach the file at the latest this long after the previous chunk: a long run's progress is
// visible, and at most this much wall time of rows is lost if the process is killed outright.
constexpr auto flush_interval = std::chrono::milliseconds(100);

// An .npy file's header (format 1.0): magic, version, the length of the dict, the dict padded with spaces to a
// newline. Always this long, so that the count written at the end fits in the placeholder written first; a
// multiple of 64, numpy's alignment of the data.
constexpr std::size_t npy_header_size = 128;

/// The .npy header of rows x width little-endian doubles in C order.
std::string rows_npy_header(long rows, std::size_t width)
{
    return npy_header("<f8", "(" + std::to_string(rows) + ", " + std::to_string(width) + ")", npy_header_size);
}

/// Copies row's values, in column order, into out as little-endian doubles; returns the end.
char* binary_row(char* out, const Row& row, const ColumnSet& set)
{
    for_each_value(row, set, [&](double v) {
        if constexpr (std::endian::native == std::endian::little) {
            std::memcpy(out, &v, sizeof v);
        } else {
            const auto bits = std::bit_cast<std::uint64_t>(v);
            for (int i = 0; i < 8; ++i) out[i] = static_cast<char>(bits >> (8 * i));
        }
        out += sizeof v;
    });
    return out;
}

/// Formats row's columns, then the optional ones of set, into out (room for max_line characters, no newline); returns
/// the end.
char* format_row(char* out, const Row& row, const ColumnSet& set)
{
    const char* start = out;
    for_each_value(row, set, [&](double v) {
        if (out != start) *out++ = ',';
        out = write_shortest(out, v);
    });
    return out;
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path) : CsvWriter(path, row_header()) {}

bool is_npy_path(const std::string& path)
{
    return std::filesystem::path(path).extension() == ".npy";
}

std::string npy_columns_path(const std::string& path)
{
    std::filesystem::path p(path);
    return p.replace_extension(".columns.txt").string();
}

CsvWriter::CsvWriter(const std::string& path, ColumnSet columns, bool durable)
    : path_(path), columns_(columns), file_(std::make_unique<OutputFile>(path)), buffer_(new char[buffer_size])
{
    file_->set_durable(durable);
    if (!is_npy_path(path)) {
        write_header(row_header(columns));
        return;
    }
    columns_file_ = std::make_unique<OutputFile>(npy_columns_path(path));
    columns_file_->set_durable(durable);
    width_ = row_width + columns.count();
    const std::string names = row_header(columns) + "\n";
    if (const int error = columns_file_->write(names); error != 0)
        throw std::runtime_error(npy_columns_path(path) + ": cannot write: " + std::strerror(error));
    // A placeholder of the header's size now (the rows follow it), the count at finish().
    const std::string header = rows_npy_header(0, width_);
    std::memcpy(buffer_.get(), header.data(), header.size());
    used_ = header.size();
    flush();
}

CsvWriter::CsvWriter(const std::string& path, const std::string& header, bool durable)
    : path_(path), file_(std::make_unique<OutputFile>(path)), buffer_(new char[buffer_size])
{
    file_->set_durable(durable);
    write_header(header);
}

void CsvWriter::write_header(const std::string& header)
{
    // The header is written at once, so that an output that cannot take anything (a full disk) stops the run
    // at its first row instead of after all the computing.
    if (header.size() >= buffer_size / 2)
        throw std::logic_error("CsvWriter: a header of " + std::to_string(header.size()) + " bytes");
    std::memcpy(buffer_.get(), header.data(), header.size());
    used_ = header.size();
    buffer_[used_++] = '\n';
    flush();
}

const std::string& CsvWriter::writing_path() const
{
    return file_->temp_path();
}

void CsvWriter::write_line(std::string_view line)
{
    if (columns_file_) throw std::logic_error("CsvWriter: a text line for an .npy file");
    if (!ok_ || finished_) return;
    if (line.size() >= buffer_size / 2)
        throw std::logic_error("CsvWriter: a line of " + std::to_string(line.size()) + " bytes");
    if (buffer_size - used_ <= line.size()) flush();
    std::memcpy(buffer_.get() + used_, line.data(), line.size());
    used_ += line.size();
    buffer_[used_++] = '\n';
    ++buffered_rows_;
    if (std::chrono::steady_clock::now() - last_flush_ >= flush_interval) flush();
}

CsvWriter::~CsvWriter()
{
    finish();
}

void CsvWriter::write(const Row& row)
{
    if (!ok_ || finished_) return;
    if (buffer_size - used_ < max_line) flush();
    if (columns_file_) {
        used_ = static_cast<std::size_t>(binary_row(buffer_.get() + used_, row, columns_) - buffer_.get());
    } else {
        char* end = format_row(buffer_.get() + used_, row, columns_);
        *end++ = '\n';
        used_ = static_cast<std::size_t>(end - buffer_.get());
    }
    ++buffered_rows_;
    // now() is a vDSO call of some tens of nanoseconds, cheap beside formatting ten doubles: checked every row
    // so that the 0.1 s bound holds however slowly rows come.
    if (std::chrono::steady_clock::now() - last_flush_ >= flush_interval) flush();
}

void CsvWriter::flush()
{
    if (ok_ && used_ > 0)
        if (const int error = file_->write(std::string_view(buffer_.get(), used_)); error != 0)
            fail("write failed after " + std::to_string(written_rows_) + " rows: " + std::strerror(error));
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
    if (ok_ && columns_file_) write_npy_header();
    if (!ok_) {
        // What the temporary file holds cannot be trusted (it may end inside a line): the target is left alone.
        file_->discard();
        if (columns_file_) columns_file_->discard();
        error_ += " (nothing written: " + path_ + " is as it was)";
        return false;
    }
    // The names first: an .npy file in place has its names beside it.
    if (columns_file_)
        if (const std::string problem = columns_file_->commit(); !problem.empty()) {
            file_->discard();
            fail(npy_columns_path(path_) + ": " + problem);
            error_ += " (nothing written: " + path_ + " is as it was)";
            return false;
        }
    if (const std::string problem = file_->commit(); !problem.empty()) {
        fail(problem);
        if (problem.rfind("write failed", 0) == 0) error_ += " (nothing written: " + path_ + " is as it was)";
        return false;
    }
    return true;
}

void CsvWriter::write_npy_header()
{
    if (const int error = file_->write_at(0, rows_npy_header(written_rows_, width_)); error != 0)
        fail(std::string("write failed (the header): ") + std::strerror(error));
}

void CsvWriter::discard()
{
    if (finished_) return;
    finished_ = true;
    used_ = 0;
    buffered_rows_ = 0;
    file_->discard();
    if (columns_file_) columns_file_->discard();
}

RowSink CsvWriter::sink()
{
    return [this](const Row& row) { write(row); };
}

std::string csv_line(const Row& row, const ColumnSet& columns)
{
    char line[max_line];
    return std::string(line, format_row(line, row, columns));
}

std::string save_rows(const std::string& path, const double* data, std::size_t rows, std::size_t width,
                      const std::string& header, const std::string& metadata, const std::vector<NamedPath>& inputs)
{
    const bool npy = is_npy_path(path);
    const std::string columns_path = npy ? npy_columns_path(path) : "", json_path = metadata_path(path);
    check_outputs(inputs, {{path, path}, {columns_path, "its column names"}, {json_path, "its metadata"}});
    std::string bytes;
    if (npy) {
        bytes = rows_npy_header(static_cast<long>(rows), width);
        const std::size_t start = bytes.size();
        bytes.resize(start + rows * width * sizeof(double));
        char* out = bytes.data() + start;
        for (std::size_t i = 0; i < rows * width; ++i) {
            const auto bits = std::bit_cast<std::uint64_t>(data[i]);
            for (int b = 0; b < 8; ++b) *out++ = static_cast<char>(bits >> (8 * b));  // '<f8' on any host
        }
    } else {
        bytes = header + "\n";
        for (std::size_t i = 0; i < rows; ++i) {
            for (std::size_t j = 0; j < width; ++j) {
                if (j > 0) bytes += ',';
                append_shortest(bytes, data[i * width + j]);
            }
            bytes += '\n';
        }
    }
    std::vector<std::unique_ptr<OutputFile>> files;
    try {
        files.push_back(std::make_unique<OutputFile>(path));
        (void)files.back()->write(bytes);  // a failed write is reported by commit_together, before any rename
        if (npy) {
            files.push_back(std::make_unique<OutputFile>(columns_path));
            (void)files.back()->write(header + "\n");
        }
        files.push_back(std::make_unique<OutputFile>(json_path));
        (void)files.back()->write(metadata);
    } catch (const std::exception& e) {
        return e.what();
    }
    std::vector<OutputFile*> set;
    for (const auto& f : files) set.push_back(f.get());
    return commit_together(set);
}

std::string csv_field(std::string_view text)
{
    if (text.find_first_of(",\"\n") == std::string_view::npos) return std::string(text);
    std::string q = "\"";
    for (const char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
}

namespace {

/// " (what the motion is": the drive's words for the summary's scene line, left open for what follows.
std::string motion_words(const Motion& m)
{
    std::ostringstream motion;
    switch (m.kind) {
        case Motion::Kind::spin_up:
            motion << " (spin-up to Omega0 = " << shortest(m.omega0) << " rad/s in T_s = " << shortest(m.spin_time)
                   << " s";
            break;
        case Motion::Kind::torque:
            motion << " (hub torque tau0 = " << shortest(m.tau0) << " N m for T_t = " << shortest(m.torque_time)
                   << " s";
            break;
        case Motion::Kind::held:
            motion << " (hub held at theta = " << shortest(m.angle) << " rad";
            break;
        case Motion::Kind::step:
            motion << " (step to " << shortest(m.angle) << " rad at t = 0";
            break;
        case Motion::Kind::table:
        case Motion::Kind::torque_table:
            motion << (m.kind == Motion::Kind::table ? " (hub angle from " : " (hub torque from ")
                   << printable(m.table_file, 200) << ", " << m.table->times().size()
                   << " rows to t = " << shortest(m.table->last_time()) << " s, "
                   << (m.kind == Motion::Kind::table ? "natural cubic spline" : "linear between rows");
            break;
    }
    if (m.kind != Motion::Kind::held && m.theta0 != 0.0) motion << ", theta0 = " << shortest(m.theta0) << " rad";
    return motion.str();
}

/// The summary's scene line: the file and what drives the hub.
void print_scene(std::ostream& out, const Scene& scene)
{
    out << "scene       " << scene.path;
    if (scene.control && scene.control->law) {
        out << " (hub torque from a torque law)\n";
    } else {
        const std::string what = motion_words(scene.motion);
        out << (scene.control ? " (controlled hub, reference: " + what.substr(2) : what) << ")\n";
    }
}

/// The summary's invariant line: the monitor's drift against its reference, or why it checked none (no line when it
/// measured nothing).
void print_invariant(std::ostream& out, const RunSummary& r)
{
    char buf[32];
    if (!r.monitor_off.empty()) {
        out << "invariant   none checked: " << r.monitor_off << "\n";
    } else if (r.vibration_energy > 0.0 && r.energy_balance) {
        char line[200];
        std::snprintf(line, sizeof line, "%.2g J from t = %g s, %.2g of %s", r.jacobi_drift, r.t_steady,
                      r.jacobi_drift / r.vibration_energy, r.invariant_reference.c_str());
        out << "invariant   energy balance E + dissipated - work drift " << line << "\n";
    } else if (r.vibration_energy > 0.0) {
        char line[160];
        // As the untrustworthy message words it (run_monitor.cpp), so that the two agree.
        std::snprintf(line, sizeof line, "%.2g J after t = %g s, %.2g of %s", r.jacobi_drift, r.t_steady,
                      r.jacobi_drift / r.vibration_energy, r.invariant_reference.c_str());
        out << "invariant   Jacobi integral drift " << line << "\n";
    } else if (r.vibration_energy == 0.0) {  // nothing moved: no energy to measure a drift against
        std::snprintf(buf, sizeof buf, "%.2g", r.jacobi_drift);
        out << "invariant   " << (r.energy_balance ? "energy balance E + dissipated - work" : "Jacobi integral")
            << " drift " << buf << " J " << (r.energy_balance ? "from" : "after") << " t = " << shortest(r.t_steady)
            << " s, with no energy in the run to compare it with\n";
    }
}

/// The summary's wall time line: the run's, and the error check's where one ran.
void print_wall_time(std::ostream& out, const RunSummary& r)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", r.wall_seconds);
    out << "wall time   " << buf << " s";
    if (r.check_wall_seconds > 0.0) {
        std::snprintf(buf, sizeof buf, "%.3f", r.check_wall_seconds);
        out << " and " << buf << " s for the error check";
    }
    out << "\n";
}

}  // namespace

std::string format_summary(const RunSummary& r, const Scene& scene)
{
    std::ostringstream out;
    print_scene(out, scene);
    out << "variant     " << r.variant << " (" << r.source << ")\n";
    out << "algebra     " << r.algebra << "\n";
    out << "stepper     " << r.stepper << (r.stepper_why.empty() ? "" : " (" + r.stepper_why + ")") << ", rtol "
        << shortest(scene.solver.rtol) << ", atol " << shortest(scene.solver.atol) << ", h0 "
        << shortest(scene.solver.h0) << " s, "
        << (scene.solver.stepping == Stepping::free ? "free steps (rows interpolated)" : "a step ends at every row")
        << "\n";
    if (!r.newton.empty()) out << "newton      " << r.newton << "\n";
    if (!r.initial.empty()) out << "initial     " << r.initial << "\n";
    out << "time        0 to " << shortest(r.t_reached) << " s of " << shortest(scene.output.t_end) << " s, rows every "
        << shortest(scene.output.dt_out) << " s";
    if (!scene.output.file.empty()) out << " in " << scene.output.file;
    out << "\n";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", r.max_abs_tip_uy);
    out << "max |tip_uy| " << buf << " m\n";
    print_invariant(out, r);
    if (r.estimated_error >= 0.0) {
        char line[240];
        std::snprintf(line, sizeof line, "%.2g of the largest value (%s), from %s re-run at rtol %g, atol %g",
                      r.estimated_error, r.error_column.c_str(), r.error_from.c_str(), r.check_rtol, r.check_atol);
        out << "error       " << line << "\n";
    }
    out << "steps       " << r.steps << " accepted, " << r.rejected_steps << " rejected by the error test\n";
    out << "RHS evals   " << r.rhs_evals << "\n";
    print_wall_time(out, r);
    if (!r.completed) out << "STOPPED     at t = " << shortest(r.t_reached) << " s: " << r.failure << "\n";
    return out.str();
}

}  // namespace hubbeam
