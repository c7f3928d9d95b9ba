// Figures with gnuplot: the shared look and the run of gnuplot.
#include "plot.hpp"

#include <cstdio>
#include <string>

namespace hubbeam {

std::string gnuplot_string(std::string_view text)
{
    std::string s = "'";
    for (const char c : text) s += c == '\'' ? std::string("''") : std::string(1, c);
    return s + "'";
}

std::string figure_style()
{
    return "set datafile separator ','\n"
           "set key outside right top box\n"
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

std::string figure_output(const std::string& prefix) { return "  set output " + gnuplot_string(prefix + ".") + ".ext\n"; }

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

}  // namespace hubbeam
