// hubbeam variants: the variants built in and cached, and how any other variant runs.
#include <hubbeam/on_demand.hpp>
#include <iostream>
#include <string>

#include "command.hpp"

namespace hubbeam::cli {

namespace {

/// hubbeam variants: the variants built in and cached, one a line with where it comes from, then how any other
/// variant would run.
int list_variants()
{
    for (const std::string& name : generated_variant_names()) std::cout << "built in  " << name << "\n";
    for (const std::string& name : cached_variant_names()) std::cout << "cached    " << name << "\n";
    std::cout << "cache: " << variant_cache_dir().string() << " (clear with: rm -r " << variant_cache_root().string()
              << ")\n";
    if (const std::string why = on_demand_problem(); why.empty())
        std::cout << "other variants: generated and compiled on first use with " << on_demand_compiler() << "\n";
    else
        std::cout << "other variants: hand-assembled (" << why << "); order full cannot run\n";
    return exit_ok;
}

}  // namespace

Command add_variants_command(CLI::App& app)
{
    Subcommand cmd(app, "variants", "List the variants built in and cached, and how any other variant runs");
    return {cmd.app(), [] { return list_variants(); }};
}

}  // namespace hubbeam::cli
