// hubbeam plot animate: the deformed beam over time as an animated GIF, drawn by gnuplot's gif terminal from a
// fields CSV (hubbeam run --fields-at), in the plane or, for a blade with flap u_z, in three dimensions; with the
// run's CSV beside it, in the inertial frame, turned by the hub angle theta(t).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>
#include <iterator>
#include <memory>
#include <sstream>

#include "plot.hpp"

namespace hubbeam {

namespace {

/// The most frames an animation takes: a GIF of 2000 frames (160 s at 12.5 frames a second) is some megabytes
/// already.
constexpr std::size_t max_frames = 2000;
/// The most rows (points of all frames) a fields CSV may hold: 2000 frames of 100 points. gnuplot's time grows with
/// the frames and their points: 2000 frames of 81 points cost it 27 s, of 196 points 39 s (docs/cli.md).
constexpr std::size_t max_field_rows = 200000;
/// The most rows of the run CSV read for the hub angle: a run of 1000 s written every millisecond (2 s to read).
constexpr std::size_t max_run_rows = 1000000;
/// The largest file read, in bytes: a run CSV of max_run_rows rows of a blade's 13 columns is about 230 MiB, a fields
/// CSV of max_field_rows rows of 12 columns 60 MiB. Checked before the file is read, so that a huge file costs nothing.
constexpr std::uintmax_t max_bytes = 256u << 20;

/// The beam at one time: each point's place (m), and the tip's (the point farthest along the beam).
struct Frame {
    double t = 0.0, theta = 0.0;
    std::vector<double> x, y, z;
};

/// What a CSV of the animation is ("a fields CSV of hubbeam run --fields-at"), the columns read from it (by name,
/// with what each is for a message), and how many rows it may hold.
struct TableFormat {
    const char* what;
    std::vector<std::pair<const char*, const char*>> columns;  // (name, meaning)
    std::size_t max_rows;
};

/// The columns of a table that the animation reads (TableFormat's, a missing optional one absent), per row.
struct Table {
    std::vector<std::string> names;  // of the columns read, in the format's order
    std::vector<std::vector<double>> rows;
    std::vector<long> lines;  // each row's line number in the file, for messages
};

/// Reads format's columns of path, every value a finite number; a file larger than max_bytes, with more than
/// format.max_rows rows, a column missing or a value that is no finite number throws PlotInputError naming the file
/// (and the line, the column's number and name), never quoting it. optional names a column that may be absent.
Table read_table(const std::string& path, const TableFormat& format, const char* optional = nullptr)
{
    const std::string file = printable(path, 400);
    const auto bad = [&](const std::string& why) { throw PlotInputError(file + ": " + why); };
    if (const std::string kind = not_a_regular_file(path); !kind.empty())
        bad("expected " + std::string(format.what) + ", got " + kind);
    if (struct stat st {}; ::stat(path.c_str(), &st) == 0 && static_cast<std::uintmax_t>(st.st_size) > max_bytes)
        bad("expected " + std::string(format.what) + " of at most " + std::to_string(max_bytes >> 20) +
            " MiB (plot animate's limit), got " + std::to_string(static_cast<std::uintmax_t>(st.st_size) >> 20) +
            " MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) bad(std::string("cannot open: ") + std::strerror(errno));
    std::string header;
    std::getline(in, header);
    if (!header.empty() && header.back() == '\r') header.pop_back();
    const CsvColumns columns(file, header);
    Table t;
    std::vector<std::size_t> at;
    for (const auto& [name, meaning] : format.columns) {
        if (optional != nullptr && std::string_view(name) == optional && !columns.has(name)) continue;
        at.push_back(columns.at(name, meaning));
        t.names.emplace_back(name);
    }
    std::string line;
    for (long n = 2; std::getline(in, line); ++n) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        if (t.rows.size() == format.max_rows)
            bad("expected at most " + std::to_string(format.max_rows) + " rows (plot animate's limit), got more");
        const std::vector<std::string> cells = csv_fields(line);
        if (cells.size() != columns.size())
            bad("line " + std::to_string(n) + ": expected " + std::to_string(columns.size()) +
                " comma-separated fields as in the header, got " + std::to_string(cells.size()));
        std::vector<double> row;
        for (std::size_t k = 0; k < at.size(); ++k) {
            const std::string& cell = cells[at[k]];
            double v = 0.0;
            const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
            // Named by line, column number and name, never quoted (a message quotes no file's content). NaN or an
            // infinity would reach gnuplot as a point it cannot place, and fail the whole animation there.
            const std::string where = "line " + std::to_string(n) + ", column " + std::to_string(at[k] + 1) + " (" +
                                      t.names[k] + "): expected a finite number, got ";
            if (ec != std::errc() || end != cell.data() + cell.size())
                bad(where + (cell.empty() ? std::string("an empty field")
                                          : std::to_string(cell.size()) + " characters that are not a number"));
            if (!std::isfinite(v)) bad(where + (std::isnan(v) ? "NaN" : "an infinity"));
            row.push_back(v);
        }
        t.rows.push_back(std::move(row));
        t.lines.push_back(n);
    }
    if (in.bad()) bad(std::string("cannot read: ") + std::strerror(errno));
    return t;
}

/// theta at t from a run's rows (t, theta), their times increasing: exact at a row's time, linear between rows.
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

/// The frames of a fields CSV, turned by the run's theta(t) where a run CSV is given. The frames' times must
/// increase (the rows of one time together), and so must the run's rows' times: theta_at looks them up by bisection,
/// and a run CSV out of order would turn the beam by the wrong angle without a word.
std::vector<Frame> frames_of(const PlotArgs& args, bool& out_of_plane)
{
    const std::string& fields = args.files[0];
    const Table f =
        read_table(fields,
                   {"a fields CSV of hubbeam run --fields-at",
                    {{"t", "time, s"}, {"x", "position, m"}, {"uy", "m"}, {"ux", "m"}, {"uz", "a blade's flap, m"}},
                    max_field_rows},
                   "uz");
    out_of_plane = f.names.size() == 5;
    std::vector<std::pair<double, double>> run;
    if (args.files.size() == 2) {
        const std::string& run_file = args.files[1];
        const Table r = read_table(
            run_file, {"a run CSV of hubbeam run", {{"t", "time, s"}, {"theta", "the hub angle"}}, max_run_rows});
        for (std::size_t k = 0; k < r.rows.size(); ++k) {
            if (k > 0 && !(r.rows[k][0] > r.rows[k - 1][0]))
                throw PlotInputError(
                    printable(run_file, 400) + ": line " + std::to_string(r.lines[k]) +
                    ": expected times t increasing from row to row, as hubbeam run writes them, got " +
                    (r.rows[k][0] == r.rows[k - 1][0] ? "the time of the row before" : "an earlier time"));
            run.emplace_back(r.rows[k][0], r.rows[k][1]);
        }
        if (run.empty()) throw PlotInputError(printable(run_file, 400) + ": expected rows, got none");
    }
    std::vector<Frame> frames;
    for (std::size_t k = 0; k < f.rows.size(); ++k) {
        const std::vector<double>& row = f.rows[k];
        const double t = row[0], x = row[1], uy = row[2], ux = row[3];
        if (frames.empty() || frames.back().t != t) {
            if (!frames.empty() && !(t > frames.back().t))
                throw PlotInputError(printable(fields, 400) + ": line " + std::to_string(f.lines[k]) +
                                     ": expected the frames' times t increasing (the rows of a time together, as "
                                     "hubbeam run writes them), got an earlier time");
            if (frames.size() == max_frames)
                throw PlotInputError(printable(fields, 400) + ": expected at most " + std::to_string(max_frames) +
                                     " times (frames; plot animate's limit), got more");
            frames.push_back({t, run.empty() ? 0.0 : theta_at(run, t, args.files[1]), {}, {}, {}});
        }
        Frame& fr = frames.back();
        // The point's place in the hub's frame (x + u_x along the beam, u_y across it), turned by theta.
        const double along = x + ux, across = uy;
        fr.x.push_back(std::cos(fr.theta) * along - std::sin(fr.theta) * across);
        fr.y.push_back(std::sin(fr.theta) * along + std::cos(fr.theta) * across);
        fr.z.push_back(out_of_plane ? row[4] : 0.0);
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
    s << "do for [i=1:" << frame_count << "] {\n  set title sprintf('%s, t = %.3f s', "
      << gnuplot_string(title, "--title") << ", T[i])\n";
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
    check_plot_args(args);
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
    s << "set terminal gif animate delay 8 size 900,720 font 'Sans,11' noenhanced\nset output "
      << gnuplot_string(gif, "-o") << "\n";
    print_data_blocks(s, frames, extent.reach);
    const std::string title = args.title.empty() ? std::string("Deformed beam") : args.title;
    print_axes(s, extent, blade, turned);
    print_frame_loop(s, frames.size(), blade, title);
    return s.str();
}

std::string draw_animation(const PlotArgs& args)
{
    check_plot_args(args);  // the prefix and every text the script holds, before anything is read or written
    std::vector<NamedPath> inputs;
    for (const std::string& f : args.files) inputs.push_back({f, "the input " + printable(f, 400)});
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
