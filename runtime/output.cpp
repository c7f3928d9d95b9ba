// CSV rows and the run summary.
#include "output.hpp"

#include "shortest.hpp"

#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace hubbeam {

CsvWriter::CsvWriter(const std::string& path) : path_(path)
{
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
    ok_ = std::fprintf(file_, "%s\n", row_header()) > 0 && std::fflush(file_) == 0;
}

CsvWriter::~CsvWriter()
{
    if (file_) std::fclose(file_);
}

void CsvWriter::write(const Row& row)
{
    const std::string line = csv_line(row) + '\n';
    if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) ok_ = false;
    else ++rows_;
}

RowSink CsvWriter::sink()
{
    return [this](const Row& row) { write(row); };
}

std::string csv_line(const Row& row)
{
    std::string s;
    s.reserve(200);
    const double columns[] = {row.t,      row.theta,   row.theta_dot, row.tip_uy,  row.tip_ux1,
                              row.tip_ux, row.kinetic, row.potential, row.momentum, row.jacobi};
    for (std::size_t i = 0; i < std::size(columns); ++i) {
        if (i) s += ',';
        append_shortest(s, columns[i]);
    }
    return s;
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
    out << "stepper     " << scene.solver.stepper << ", rtol " << shortest(scene.solver.rtol) << ", atol "
        << shortest(scene.solver.atol) << ", h0 " << shortest(scene.solver.h0) << " s\n";
    out << "time        0 to " << shortest(r.t_reached) << " s of " << shortest(scene.output.t_end) << " s, rows every "
        << shortest(scene.output.dt_out) << " s";
    if (!scene.output.file.empty()) out << " in " << scene.output.file;
    out << "\n";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", r.max_abs_tip_uy);
    out << "max |tip_uy| " << buf << " m\n";
    out << "steps       " << r.steps << "\n";
    out << "RHS evals   " << r.rhs_evals << "\n";
    std::snprintf(buf, sizeof buf, "%.3f", r.wall_seconds);
    out << "wall time   " << buf << " s\n";
    if (!r.completed) out << "STOPPED     at t = " << shortest(r.t_reached) << " s: " << r.failure << "\n";
    return out.str();
}

}  // namespace hubbeam
