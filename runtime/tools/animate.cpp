// hubbeam plot animate: the deformed beam over time as an animated GIF, drawn by gnuplot's gif terminal from a
// fields CSV (hubbeam run --fields-at), in the plane or, for a blade with flap u_z, in three dimensions; with the
// run's CSV beside it, in the inertial frame, turned by the hub angle theta(t).
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "io/output_file.hpp"
#include "plot.hpp"
#include "text/csv_columns.hpp"
#include "text/printable.hpp"
#include "text/shortest.hpp"

namespace hubbeam {

namespace {

/// The most frames an animation takes: a GIF of 2000 frames is some megabytes already.
constexpr std::size_t max_frames = 2000;

/// The beam at one time: each point's place (m), and the tip's (the point farthest along the beam).
struct Frame {
    double t = 0.0, theta = 0.0;
    std::vector<double> x, y, z;
};

/// A CSV file's header and numeric rows; PlotInputError naming the file, line and column of a cell that is no number.
struct Table {
    std::string header;
    std::vector<std::vector<double>> rows;
};

Table read_table(const std::string& path, const char* what)
{
    if (const std::string kind = not_a_regular_file(path); !kind.empty())
        throw PlotInputError(printable(path, 400) + ": expected " + what + ", got " + kind);
    std::ifstream in(path);
    if (!in) throw PlotInputError(printable(path, 400) + ": cannot open: " + std::strerror(errno));
    Table t;
    std::getline(in, t.header);
    if (!t.header.empty() && t.header.back() == '\r') t.header.pop_back();
    std::string line;
    for (long n = 2; std::getline(in, line); ++n) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        std::vector<double> row;
        for (const std::string& cell : csv_fields(line)) {
            double v = 0.0;
            const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
            if (ec != std::errc() || end != cell.data() + cell.size())
                throw PlotInputError(printable(path, 400) + ":" + std::to_string(n) + ": expected numbers (" + what +
                                     "), got \"" + printable(cell, 40) + "\"");
            row.push_back(v);
        }
        t.rows.push_back(std::move(row));
    }
    return t;
}

/// theta at t from a run's rows (t, theta): exact at a row's time, linear between rows.
double theta_at(const std::vector<std::pair<double, double>>& run, double t, const std::string& file)
{
    const auto it = std::lower_bound(run.begin(), run.end(), t, [](const auto& r, double v) { return r.first < v; });
    if (it != run.end() && it->first == t) return it->second;
    if (it == run.begin() || it == run.end())
        throw PlotInputError(printable(file, 400) + ": expected rows from t = " + shortest(t) +
                             " s on (the fields' times), got rows from " + shortest(run.front().first) + " to " +
                             shortest(run.back().first) + " s");
    const auto& [t0, a] = *(it - 1);
    const auto& [t1, b] = *it;
    return a + (b - a) * (t - t0) / (t1 - t0);
}

/// The frames of a fields CSV, turned by the run's theta(t) where a run CSV is given.
std::vector<Frame> frames_of(const PlotArgs& args, bool& out_of_plane)
{
    const std::string& fields = args.files[0];
    const Table f = read_table(fields, "a fields CSV of hubbeam run --fields-at");
    const CsvColumns c(printable(fields, 400), f.header);
    const std::size_t it = c.at("t"), ix = c.at("x"), iuy = c.at("uy"), iux = c.at("ux");
    out_of_plane = f.header.find(",uz") != std::string::npos;
    const std::size_t iuz = out_of_plane ? c.at("uz") : 0;
    std::vector<std::pair<double, double>> run;
    if (args.files.size() == 2) {
        const Table r = read_table(args.files[1], "a run CSV of hubbeam run");
        const CsvColumns rc(printable(args.files[1], 400), r.header);
        const std::size_t rt = rc.at("t"), rth = rc.at("theta", "the hub angle");
        for (const auto& row : r.rows) run.emplace_back(row.at(rt), row.at(rth));
        if (run.empty()) throw PlotInputError(printable(args.files[1], 400) + ": expected rows, got none");
    }
    std::vector<Frame> frames;
    for (const auto& row : f.rows) {
        if (row.size() <= std::max({it, ix, iuy, iux, iuz}))
            throw PlotInputError(printable(fields, 400) + ": expected every row as long as its header");
        if (frames.empty() || frames.back().t != row[it]) {
            if (frames.size() == max_frames)
                throw PlotInputError(printable(fields, 400) + ": expected at most " + std::to_string(max_frames) +
                                     " times (frames), got more");
            frames.push_back({row[it], run.empty() ? 0.0 : theta_at(run, row[it], args.files[1]), {}, {}, {}});
        }
        Frame& fr = frames.back();
        // The point's place in the hub's frame (x + u_x along the beam, u_y across it), turned by theta.
        const double along = row[ix] + row[iux], across = row[iuy];
        fr.x.push_back(std::cos(fr.theta) * along - std::sin(fr.theta) * across);
        fr.y.push_back(std::sin(fr.theta) * along + std::cos(fr.theta) * across);
        fr.z.push_back(out_of_plane ? row[iuz] : 0.0);
    }
    if (frames.empty()) throw PlotInputError(printable(fields, 400) + ": expected rows, got none");
    return frames;
}

std::string number(double v)
{
    return shortest(v);
}

/// How far the frames reach: the largest distance from the axis in the plane, padded by 8 % (1 m if none), and the
/// range of u_z.
struct Extent {
    double reach = 0.0, zlo = 0.0, zhi = 0.0;
};

/// The frames' extent (Extent).
Extent extent_of(const std::vector<Frame>& frames)
{
    Extent e;
    for (const Frame& f : frames)
        for (std::size_t i = 0; i < f.x.size(); ++i) {
            e.reach = std::max({e.reach, std::abs(f.x[i]), std::abs(f.y[i])});
            e.zlo = std::min(e.zlo, f.z[i]);
            e.zhi = std::max(e.zhi, f.z[i]);
        }
    e.reach = e.reach > 0.0 ? 1.08 * e.reach : 1.0;
    return e;
}

/// The script's data: the beam at each frame ($beam), the tip's path ($tip), the hub's outline ($hub) and the
/// frames' times (T).
void print_data_blocks(std::ostringstream& s, const std::vector<Frame>& frames, double reach)
{
    s << "$beam << EOD\n";
    for (const Frame& f : frames) {
        for (std::size_t i = 0; i < f.x.size(); ++i)
            s << number(f.x[i]) << ' ' << number(f.y[i]) << ' ' << number(f.z[i]) << '\n';
        s << "\n\n";
    }
    s << "EOD\n$tip << EOD\n";
    for (const Frame& f : frames)
        s << number(f.x.back()) << ' ' << number(f.y.back()) << ' ' << number(f.z.back()) << '\n';
    s << "EOD\n$hub << EOD\n";
    const double r = 0.04 * reach;
    for (int k = 0; k <= 36; ++k)
        s << number(r * std::cos(k * M_PI / 18)) << ' ' << number(r * std::sin(k * M_PI / 18)) << " 0\n";
    s << "EOD\narray T[" << frames.size() << "] = [";
    for (std::size_t i = 0; i < frames.size(); ++i) s << (i ? "," : "") << number(frames[i].t);
    s << "]\n";
}

/// The script's key, grid and axes: the plane seen from above, or a blade's flapwise deflection in 3-D.
void print_axes(std::ostringstream& s, const Extent& extent, bool blade, bool turned)
{
    const double reach = extent.reach, zlo = extent.zlo, zhi = extent.zhi;
    s << "set key outside right top box\nset grid\n";
    s << "set xrange [" << number(-reach) << ":" << number(reach) << "]\nset yrange [" << number(-reach) << ":"
      << number(reach) << "]\n";
    const std::string frame = turned ? "inertial frame" : "the hub's frame";
    if (blade) {
        const double span = std::max(zhi - zlo, 0.05 * reach);
        s << "set zrange [" << number(zlo - 0.1 * span) << ":" << number(zhi + 0.1 * span) << "]\n"
          << "set view 60, 30\nset xlabel " << gnuplot_string("X (m, " + frame + ")")
          << "\nset ylabel 'Y (m)'\nset zlabel 'u_z (m, flap)' rotate parallel\nset ticslevel 0\n";
    } else {
        s << "set size ratio -1\nset xlabel " << gnuplot_string("X (m, " + frame + ")") << "\nset ylabel 'Y (m)'\n";
    }
}

/// The script's loop over the frames: the hub, the tip's path so far and the beam, titled by the time.
void print_frame_loop(std::ostringstream& s, std::size_t frame_count, bool blade, const std::string& title)
{
    s << "do for [i=1:" << frame_count << "] {\n  set title sprintf('%s, t = %.3f s', " << gnuplot_string(title)
      << ", T[i])\n";
    const char* cmd = blade ? "splot" : "plot";
    const char* cols = blade ? "1:2:3" : "1:2";
    s << "  " << cmd << " $hub using " << cols << " with lines lw 2 lc rgb '#555555' title 'hub', \\\n"
      << "    $tip every ::0::i-1 using " << cols << " with lines lc rgb '#d62728' title 'tip path', \\\n"
      << "    $beam index i-1 using " << cols << " with linespoints lw 3 pt 7 ps 0.6 lc rgb '#1f77b4' title 'beam'\n}\n"
      << "unset output\n";
}

}  // namespace

std::string animation_script(const PlotArgs& args, const std::string& gif)
{
    if (args.files.empty() || args.files.size() > 2)
        throw PlotInputError(
            "FILE: expected a fields CSV (hubbeam run --fields-at), and optionally the run's CSV "
            "for the hub angle, got " +
            std::to_string(args.files.size()) + " files");
    bool blade = false;
    const std::vector<Frame> frames = frames_of(args, blade);
    const Extent extent = extent_of(frames);
    const bool turned = args.files.size() == 2;
    std::ostringstream s;
    s << "# hubbeam plot animate: " << frames.size() << " frames of " << printable(args.files[0], 400)
      << (turned ? ", turned by theta(t) of " + printable(args.files[1], 400) : std::string(", in the hub's frame"))
      << "\n# $beam: one block per frame (x y z, m); $tip: the tip at each frame; $hub: the hub's outline.\n";
    s << "set terminal gif animate delay 8 size 900,720 font 'Sans,11' noenhanced\nset output " << gnuplot_string(gif)
      << "\n";
    print_data_blocks(s, frames, extent.reach);
    const std::string title = args.title.empty() ? std::string("Deformed beam") : args.title;
    print_axes(s, extent, blade, turned);
    print_frame_loop(s, frames.size(), blade, title);
    return s.str();
}

std::string draw_animation(const PlotArgs& args)
{
    std::vector<NamedPath> inputs;
    for (const std::string& f : args.files) inputs.push_back({f, "the input " + printable(f, 400)});
    if (args.prefix.empty()) throw PlotInputError("-o: expected a path prefix for PREFIX.gif, got \"\"");
    check_outputs(inputs, {{args.prefix + ".gp", "-o"}, {args.prefix + ".gif", "-o"}});
    std::string script;
    try {
        script = animation_script(args, args.prefix + ".gif");  // the inputs read and checked first
    } catch (const CsvColumnError& e) {
        throw PlotInputError(e.what());
    }
    // gnuplot draws into the GIF's temporary file, renamed over PREFIX.gif only when whole.
    std::unique_ptr<OutputFile> gif;
    const std::filesystem::path p(args.prefix);
    for (int attempt = 0; !gif; ++attempt) {
        std::string name = ".";  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + string
        name += p.filename().string();
        name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(attempt) + ".gif";
        const std::string temp = (p.parent_path() / name).string();
        try {
            gif = std::make_unique<OutputFile>(args.prefix + ".gif", temp);
        } catch (const OutputFile::TempExists&) {
            if (attempt >= 100) throw std::runtime_error(args.prefix + ": cannot create its temporary animation");
        }
    }
    OutputFile gp(args.prefix + ".gp");
    if (const int error = gp.write(script); error != 0)
        return printable(args.prefix, 400) + ".gp: write failed: " + std::strerror(error) + " (no animation replaced)";
    OutputFile draw(gif->temp_path() + ".gp");
    if (const int error = draw.write(animation_script(args, gif->temp_path())); error != 0)
        return printable(draw.temp_path(), 400) + ": write failed: " + std::strerror(error);
    const std::string problem = run_gnuplot(draw.temp_path());
    draw.discard();
    if (!problem.empty()) return problem;
    // A whole GIF begins with its signature and ends with its trailer byte (0x3B).
    std::ifstream in(gif->temp_path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 14 || bytes.compare(0, 6, "GIF89a") != 0 || bytes.back() != '\x3b')
        return printable(args.prefix, 400) +
               ".gif: gnuplot wrote an incomplete file (a full disk?); the old one is as "
               "it was";
    if (const std::string why = gp.commit(); !why.empty()) return printable(args.prefix, 400) + ".gp: " + why;
    if (const std::string why = gif->commit(); !why.empty()) return printable(args.prefix, 400) + ".gif: " + why;
    return {};
}

}  // namespace hubbeam
