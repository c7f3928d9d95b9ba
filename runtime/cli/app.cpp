// The command line's app, the one file that compiles CLI11 (its inline functions took about 7 s in each file that
// included it: docs/performance.md, "Set-up"): the options the commands declare through command.hpp's Subcommand and
// Option, the commands added to the app, the parse and its messages, and the run of the command given.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <exception>
#include <hubbeam/printable.hpp>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.hpp"

namespace hubbeam::cli {

Option& Option::required()
{
    option_->required();
    return *this;
}

Option& Option::type_name(const std::string& name)
{
    option_->type_name(name);
    return *this;
}

Option& Option::excludes(const Option& other)
{
    option_->excludes(other.option_);
    return *this;
}

bool Option::given() const
{
    return option_ != nullptr && option_->count() > 0;
}

Subcommand::Subcommand(CLI::App& app, const std::string& name, const std::string& description)
    : sub_(app.add_subcommand(name, description))
{
}

Option Subcommand::add_option(const std::string& name, std::string& value, const std::string& help)
{
    return Option(sub_->add_option(name, value, help));
}

Option Subcommand::add_option(const std::string& name, std::vector<std::string>& values, const std::string& help)
{
    return Option(sub_->add_option(name, values, help));
}

Option Subcommand::add_flag(const std::string& name, bool& value, const std::string& help)
{
    return Option(sub_->add_flag(name, value, help));
}

void Subcommand::footer(const std::string& text)
{
    sub_->footer(text);
}

void Subcommand::pass_arguments_through()
{
    sub_->prefix_command();
    sub_->set_help_flag();
}

std::vector<std::string> Subcommand::remaining() const
{
    return sub_->remaining();
}

namespace {

/// The number of single-character insertions, deletions and substitutions that turn a into b (Levenshtein).
std::size_t edit_distance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// The one of names nearest to word when word is a likely typo of it (at most two edits, a swap of two letters
/// being two, and fewer than word has letters), else empty.
std::string nearest_name(const std::string& word, const std::vector<std::string>& names)
{
    std::string nearest;
    std::size_t best = 0;
    for (const std::string& name : names)
        if (const std::size_t d = edit_distance(word, name); nearest.empty() || d < best) nearest = name, best = d;
    return best <= 2 && best < word.size() ? nearest : std::string();
}

/// Why the first argument names no command (empty if it names one, or is an option such as --help): the word
/// itself, the nearest command when it is a likely typo, and the list of commands.
std::string unknown_command(const std::vector<Command>& commands, int argc, char** argv)
{
    std::vector<std::string> names;
    for (const Command& c : commands) names.push_back(c.sub->get_name());
    const std::string list = "one of " + hubbeam::joined(names) + " (hubbeam --help)";
    if (argc < 2) return "a command is required: " + list;
    const std::string word = argv[1];
    if (word.rfind('-', 0) == 0 || std::find(names.begin(), names.end(), word) != names.end()) return {};
    const std::string nearest = nearest_name(word, names);
    return "unknown command '" + hubbeam::printable(word, 40) + "'" +
           (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") + "; expected " + list;
}

/// For arguments the command does not take (CLI11's ExtrasError): the first that looks like an option, with the
/// command's option nearest to it when it is a likely typo ("--methd": did you mean '--method'?); empty otherwise.
std::string unknown_option(const CLI::App& command, const std::vector<std::string>& extras)
{
    std::vector<std::string> names;
    for (const CLI::Option* o : command.get_options()) {
        for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
        for (const std::string& s : o->get_snames()) names.push_back("-" + s);
    }
    for (const std::string& word : extras) {
        if (word.rfind('-', 0) != 0) continue;
        const std::string name = word.substr(0, word.find('='));  // --methd=fem
        const std::string nearest = nearest_name(name, names);
        return "unknown option '" + hubbeam::printable(name, 40) + "'" +
               (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") + "; " + command.get_name() +
               " --help lists its options";
    }
    return {};
}

/// The commands, each with the function that adds it to the app.
const std::array<std::pair<const char*, Command (*)(CLI::App&)>, 10> command_table = {{
    {"run", add_run_command},
    {"variants", add_variants_command},
    {"bench", add_bench_command},
    {"stress", add_stress_command},
    {"modes", add_modes_command},
    {"linearize", add_linearize_command},
    {"sweep", add_sweep_command},
    {"kernels", add_kernels_command},
    {"plot", add_plot_command},
    {"import", add_import_command},
}};

/// The commands added to app: only the one argv names when it names one (its options alone are built: a run's
/// start-up pays for no other command's option tables, 0.82 million instructions), else all of them (for
/// --help, --version, and the message for an unknown command).
std::vector<Command> add_commands(CLI::App& app, int argc, char** argv)
{
    const auto added = [&](const char* name, Command (*add)(CLI::App&)) {
        Command c = add(app);
        if (c.sub->get_name() != name)
            throw std::logic_error("command_table names " + std::string(name) + " where the command is " +
                                   c.sub->get_name());
        return c;
    };
    for (const auto& [name, add] : command_table)
        if (argc >= 2 && std::string(argv[1]) == name) return {added(name, add)};
    std::vector<Command> commands;
    for (const auto& [name, add] : command_table) commands.push_back(added(name, add));
    return commands;
}

}  // namespace

int run_command_line(int argc, char** argv, const std::string& version)
{
    CLI::App app{"hubbeam: rotating flexible hub-beam simulator (equations derived by GiNaC, integrated by GSL).\n" +
                 std::string(exit_codes_help)};
    app.require_subcommand(1);
    app.set_version_flag("--version", version, "Print the version and exit");
    const std::vector<Command> commands = add_commands(app, argc, argv);
    if (const std::string why = unknown_command(commands, argc, argv); !why.empty()) {
        std::cerr << "hubbeam: " << why << "\n";
        return exit_bad_input;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::string why;
        if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr)
            for (const Command& c : commands)
                if (c.sub->parsed() && why.empty()) why = unknown_option(*c.sub, c.sub->remaining());
        std::cerr << "hubbeam: " << (why.empty() ? std::string(e.what()) : why) << "\n";
        return exit_bad_input;
    }
    try {
        for (const Command& c : commands)
            if (c.sub->parsed()) return with_standard_output(c.run);
    } catch (const std::exception& e) {
        std::cerr << "hubbeam: " << e.what() << "\n";
        return exit_stopped;
    }
    return exit_bad_input;
}

}  // namespace hubbeam::cli
