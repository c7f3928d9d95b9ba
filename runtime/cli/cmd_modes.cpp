// hubbeam modes and hubbeam linearize: the command-line side (options, the scene with its overrides) of
// modes.cpp's Campbell table and state-space model.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "modes.hpp"

namespace hubbeam::cli {

namespace {

/// The scene keys that `modes` and `linearize` take as options ("--nx", "--order", "--source"; linearize also
/// "--method", "--ny", "--nz", "--nt"), as overrides, as `run` takes them; the options, their help and their checks
/// are the key table's. modes takes --ny, --nz and --nt as lists of its own.
struct LinearOverrides {
    std::vector<std::string> keys, values;  // scene key names, and the values typed (empty: not given)
    Overrides overrides() const
    {
        Overrides o;
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (!values[i].empty()) o.emplace_back(keys[i], values[i]);
        return o;
    }
};

void add_linear_overrides(Subcommand& sub, LinearOverrides& o, bool single_variant)
{
    o.keys = {"discretization.nx", "model.order", "model.source"};
    if (single_variant)
        o.keys.insert(o.keys.end(),
                      {"discretization.method", "discretization.ny", "discretization.nz", "discretization.nt"});
    o.values.assign(o.keys.size(), "");  // sized before the options hold references into it
    for (std::size_t i = 0; i < o.keys.size(); ++i)
        add_key_option(sub, scene_key(o.keys[i]), o.values[i], " (default: the scene's)");
}

/// hubbeam modes and hubbeam linearize: load the scene with the overrides, then act; returns the exit code.
template <class Act>
int linear_command(const std::string& scene_path, const LinearOverrides& lo, const Act& act)
{
    const Overrides overrides = lo.overrides();
    Scene scene;
    try {
        scene = load_scene(scene_path, overrides);
    } catch (const SceneError& e) {
        std::cerr << message_for(e, overrides) << "\n";
        return exit_bad_input;
    }
    return refusing(scene.path, [&] {
        act(scene);
        return exit_ok;
    });
}

}  // namespace

Command add_modes_command(CLI::App& app)
{
    struct Options {
        std::string scene;
        ModesArgs args;
        LinearOverrides overrides;
    };
    auto o = std::make_shared<Options>();
    Subcommand modes_cmd(app, "modes",
                         "Natural frequencies about a steady spin, per method, Ny and spin rate (a Campbell table)");
    modes_cmd.add_option("scene", o->scene, "Scene file (TOML)").required().type_name("SCENE.toml");
    modes_cmd
        .add_option("--omega", o->args.omega,
                    "Spin rates (rad/s): a comma-separated list, items may be ranges FIRST:LAST:STEP "
                    "(default: 0 and the scene's steady rate)")
        .type_name("LIST");
    modes_cmd.add_option("--methods", o->args.methods, "Methods, comma-separated (default: the scene's)")
        .type_name("LIST");
    modes_cmd.add_option("--ny", o->args.ny, "Ny values, comma-separated (default: the scene's)").type_name("LIST");
    modes_cmd
        .add_option("--nz", o->args.nz,
                    "Nz values (flapwise coordinates: a blade's edge and flap modes), comma-separated (default: the "
                    "scene's)")
        .type_name("LIST");
    modes_cmd
        .add_option("--nt", o->args.nt,
                    "Nt values (twist coordinates: twist modes), comma-separated (default: the "
                    "scene's)")
        .type_name("LIST");
    modes_cmd
        .add_option("--count", o->args.count,
                    "Modes printed per kind (bending or edge and flap, twist, axial, hub, overdamped) and spin rate, "
                    "the lowest first (default 4; the CSV has all)")
        .type_name("N");
    modes_cmd.add_option("-o,--output", o->args.output, "Also write every mode as CSV to FILE (default: no file)")
        .type_name("FILE");
    modes_cmd.add_option("--plot", o->args.plot, "Also draw the Campbell diagram PREFIX.png and PREFIX.svg (needs -o)")
        .type_name("PREFIX");
    modes_cmd
        .add_option("--harmonics", o->args.harmonics,
                    "Excitation lines omega = n Omega whose crossings with the modes are printed as critical speeds "
                    "(default 1,2,3; none: no critical speed searched)")
        .type_name("LIST");
    modes_cmd.add_option("--critical", o->args.critical, "Also write the critical speeds as CSV to FILE")
        .type_name("FILE");
    modes_cmd
        .add_option("--elastodyn", o->args.elastodyn,
                    "Also write the blade's mode shapes at the first --omega as ElastoDyn's BLADE MODE SHAPES section "
                    "(BldFl1Sh, BldFl2Sh, BldEdgSh: polynomials x^2..x^6 fitted to flap 1, flap 2, edge 1) to FILE; "
                    "one variant, nz > 0")
        .type_name("FILE");
    modes_cmd
        .add_option("--frame", o->args.frame,
                    "A rotor of 3 or more identical blades: fixed (multi-blade coordinates: collective, FW and BW "
                    "whirls, differential; the default where they apply) or rotating (each blade in its own frame)")
        .type_name("FRAME");
    modes_cmd.add_flag("-q,--quiet", o->args.quiet,
                       "Print only how many modes were written, not the table (the CSV has every mode)");
    add_linear_overrides(modes_cmd, o->overrides, false);
    modes_cmd.footer(
        "Prints the table; writes a file only when asked (-o, --critical, --plot, --elastodyn). docs/cli.md. "
        "Exit code 2 for a bad option value or an output that is the scene, another output, not a "
        "regular file, or being written by another hubbeam.");
    return {modes_cmd.app(), [o] {
                return linear_command(o->scene, o->overrides, [&](const Scene& scene) {
                    run_modes(scene, parse_modes_options(o->args, scene), std::cout);
                });
            }};
}

Command add_linearize_command(CLI::App& app)
{
    struct Options {
        std::string scene, omega, prefix, frame;
        LinearOverrides overrides;
    };
    auto o = std::make_shared<Options>();
    Subcommand linearize_cmd(app, "linearize",
                             "State-space matrices A, B, C, D about a steady spin (input hub torque or acceleration)");
    linearize_cmd.add_option("scene", o->scene, "Scene file (TOML)").required().type_name("SCENE.toml");
    linearize_cmd.add_option("--omega", o->omega, "Steady spin rate (rad/s), >= 0").required().type_name("W");
    linearize_cmd
        .add_option("-o,--output", o->prefix,
                    "Writes PREFIX-A.csv, PREFIX-B.csv, PREFIX-C.csv, PREFIX-D.csv and PREFIX.npz (all four for "
                    "numpy); with [control] also PREFIX-open-*.csv and PREFIX-open.npz (the open loop)")
        .type_name("PREFIX")
        .required();
    linearize_cmd
        .add_option("--frame", o->frame,
                    "A rotor of 3 or more identical blades: fixed (multi-blade coordinates, the default where they "
                    "apply) or rotating (each blade's coordinates in its own frame)")
        .type_name("FRAME");
    add_linear_overrides(linearize_cmd, o->overrides, true);
    linearize_cmd.footer("docs/cli.md. Exit code 2 for a bad option value.");
    return {linearize_cmd.app(), [o] {
                return linear_command(o->scene, o->overrides, [&](const Scene& scene) {
                    const std::vector<double> omega = parse_spin_rates("--omega", o->omega);
                    if (omega.size() != 1)
                        throw ModesOptionError("--omega: expected one spin rate >= 0, got " + o->omega);
                    run_linearize(scene, omega[0], o->prefix, std::cout, parse_frame(o->frame, scene));
                });
            }};
}

}  // namespace hubbeam::cli
