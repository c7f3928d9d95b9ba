// The scene key table, the one definition of the keys (name, option, what each holds), and its lookups.
#include <algorithm>
#include <deque>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/scene.hpp>

#include "dynamics/stepper_names.hpp"
#include "io/scene_io.hpp"
#include "terms.hpp"

namespace hubbeam {

using scene_io::motion_kinds;

namespace {

// The words of motion.kind; the key table's motion_kinds entries are among them (tests/io/test_scene.cpp).
const WordTable<Motion::Kind, 6> kind_words = {{Motion::Kind::spin_up, "spin-up"},
                                               {Motion::Kind::torque, "torque"},
                                               {Motion::Kind::held, "held"},
                                               {Motion::Kind::table, "table"},
                                               {Motion::Kind::torque_table, "torque-table"},
                                               {Motion::Kind::step, "step"}};

}  // namespace

std::vector<std::string> scene_io::motion_kinds()
{
    return all_words(kind_words);
}

bool scene_io::parse_kind(std::string_view w, Motion::Kind& k)
{
    return parse_word(w, kind_words, k);
}

std::string scene_io::kind_word(Motion::Kind k)
{
    return word_of(k, kind_words);
}

namespace {

std::string one_of(const std::vector<std::string>& words)
{
    return "one of " + joined(words, "\"");
}

/// "auto" (the stepper for the scene's stiffness), then every GSL step type.
std::vector<std::string> stepper_words()
{
    std::vector<std::string> w = {automatic_stepper_word};
    for (const std::string& s : stepper_names()) w.push_back(s);
    return w;
}

std::vector<SceneKey> make_scene_keys()
{
    using K = SceneKey::Kind;
    std::vector<SceneKey> keys = {
        {"beam.length", nullptr, K::number, "a number > 0 (L, m)"},
        {"beam.density", nullptr, K::number, "a number > 0 (rho, kg/m^3)"},
        {"beam.area", nullptr, K::number, "a number > 0 (S, m^2)"},
        {"beam.second_moment", nullptr, K::number, "a number > 0 (I, m^4)"},
        {"beam.youngs_modulus", nullptr, K::number, "a number > 0 (E, Pa)"},
        {"beam.taper", nullptr, K::word, one_of(words<Taper>())},
        {"beam.tip_ratio", nullptr, K::number, "a number > 0 (the tapered dimension at the tip over the root)"},
        {"beam.profile", nullptr, K::file,
         "a CSV file name relative to the scene's folder, with the columns x/L, m, EI, ES (m kg/m, EI N m^2, ES N) "
         "and, "
         "for a blade, any of EI_flap, GJ, twist, j_c, j_n, inertia_twist, cg_offset, tc_offset; empty: none",
         {},
         scene_io::max_profile_bytes},
        {"beam.blade_file", nullptr, K::file,
         "a BModes section-properties file or an ElastoDyn blade file, relative to the scene's folder; empty: none",
         {},
         max_blade_file_bytes},
        {"beam.blade_stations", nullptr, K::integer,
         "0 (the file's own stations) or an integer from 2 to 10000 (stations to resample beam.blade_file at)"},
        {"beam.second_moment_flap", nullptr, K::number,
         "a number > 0 (I_flap, m^4, bending out of the plane; default beam.second_moment)"},
        {"beam.shear_modulus", nullptr, K::number, "a number >= 0 (G, Pa; > 0 needed with nt > 0)"},
        {"beam.torsion_constant", nullptr, K::number, "a number >= 0 (J_t, m^4; > 0 needed with nt > 0)"},
        {"beam.pitch", nullptr, K::number,
         "a number from -2 pi to 2 pi (the section's pitch, rad: one turn either way)"},
        {"beam.twist", nullptr, K::number, "a number from -2 pi to 2 pi (the pre-twist, tip minus root, rad: one turn either way)"},
        {"beam.precone", nullptr, K::number, "a number in (-1.5, 1.5) (the precone, rad; positive towards +k)"},
        // [blade_scale]: in the order of blade_scale_fields (blade_files.hpp), which the reader and printer iterate.
        {"blade_scale.mass", nullptr, K::number, "a number > 0 (the factor on beam.blade_file's mass per length)"},
        {"blade_scale.inertia_flap", nullptr, K::number,
         "a number >= 0 (the factor on beam.blade_file's flapwise mass moment of inertia, j_c)"},
        {"blade_scale.inertia_edge", nullptr, K::number,
         "a number >= 0 (the factor on beam.blade_file's edgewise mass moment of inertia, j_n)"},
        {"blade_scale.stiffness_flap", nullptr, K::number,
         "a number > 0 (the factor on beam.blade_file's flapwise bending stiffness)"},
        {"blade_scale.stiffness_edge", nullptr, K::number,
         "a number > 0 (the factor on beam.blade_file's edgewise bending stiffness)"},
        {"blade_scale.stiffness_torsion", nullptr, K::number,
         "a number > 0 (the factor on beam.blade_file's torsional stiffness)"},
        {"blade_scale.stiffness_axial", nullptr, K::number,
         "a number > 0 (the factor on beam.blade_file's axial stiffness)"},
        {"blade_scale.cg_offset", nullptr, K::number,
         "a finite number (the factor on beam.blade_file's centre-of-mass offset)"},
        {"blade_scale.tc_offset", nullptr, K::number,
         "a finite number (the factor on beam.blade_file's tension-centre offset)"},
        {"hub.radius", nullptr, K::number, "a number >= 0 (a, m)"},
        {"hub.inertia", nullptr, K::number, "a number > 0 (J_oh, kg m^2)"},
        {"hub.mass", nullptr, K::number, "a number >= 0 (m_hub, kg: the hub's translating mass, blades excluded)"},
    };
    // A term's own keys, each as its registry row (model/terms.cpp) says it, in their tables' places. Their dotted
    // names live as long as the table (never destroyed, as the registry).
    static std::deque<std::string>& names = *new std::deque<std::string>;
    std::vector<std::string_view> placed;
    const auto term_keys = [&keys, &placed](std::string_view table) {
        placed.push_back(table);
        for (const TermInfo& t : terms())
            for (const TermSceneKey& k : t.scene_keys)
                if (std::string_view(k.table) == table)
                    keys.push_back({names.emplace_back(k.name()).c_str(), nullptr, K::number, k.expected()});
    };
    term_keys("support");
    term_keys("tip");
    term_keys("damping");
    keys.insert(keys.end(), {
        {"damping.flap_ratios", nullptr, K::numbers,
         "an array of numbers >= 0 (fractions of critical of the blade's first flapwise modes at rest)"},
        {"damping.edge_ratios", nullptr, K::numbers,
         "an array of numbers >= 0 (fractions of critical of the blade's first edgewise modes at rest)"},
    });
    term_keys("gravity");
    keys.insert(keys.end(), {
        {"gravity.direction", nullptr, K::word,
         "one of \"plane\" (along -j of a vertical plane of rotation) or \"axis\" (along -k, the spin axis vertical)"},
        {"motion.kind", nullptr, K::word, one_of(motion_kinds())},
        {"motion.omega0", nullptr, K::number, "a finite number (Omega0, rad/s)", {"spin-up"}},
        {"motion.tau0", nullptr, K::number, "a finite number (tau0, N m)", {"torque"}},
        {"motion.duration", nullptr, K::number, "a number > 0 (T_s or T_t, s)", {"spin-up", "torque"}},
        {"motion.theta0",
         nullptr,
         K::number,
         "a finite number (theta0, rad)",
         {"spin-up", "torque", "table", "torque-table"}},
        {"motion.angle", nullptr, K::number, "a finite number (the hub angle, rad)", {"held", "step"}},
        {"motion.file",
         nullptr,
         K::file,
         "a CSV file with columns t, theta (table) or t, tau (torque-table)",
         {"table", "torque-table"},
         max_table_bytes},
        {"control.kp", nullptr, K::number, "a number >= 0 (kp, N m/rad)"},
        {"control.kd", nullptr, K::number, "a number >= 0 (kd, N m s/rad)"},
        {"control.ki", nullptr, K::number, "a number >= 0 (ki, N m/(rad s))"},
        {"control.tau_max", nullptr, K::number, "a number > 0 or inf (tau_max, N m)"},
        {"control.k_tip", nullptr, K::number, "a finite number (k_tip, N m/m)"},
        {"rotor.blades", nullptr, K::integer,
         "an integer from 1 to " + std::to_string(max_blades) + " (N, the rotor's blades; 1: the beam alone)"},
        {"rotor.pitch_offsets", nullptr, K::numbers,
         "an array of rotor.blades numbers (rad, each blade's pitch increment; the pitch stays within one turn)"},
        {"rotor.tip_masses", nullptr, K::numbers,
         "an array of rotor.blades numbers >= 0 (kg, each blade's tip mass in place of tip.mass)"},
        {"discretization.method", "--method", K::word, one_of(words<Method>())},
        {"discretization.ny", "--ny", K::integer, "an integer >= 1 (Ny)"},
        {"discretization.nx", "--nx", K::integer, "an integer >= 0 (Nx)"},
        {"discretization.nz", "--nz", K::integer, "an integer >= 0 (Nz, flapwise coordinates; 0: in the plane)"},
        {"discretization.nt", "--nt", K::integer, "an integer >= 0 (Nt, twist coordinates)"},
        {"discretization.spline_basis", "--spline-basis", K::word, one_of(words<SplineBasis>())},
        {"model.order", "--order", K::word, one_of(words<Order>())},
        {"model.source", "--source", K::word, one_of(words<ModelSource>())},
        {"model.axial", "--axial", K::word, one_of(words<Axial>())},
        {"solver.stepper", "--stepper", K::word, one_of(stepper_words())},
        {"solver.rtol", "--rtol", K::number, "a number in (0, 1) (relative tolerance)"},
        {"solver.atol", "--atol", K::number, "a number > 0 (absolute tolerance)"},
        {"solver.h0", "--h0", K::number, "a number > 0 (first trial step, s)"},
        {"solver.stepping", "--stepping", K::word, one_of(words<Stepping>())},
        {"solver.max_steps", "--max-steps", K::number, "a whole number from 1 to 1e15 (step budget)"},
        {"solver.error_check", "--error-check", K::word, one_of(words<ErrorCheck>())},
        {"solver.sensitivity_error_control", "--sensitivity-error-control", K::word,
         one_of(words<SensitivityErrorControl>())},
        {"output.t_end", "--t-end", K::number, "a number > 0 (end time, s)"},
        {"output.dt_out", "--dt-out", K::number, "a number > 0 and <= output.t_end (output interval, s)"},
        {"output.file", "-o,--output", K::text, "a file name"},
        {"output.sensitivities", "--sensitivities", K::text,
         "parameter symbols separated by commas, each once: L, rho, S, I, E, a, J_oh, m_tip, J_tip, g, alpha, beta, "
         "tip_ratio, I_flap, G, J_t, pitch, twist, precone, g_axis, kp, kd, ki, k_tip"},
        {"output.loads", "--loads", K::word, one_of(words<OutputLoads>())},
        {"initial.state", "--initial", K::word, one_of(words<InitialState>())},
    });
    // A term's table that has no place above follows the rest.
    for (const TermInfo& t : terms())
        if (!t.scene_keys.empty() &&
            std::find(placed.begin(), placed.end(), std::string_view(t.scene_keys.front().table)) == placed.end())
            term_keys(t.scene_keys.front().table);
    return keys;
}

}  // namespace

const std::string& scene_io::expected(const std::string& key)
{
    return scene_key(key).expected;
}

const std::vector<SceneKey>& scene_keys()
{
    static const std::vector<SceneKey> keys = make_scene_keys();
    return keys;
}

const SceneKey& scene_key(const std::string& name)
{
    for (const SceneKey& k : scene_keys())
        if (name == k.name) return k;
    throw std::logic_error("no scene key " + name);
}

std::vector<const SceneKey*> file_keys()
{
    std::vector<const SceneKey*> out;
    for (const SceneKey& k : scene_keys())
        if (k.kind == SceneKey::Kind::file) out.push_back(&k);
    return out;
}

std::string SceneKey::table() const
{
    const std::string_view n = name;
    return std::string(n.substr(0, n.find('.')));
}

std::string SceneKey::leaf() const
{
    const std::string_view n = name;
    return std::string(n.substr(n.find('.') + 1));
}

std::vector<std::string> scene_tables()
{
    std::vector<std::string> tables;
    for (const SceneKey& k : scene_keys())
        if (std::find(tables.begin(), tables.end(), k.table()) == tables.end()) tables.push_back(k.table());
    return tables;
}

std::vector<std::string> table_keys(const std::string& table, const std::string& motion_kind)
{
    std::vector<std::string> leaves;
    for (const SceneKey& k : scene_keys())
        if (k.table() == table &&
            (k.motion_kinds.empty() || motion_kind.empty() ||
             std::find(k.motion_kinds.begin(), k.motion_kinds.end(), motion_kind) != k.motion_kinds.end()))
            leaves.push_back(k.leaf());
    return leaves;
}

std::string option_name(const SceneKey& k)
{
    if (k.option == nullptr) return k.name;  // overridden from code (the Python module), not an option
    const std::string names = k.option;
    return names.substr(0, names.find(','));
}

}  // namespace hubbeam
