// What the files of the scene reader share (scene.cpp reads a file's tables, scene_keys.cpp holds the key table,
// scene_tables.cpp reads files and the CSV tables a scene names, scene_validate.cpp checks a Scene,
// scene_messages.cpp words the errors): private to them.
#pragma once

#include <array>
#include <cstddef>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/scene.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hubbeam::scene_io {

/// One factor of BladeScale: its key in [blade_scale], its member, the BladeTable column it multiplies.
struct BladeScaleField {
    const char* key;
    double BladeScale::*factor;
    std::vector<double> BladeTable::*column;
};

/// Every factor, in the order of [blade_scale]'s keys in scene_keys.cpp and of BModes' multipliers (sc_offst_mult
/// aside).
inline constexpr std::array<BladeScaleField, 9> blade_scale_fields = {{
    {"mass", &BladeScale::mass, &BladeTable::mass_per_length},
    {"inertia_flap", &BladeScale::inertia_flap, &BladeTable::mass_moment_flap},
    {"inertia_edge", &BladeScale::inertia_edge, &BladeTable::mass_moment_edge},
    {"stiffness_flap", &BladeScale::stiffness_flap, &BladeTable::EI_flap},
    {"stiffness_edge", &BladeScale::stiffness_edge, &BladeTable::EI_edge},
    {"stiffness_torsion", &BladeScale::stiffness_torsion, &BladeTable::GJ},
    {"stiffness_axial", &BladeScale::stiffness_axial, &BladeTable::EA},
    {"cg_offset", &BladeScale::cg_offset, &BladeTable::cg_offset},
    {"tc_offset", &BladeScale::tc_offset, &BladeTable::tc_offset},
}};

/// table's columns, each times its factor in scale (a column the file lacks stays empty).
inline void scale_columns(BladeTable& table, const BladeScale& scale)
{
    for (const BladeScaleField& f : blade_scale_fields)
        for (double& v : table.*f.column) v *= scale.*f.factor;
}

/// The "got" of a required key that is absent.
inline constexpr const char* missing = "nothing (the key is missing)";

/// The words of motion.kind, in table order; the key table's motion_kinds entries are among them.
std::vector<std::string> motion_kinds();
bool parse_kind(std::string_view w, Motion::Kind& k);
std::string kind_word(Motion::Kind k);

/// The key table's `expected` of a dotted key name.
const std::string& expected(const std::string& key);

/// Throws SceneError(file, key, expected, got).
[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& expected,
                       const std::string& got);
/// The bound on a hub angle, as messages state it.
std::string angle_bound();

/// A file's text, at most cap + 1 bytes of it (the caller refuses more).
std::string read_file(const std::string& path, std::size_t cap = max_scene_bytes);
/// s without the blanks around it.
std::string_view trimmed(std::string_view s);

/// The [beam] keys a table (beam.profile, beam.blade_file) replaces: parsing refuses them beside it, the effective
/// scene leaves them out.
inline constexpr std::array<const char*, 10> keys_a_table_replaces = {"density",
                                                                      "area",
                                                                      "second_moment",
                                                                      "youngs_modulus",
                                                                      "taper",
                                                                      "tip_ratio",
                                                                      "second_moment_flap",
                                                                      "shear_modulus",
                                                                      "torsion_constant",
                                                                      "twist"};

/// The largest profile table read (beam.profile): 10,000 stations of nine columns at full precision.
inline constexpr std::size_t max_profile_bytes = 1 << 22;
/// The most stations a profile table or blade file may have (scene_tables.cpp says why).
inline constexpr std::size_t max_profile_stations = 10000;

/// A profile table as read: the key that named it (beam.profile, beam.blade_file), its file, the blade columns it has
/// (EI_flap, GJ, twist, j_c, j_n) and whether it gives ES (a blade file may not).
struct ProfileTable {
    std::string key, file;
    std::vector<std::string> blade_columns;
    bool axial = true;
    int resample = 0;  // beam.blade_stations
};
/// beam.profile's table into the variant's stations and p.profile (every value per station; fit_profile keeps what
/// the variant reads).
ProfileTable read_profile(const std::string& scene_path, const std::string& name, Parameters& p, Extras& extras);
/// beam.blade_file's BModes or ElastoDyn file as a profile (its stations, or `resample` equally spaced ones if > 0),
/// its columns times scale's factors.
ProfileTable read_blade(const std::string& scene_path, const std::string& name, int resample,
                        const BladeScale& scale, Parameters& p, Extras& extras);
/// p.profile as the scene's variant reads it, once the discretization and the beam's angles are known.
void fit_profile(const std::string& scene_path, const ProfileTable& table, const VariantKey& key, Parameters& p);
/// The table of motion.file (resolved already by table_path): columns t and `column`.
std::shared_ptr<const DriveTable> read_drive_table(const std::string& scene, const std::string& file,
                                                   const char* column, const char* meaning,
                                                   DriveTable::Interpolation interpolation);
/// A file key's value as the path its reader opens and scene_files lists (one resolution for both): relative to
/// the scene file's folder.
std::string table_path(const std::string& scene, const std::string& file);
/// A motion table's problem: "SCENE: motion.file: WHERE: WHAT".
[[noreturn]] void table_fail(const std::string& scene, const std::string& where, const std::string& what);

}  // namespace hubbeam::scene_io
