// hubbeam bench --plot: the work-precision and DOF figures drawn by gnuplot from the bench CSV, with the data
// files their script reads.
#include "bench_parts.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/shortest.hpp>
#include <map>
#include <ostream>

#include "plot.hpp"

namespace hubbeam {

using namespace bench_parts;

namespace {

/// The figures' script and the data files beside the CSV that it reads.
struct BenchFigures {
    std::string script, front, dofs;
};

/// A finished run of the bench CSV, as the figures draw it.
struct FigurePoint {
    std::string method, stepper;
    int ny;
    double wall, error;  // s; m, the larger of its two errors
};

/// The bench CSV at csv's finished runs, read back by column name.
std::vector<FigurePoint> read_points(const std::string& csv)
{
    std::vector<FigurePoint> points;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    const CsvColumns columns(csv, line);
    const std::size_t method = columns.at("method"), stepper = columns.at("stepper"), ny = columns.at("ny"),
                      wall = columns.at("wall_median"), time_error = columns.at("time_error"),
                      disc_error = columns.at("disc_error"), status = columns.at("status");
    while (std::getline(in, line)) {
        const std::vector<std::string> f = csv_fields(line);
        if (f.size() != columns.size() || f[status] != "ok") continue;
        points.push_back({f[method], f[stepper], std::atoi(f[ny].c_str()), std::atof(f[wall].c_str()),
                          std::max(std::atof(f[time_error].c_str()), std::atof(f[disc_error].c_str()))});
    }
    return points;
}

/// The series the points make, each sorted: (method, stepper) pairs and methods as indices into words<Method>()
/// and stepper_names(), so that a method keeps its colour and a stepper its marker from one figure to the next.
struct FigureSeries {
    std::vector<std::pair<std::size_t, std::size_t>> lines;  // (method, stepper): a line of the work figure each
    std::vector<std::size_t> methods;                        // a line of the DOF figure each
    std::vector<int> nys;                                    // the DOF figure's ticks
};

FigureSeries figure_series(const std::vector<FigurePoint>& points)
{
    const std::vector<std::string> all_steppers = steppers_and_auto(), method_names = words<Method>();
    const auto index = [](const std::vector<std::string>& names, const std::string& name) {
        return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    FigureSeries s;
    for (const FigurePoint& p : points) {
        add_unique(s.lines, std::make_pair(index(method_names, p.method), index(all_steppers, p.stepper)));
        add_unique(s.methods, index(method_names, p.method));
        add_unique(s.nys, p.ny);
    }
    std::sort(s.lines.begin(), s.lines.end());
    std::sort(s.methods.begin(), s.methods.end());
    std::sort(s.nys.begin(), s.nys.end());
    return s;
}

/// A name of a method or stepper in the script's quotes.
std::string quoted(const std::string& s)
{
    return "'" + s + "'";
}

/// The work figure's plot command: a line per method and stepper read from the CSV (a colour per method, a point
/// type and dash pattern per stepper, so that no two lines look alike), and the Pareto front from PREFIX-front.dat.
std::string work_plot(const std::string& prefix, const std::string& csv, const FigureSeries& series)
{
    const std::vector<std::string> all_steppers = steppers_and_auto(), method_names = words<Method>();
    static const char* const dashes[] = {"1", "2", "3", "4", "5", "(20,6,3,6,3,6)", "(4,8)", "(30,10)"};
    std::string work = "  plot ";
    for (std::size_t i = 0; i < series.lines.size(); ++i) {
        const auto [m, st] = series.lines[i];
        work += (i ? ", \\\n       " : "") + quoted(csv) + " using (strcol('method') eq " + quoted(method_names[m]) +
                " && strcol('stepper') eq " + quoted(all_steppers[st]) +
                " && strcol('status') eq 'ok' ? column('wall_median') : NaN):(larger(column('time_error'), column('disc_error')))"
                " with linespoints lw 1.5 lc " +
                std::to_string(m + 1) + " pt " + std::to_string(st % 13 + 1) + " dt " + dashes[st % 8] +
                " title " + quoted(method_names[m] + " " + all_steppers[st]);
    }
    return work + ", \\\n       '" + prefix +
           "-front.dat' using 'wall':'error' with steps lw 3 lc rgb 'black' title 'Pareto front'";
}

/// The DOF figure's axis settings and plot command: the smallest error per method against Ny from PREFIX-dofs.dat,
/// ticks at the grid's Ny, and the reference's resolution when known.
std::string dofs_plot(const std::string& prefix, const FigureSeries& series, double resolution)
{
    const std::vector<std::string> method_names = words<Method>();
    std::string dofs = "  plot ";
    for (std::size_t i = 0; i < series.methods.size(); ++i)
        dofs += (i ? ", \\\n       " : "") +
                ("'" + prefix + "-dofs.dat' using (strcol('method') eq " + quoted(method_names[series.methods[i]]) +
                 " ? column('ny') : NaN):'error' " + "with linespoints lw 2 pt 7 lc " +
                 std::to_string(series.methods[i] + 1) + " title " + quoted(method_names[series.methods[i]]));
    if (resolution > 0.0)
        dofs += ", \\\n       " + shortest(resolution) +
                " with lines dt 2 lw 2 lc rgb 'gray40' title 'reference resolution'";
    std::string ny_tics, ny_range;
    for (const int n : series.nys) ny_tics += (ny_tics.empty() ? "" : ", ") + std::to_string(n);
    if (!series.nys.empty())  // a little beyond the grid's Ny on either side, not the decades around them
        ny_range =
            "  set xrange [" + shortest(series.nys.front() / 1.15) + ":" + shortest(series.nys.back() * 1.15) + "]\n";
    return "  set xtics (" + ny_tics + ")\n" + ny_range + dofs;
}

/// PREFIX-front.dat: the points on the Pareto front (errors within the reference's resolution are ties).
std::string front_data(const std::vector<FigurePoint>& points, double resolution)
{
    std::vector<WorkPoint> plane;
    for (const FigurePoint& p : points) plane.push_back({p.wall, p.error});
    std::string front = "wall,error\n";
    for (const std::size_t i : pareto_front(plane, resolution))
        front += shortest(points[i].wall) + "," + shortest(points[i].error) + "\n";
    return front;
}

/// PREFIX-dofs.dat: the smallest error per method and Ny.
std::string dofs_data(const std::vector<FigurePoint>& points)
{
    std::map<std::pair<std::string, int>, double> smallest;
    for (const FigurePoint& p : points) {
        auto [it, added] = smallest.emplace(std::make_pair(p.method, p.ny), p.error);
        if (!added) it->second = std::min(it->second, p.error);
    }
    std::string dofs = "method,ny,error\n";
    for (const auto& [k, e] : smallest) dofs += k.first + "," + std::to_string(k.second) + "," + shortest(e) + "\n";
    return dofs;
}

/// The figures of the bench CSV at csv (drawn to figures[0], the work against precision, and figures[1], the error
/// against Ny) and the data files they read beside it, computed here.
BenchFigures bench_figures(const std::string& prefix, const std::vector<std::string>& figures, const std::string& csv,
                           const std::string& scene, double resolution)
{
    const std::vector<FigurePoint> points = read_points(csv);
    const FigureSeries series = figure_series(points);
    BenchFigures f;
    f.script = "# gnuplot script written by hubbeam bench: work-precision figures from " + csv + "\n" + figure_style() +
               "set logscale xy\n"
               "set format y '10^{%L}'\n"
               "larger(a, b) = a > b ? a : b\n" +
               in_png_and_svg(figure_output(figures[0]) + "  set title " +
                              gnuplot_string("Work against precision, " + scene +
                                             ": tip deflection error against the converged solution") +
                              " noenhanced\n"
                              "  set xlabel 'wall time per run (s, in process, median)'\n"
                              "  set ylabel 'max |tip u_y - reference| (m)'\n"
                              "  set xtics autofreq\n"
                              "  set autoscale x\n" +
                              work_plot(prefix, csv, series) + "\n" + figure_output(figures[1]) + "  set title " +
                              gnuplot_string("Discretization error against DOF count, " + scene +
                                             " (the smallest error of each method and Ny)") +
                              " noenhanced\n"
                              "  set xlabel 'transverse DOFs N_y'\n"
                              "  set ylabel 'max |tip u_y - converged reference| (m)'\n" +
                              dofs_plot(prefix, series, resolution) + "\n");
    f.front = front_data(points, resolution);
    f.dofs = dofs_data(points);
    return f;
}

}  // namespace

std::string bench_parts::plot(const std::string& prefix, const std::string& csv, const std::string& scene,
                              double resolution, std::ostream& out)
{
    const std::vector<std::string> names = {prefix + figure_suffixes[0], prefix + figure_suffixes[1]};
    const BenchFigures figures = bench_figures(prefix, names, csv, scene, resolution);
    const std::string script_path = prefix + script_suffix;
    // The data the script reads beside the CSV, then the figures (draw_figures draws them into temporary files).
    for (const auto& [path, text] : {std::pair{prefix + data_suffixes[0], figures.front},
                                     std::pair{prefix + data_suffixes[1], figures.dofs}}) {
        OutputFile file(path);
        if (const int error = file.write(text); error != 0) return path + ": write failed: " + std::strerror(error);
        if (const std::string why = file.commit(); !why.empty()) return path + ": " + why;
    }
    if (const std::string problem =
            draw_figures(names, script_path, figures.script,
                         [&](const std::vector<std::string>& temp) {
                             return bench_figures(prefix, temp, csv, scene, resolution).script;
                         });
        !problem.empty())
        return problem;
    out << "figures: " << names[0] << ".{png,svg}, " << names[1] << ".{png,svg} (script " << script_path << ")\n";
    return {};
}

}  // namespace hubbeam
