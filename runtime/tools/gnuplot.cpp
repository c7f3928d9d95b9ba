// Figures with gnuplot: the look they share, text quoted for a script, and gnuplot's run into temporary files that
// replace the figures only when whole.
#include "gnuplot.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>

namespace hubbeam {

std::string gnuplot_string(std::string_view text, const std::string& name)
{
    // Inside single quotes gnuplot reads every byte as it is but a quote (below) and the line's end: a newline in
    // a name would end the string's command, and the next line is gnuplot's to run ('!' hands it to the shell).
    check_handed_text<PlotInputError>(name, text, "text");
    if (text.find('\'') == std::string_view::npos) return "'" + std::string(text) + "'";
    // Not 'it''s': gnuplot 5.4 misreads two doubled quotes in a row. Each quote is a "'" of its own, concatenated
    // (a double-quoted string holding more would run any `command` in backquotes).
    std::string s = "(";
    std::size_t start = 0;
    while (true) {
        const std::size_t quote = text.find('\'', start);
        const std::string_view part = text.substr(start, quote == std::string_view::npos ? quote : quote - start);
        if (!part.empty()) s += (s.size() > 1 ? "." : "") + ("'" + std::string(part) + "'");
        if (quote == std::string_view::npos) return s + ")";
        s += (s.size() > 1 ? "." : "") + std::string("\"'\"");
        start = quote + 1;
    }
}

void check_prefix(const std::string& option, const std::string& prefix)
{
    if (prefix.empty()) bad_option<OutputRefused>(option, "a path prefix for the figure's files", "");
    check_handed_text<OutputRefused>(option, prefix, "a path prefix");
    // The files are PREFIX.png and so on: a prefix that names a folder (DIR/, DIR/., ..) would make them the hidden
    // DIR/.png or the names ..png, ...png beside it.
    if (const std::string name = std::filesystem::path(prefix).filename().string();
        name.empty() || name == "." || name == "..")
        throw OutputRefused(option + ": expected a path prefix that ends in a file name (as DIR/NAME for " +
                            "DIR/NAME.png), got \"" + printable(prefix, 400) + "\", which names a folder");
}

std::string figure_style()
{
    return "set datafile separator ','\n"
           "set key outside right top box width 2\n"
           "set grid\n";
}

std::string in_png_and_svg(const std::string& figures)
{
    return "do for [term in 'pngcairo svg'] {\n"
           "  ext = (term eq 'svg') ? 'svg' : 'png'\n"
           "  if (term eq 'svg') { set terminal svg size 1000,640 font 'Sans,12' } else { set terminal pngcairo size "
           "1000,640 font 'Sans,11' }\n" +
           figures + "}\n";
}

std::string figure_output(const std::string& prefix)
{
    return "  set output " + gnuplot_string(prefix + ".") + ".ext\n";
}

std::string run_gnuplot(const std::string& script_path)
{
    // The path in the shell's single quotes, its own quotes as '\'' (close, escaped quote, reopen).
    std::string quoted = "'";
    for (const char c : script_path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    const std::string command = "gnuplot " + quoted + "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return "cannot run gnuplot";
    std::string messages;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe) != nullptr) messages += buf;
    const int status = ::pclose(pipe);
    while (!messages.empty() && (messages.back() == '\n' || messages.back() == ' ')) messages.pop_back();
    if (status != 0) return "gnuplot failed (is it installed? apt-get install gnuplot-nox): " + messages;
    return {};
}

namespace {

/// Whether gnuplot's figure at path ends as a whole PNG (its IEND chunk) or SVG (the closing tag) does: a full disk or
/// a file size limit cuts it, and gnuplot does not always say so.
bool complete_figure(const std::string& path, bool png)
{
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return false;
    if (png) {
        static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
        return text.size() >= 20 && text.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 &&
               text.compare(text.size() - iend.size(), iend.size(), iend) == 0;
    }
    const std::size_t end = text.find_last_not_of(" \t\r\n");
    return end != std::string::npos && end >= 5 && text.compare(end - 5, 6, "</svg>") == 0;
}

}  // namespace

std::string draw_figures(const std::vector<std::string>& prefixes, const std::string& script_path,
                         const std::string& script,
                         const std::function<std::string(const std::vector<std::string>&)>& script_for)
{
    // Each figure gets its lock and its temporary files DIR/.NAME.tmp-PID.png and .svg first: one prefix, since
    // the script derives both names from it.
    std::vector<std::unique_ptr<OutputFile>> figures;
    std::vector<std::string> temp_prefixes;
    for (const std::string& prefix : prefixes) {
        check_prefix("PREFIX", prefix);  // for every caller (plot, bench --plot, modes --plot), whatever it checked
        const std::filesystem::path p(prefix);
        for (int attempt = 0;; ++attempt) {
            std::string name = ".";
            name += p.filename().string();
            name += ".tmp-" + std::to_string(::getpid()) + (attempt ? "-" + std::to_string(attempt) : "");
            const std::string temp = (p.parent_path() / name).string();
            try {
                auto png = std::make_unique<OutputFile>(prefix + ".png", temp + ".png");
                auto svg = std::make_unique<OutputFile>(prefix + ".svg", temp + ".svg");
                figures.push_back(std::move(png));
                figures.push_back(std::move(svg));
                temp_prefixes.push_back(temp);
                break;
            } catch (const OutputFile::TempExists&) {
                if (attempt >= 100) throw std::runtime_error(prefix + ": cannot create its temporary figures");
            }
        }
    }
    OutputFile gp(script_path);
    if (const int error = gp.write(script); error != 0)
        return printable(script_path, 400) + ": write failed: " + std::strerror(error) + " (no figure replaced)";
    // gnuplot draws into the temporary files, from a script of its own beside them (removed afterwards).
    OutputFile draw(temp_prefixes.front() + ".gp");
    if (const int error = draw.write(script_for(temp_prefixes)); error != 0)
        return printable(draw.temp_path(), 400) + ": write failed: " + std::strerror(error) + " (no figure replaced)";
    const std::string problem = run_gnuplot(draw.temp_path());
    draw.discard();
    if (!problem.empty()) return problem;
    for (std::size_t i = 0; i < figures.size(); ++i)
        if (!complete_figure(figures[i]->temp_path(), i % 2 == 0))
            return printable(figures[i]->path(), 400) + ": gnuplot wrote an incomplete file (a full disk?); the old "
                   "figures are as they were";
    if (const std::string why = gp.commit(); !why.empty()) return printable(script_path, 400) + ": " + why;
    for (const auto& f : figures)
        if (const std::string why = f->commit(); !why.empty()) return printable(f->path(), 400) + ": " + why;
    return {};
}

}  // namespace hubbeam
