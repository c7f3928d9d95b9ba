// hubbeam-gen: derives the named variants symbolically and writes one C++ source per variant, plus either the
// registry that compiles them into the hubbeam build or, with --module, an entry point per source for loading
// it as a shared object (the runtime's on-demand variants, runtime/include/hubbeam/on_demand.hpp).
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "variant_source.hpp"

#ifndef HUBBEAM_VERSION
#define HUBBEAM_VERSION "dev"
#endif

namespace {

void write(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream f(path);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

/// What the command line asks for.
struct Arguments {
    std::string out = ".";
    bool module = false, quiet = false;
    std::string form = "auto";
    std::vector<std::string> names;
    hubbeam::gen::EmitOptions options;
};

/// The options and their help, bound to a's fields.
void add_options(CLI::App& app, Arguments& a)
{
    app.add_option("--out", a.out, "Folder for the sources (created if missing; default: the current folder)")
        ->type_name("DIR");
    app.add_flag("--module", a.module,
                 "Write each source with an entry point `hubbeam_variant()` for a shared object, and the interface "
                 "header generated_abi.h beside it instead of a registry");
    app.add_flag("-q,--quiet", a.quiet, "Print nothing on success");
    app.add_option("--form", a.form,
                   "How kernels are printed: unrolled (fastest code), tables (constant tables and loops: compile time "
                   "linear in the terms), or auto: tables for kernels of more than --table-threshold terms "
                   "(default auto)")
        ->check(CLI::IsMember({"auto", "unrolled", "tables"}))
        ->type_name("FORM");
    app.add_option("--table-threshold", a.options.table_threshold, "Terms above which auto prints a kernel as tables "
                                                                     "(default 1000)")
        ->check(CLI::PositiveNumber)
        ->type_name("N");
    app.add_option("--rhs-table-threshold", a.options.rhs_table_threshold,
                   "Terms above which auto prints a kernel called at every right-hand side (the forces, the mass "
                   "matrix) as tables (default 4000)")
        ->check(CLI::PositiveNumber)
        ->type_name("N");
    app.add_option("variants", a.names,
                   std::string("Variant names ") + hubbeam::variant_name_grammar +
                       ": METHOD amm|fem|bim|bsim, Nx axial and Ny transverse (in-plane) coordinates, Nz flapwise and "
                       "Nt twist coordinates (left out where 0), DRIVE prescribed|torque, "
                       "ORDER zero|first|full; _open: BSIM's open uniform basis; _tip: a tip body; _gravity; _damped: "
                       "Rayleigh damping; _width|_depth: a linear taper; _profile: a tabulated profile "
                       "(its stations and values are run-time data); _offsets: a blade table's centre-of-mass offsets; "
                       "_pitched, _twisted, _coned: the section's pitch and "
                       "pre-twist, the precone; _hub: a moving hub; _tipbody: the tip body's flap and torsion "
                       "inertias and offset in the blade's axes; the suffixes in this order; "
                       "e.g. bim_nx4_ny4_torque_first, amm_nx0_ny4_torque_first_tip_gravity, "
                       "fem_nx0_ny8_nz8_nt2_torque_first_pitched")
        ->required()
        ->type_name("VARIANT");
    app.footer("Writes DIR/VARIANT.cpp for each variant, and DIR/registry.cpp (without --module) or DIR/generated_abi.h "
               "(with --module). Exit codes: 0 "
               "success, 1 a variant could not be derived or written, 2 bad arguments (one line on stderr).");
}

/// The variants named, each spelled canonically and with DOF counts its method takes; throws
/// std::invalid_argument naming the first that is not.
std::vector<hubbeam::VariantKey> parse_variants(const std::vector<std::string>& names)
{
    std::vector<hubbeam::VariantKey> keys;
    for (const std::string& name : names) {
        keys.push_back(hubbeam::VariantKey::parse(name));
        if (keys.back().name() != name)
            throw std::invalid_argument("variant '" + name + "' is spelled " + keys.back().name());
        if (const std::string why = keys.back().dof_problem(); !why.empty())
            throw std::invalid_argument("variant '" + name + "': " + why);
    }
    return keys;
}

/// Derives and writes each variant's source, then the registry or the interface header; throws on failure.
void write_sources(const std::vector<hubbeam::VariantKey>& keys, const Arguments& a)
{
    std::filesystem::create_directories(a.out);
    for (const hubbeam::VariantKey& key : keys) {
        const auto start = std::chrono::steady_clock::now();
        std::string text = hubbeam::gen::variant_source(key, a.options);
        if (a.module) text += hubbeam::gen::module_entry_source(key.name());
        write(std::filesystem::path(a.out) / (key.name() + ".cpp"), text);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!a.quiet) std::cout << "hubbeam-gen: " << key.name() << " (" << s << " s)\n";
    }
    if (a.module) write(std::filesystem::path(a.out) / "generated_abi.h", hubbeam::gen::abi_header());
    else write(std::filesystem::path(a.out) / "registry.cpp", hubbeam::gen::registry_source(a.names));
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"hubbeam-gen: derives the rotating hub-beam's equations of motion with GiNaC (Lagrange's equations of\n"
                 "T and U, docs/model.md) and emits C++ kernels for the named variants."};
    Arguments a;
    app.set_version_flag("--version", "hubbeam-gen " HUBBEAM_VERSION, "Print the version and exit");
    add_options(app, a);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 2;
    }
    using Form = hubbeam::gen::EmitOptions::Form;
    a.options.form = a.form == "tables" ? Form::tables : a.form == "unrolled" ? Form::unrolled : Form::automatic;
    std::vector<hubbeam::VariantKey> keys;
    try {
        keys = parse_variants(a.names);
    } catch (const std::invalid_argument& e) {
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 2;
    }
    try {
        write_sources(keys, a);
    } catch (const std::exception& e) {
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
