// hubbeam-gen: derives the named variants symbolically and writes one C++ source per variant, plus either the
// registry that compiles them into the hubbeam build or, with --module, an entry point per source for loading
// it as a shared object (the runtime's on-demand variants, runtime/on_demand.hpp).
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "variant_source.hpp"

namespace {

void write(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream f(path);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"hubbeam-gen: derives the rotating hub-beam's equations of motion with GiNaC (Lagrange's equations of\n"
                 "T and U, docs/model.md) and emits C++ kernels for the named variants."};
    std::string out = ".";
    bool module = false, quiet = false;
    std::string form = "auto";
    std::vector<std::string> names;
    app.add_option("--out", out, "Folder for the sources (created if missing; default: the current folder)")
        ->type_name("DIR");
    app.add_flag("--module", module,
                 "Write each source with an entry point `hubbeam_variant()` for a shared object, and the interface "
                 "header generated_abi.h beside it instead of a registry");
    app.add_flag("-q,--quiet", quiet, "Print nothing on success");
    hubbeam::gen::EmitOptions options;
    app.add_option("--form", form,
                   "How kernels are printed: unrolled (fastest code), tables (constant tables and loops: compile time "
                   "linear in the terms), or auto: tables for kernels of more than --table-threshold terms "
                   "(default auto)")
        ->check(CLI::IsMember({"auto", "unrolled", "tables"}))
        ->type_name("FORM");
    app.add_option("--table-threshold", options.table_threshold, "Terms above which auto prints a kernel as tables "
                                                                   "(default 1000)")
        ->check(CLI::PositiveNumber)
        ->type_name("N");
    app.add_option("variants", names,
                   "Variant names METHOD_nxN_nyN_DRIVE_ORDER[_open]: METHOD amm|fem|bim|bsim, Nx axial and Ny "
                   "transverse coordinates, DRIVE prescribed|torque, ORDER zero|first|full, _open for BSIM's open "
                   "uniform basis; e.g. bim_nx4_ny4_torque_first")
        ->required()
        ->type_name("VARIANT");
    app.footer("Writes DIR/VARIANT.cpp for each variant, and DIR/registry.cpp (without --module) or DIR/generated_abi.h "
               "(with --module). Exit codes: 0 "
               "success, 1 a variant could not be derived or written, 2 bad arguments (one line on stderr).");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 2;
    }
    using Form = hubbeam::gen::EmitOptions::Form;
    options.form = form == "tables" ? Form::tables : form == "unrolled" ? Form::unrolled : Form::automatic;
    std::vector<hubbeam::VariantKey> keys;
    for (const std::string& name : names) {
        try {
            keys.push_back(hubbeam::VariantKey::parse(name));
            if (keys.back().name() != name)
                throw std::invalid_argument("variant '" + name + "' is spelled " + keys.back().name());
            if (const std::string why = keys.back().dof_problem(); !why.empty())
                throw std::invalid_argument("variant '" + name + "': " + why);
        } catch (const std::invalid_argument& e) {
            std::cerr << "hubbeam-gen: " << e.what() << "\n";
            return 2;
        }
    }
    try {
        std::filesystem::create_directories(out);
        for (const hubbeam::VariantKey& key : keys) {
            const auto start = std::chrono::steady_clock::now();
            std::string text = hubbeam::gen::variant_source(key, options);
            if (module) text += hubbeam::gen::module_entry_source(key.name());
            write(std::filesystem::path(out) / (key.name() + ".cpp"), text);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!quiet) std::cout << "hubbeam-gen: " << key.name() << " (" << s << " s)\n";
        }
        if (module) write(std::filesystem::path(out) / "generated_abi.h", hubbeam::gen::abi_header());
        else write(std::filesystem::path(out) / "registry.cpp", hubbeam::gen::registry_source(names));
    } catch (const std::exception& e) {
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
