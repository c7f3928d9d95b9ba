// Readers for the main input files that name a blade's section file (a BModes .bmi, an ElastoDyn main input file), and
// the hubbeam scene (TOML) they become: what `hubbeam import` reads and writes.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace hubbeam {

/// One setting of a main input file as read: its name there, its 1-based line, its value as written and as a number.
struct InputSetting {
    std::string name;
    long line = 0;
    std::string text;
    double value = 0.0;
};

/// What a main input file says of one blade, in the file's own units (rpm, degrees), each value with the line that
/// gave it, so that a scene key it becomes can be traced back to the file.
struct ImportedBlade {
    std::string format;      // main_input_bmodes or main_input_elastodyn
    std::string file;        // the main input file, as given
    std::string blade_file;  // the section file it names, resolved against the main file's folder
    InputSetting blade_file_setting;
    InputSetting rotor_speed;  // rpm
    // BModes' romg_mult (v3: rpm_mult): the blade spins at rotor_speed times it (v3 multiplies the speed; v1 divides
    // the stiffnesses by its square and multiplies the frequencies by it, which is the same blade at that speed). 1,
    // line 0, for ElastoDyn.
    InputSetting rotor_speed_factor{"", 0, "1", 1.0};
    InputSetting tip_radius;   // m, from the axis (BModes' radius, ElastoDyn's TipRad)
    InputSetting hub_radius;   // m (hub_rad, HubRad)
    InputSetting precone;      // deg
    InputSetting pitch;        // deg
    InputSetting tip_mass;     // kg
    InputSetting tip_inertia;  // kg m^2, the tip body's lag inertia (BModes' ixx_tip; ElastoDyn has none: 0)
    // The tip body's flap and torsion inertias (kg m^2) and its centre of mass's offset along the tip chord (m,
    // positive towards the trailing edge): BModes' iyy_tip, izz_tip, cm_loc; ElastoDyn has none (line 0).
    InputSetting tip_inertia_flap, tip_inertia_twist, tip_offset;
    // BModes' property multipliers (sec_mass_mult ... tc_offst_mult, sc_offst_mult aside), in the order of
    // blade_scale_fields: the scene's [blade_scale]. Empty for ElastoDyn, whose blade file applies its own.
    std::vector<InputSetting> blade_scale;
    bool has_gravity = false;
    InputSetting gravity;  // m/s^2 (ElastoDyn up to FAST v8: Gravity)
    /// The blade file's structural damping ratios (ElastoDyn's BldFlDmp(1), BldFlDmp(2), BldEdDmp(1), percent of
    /// critical): the scene's [damping] flap_ratios and edge_ratios.
    std::string damping_file;
    std::vector<InputSetting> damping;
};

/// ImportedBlade::format of a BModes main input file.
inline constexpr const char* main_input_bmodes = "BModes main input";
/// ImportedBlade::format of an ElastoDyn main input file.
inline constexpr const char* main_input_elastodyn = "ElastoDyn main input";

/// The largest main input file read (bytes): an ElastoDyn file with every output channel listed is some 100 kB.
inline constexpr std::size_t max_main_input_bytes = 1u << 20;

/// A main input file that cannot be read, or holds a setting hubbeam does not model: what() is one line,
/// "FILE[:LINE]: [SETTING: ]expected ...", naming where and what, never the file's text beyond the setting's name.
struct MainInputError : std::runtime_error {
    std::string file;
    long line = 0;
    std::string setting;
    MainInputError(std::string file, long line, std::string setting, const std::string& expected);
};

/// Reads a BModes main input file (.bmi, BModes v1 to v3) by position, as BModes does, checking each line's label;
/// throws MainInputError for a setting hubbeam does not model (a tower, a multiplier other than 1, a tip mass's
/// centre-of-mass offset, ...).
ImportedBlade read_bmodes_main(const std::string& path);

/// Reads an ElastoDyn main input file (FAST v8 to OpenFAST) by setting name in the sections that concern a blade
/// (ENVIRONMENTAL CONDITION, INITIAL CONDITIONS, TURBINE CONFIGURATION, MASS AND INERTIA, BLADE), and the damping and
/// modal tuners of the blade file BldFile(1) names; throws MainInputError.
ImportedBlade read_elastodyn_main(const std::string& path);

/// Reads a main input file of either format, recognised by its content (BModes' header "BModes", an ElastoDyn
/// file's TURBINE CONFIGURATION section).
ImportedBlade read_main_input(const std::string& path);

/// The scene of an imported blade as TOML, for a scene file at scene_path (its beam.blade_file is written relative
/// to that file's folder): one blade spun up to the file's rotor speed, FEM out of the plane, every value with a
/// comment naming the setting and line it came from. Throws MainInputError (naming the input's setting) when the
/// scene would be refused, and BladeFileError for the section file.
std::string imported_scene_toml(const ImportedBlade& blade, const std::string& scene_path);

}  // namespace hubbeam
