// Main input files into a scene (main_input.hpp): a BModes .bmi and an ElastoDyn main input file, read, checked, and
// refused in one line where they hold what hubbeam does not model; then the scene they become, checked by hubbeam's
// own scene reader before anyone writes it.
//
// The formats as their own programs read them, checked against these public files:
//   BModes    old-NWTC/BModes src/bmodes/BModes.f90 (ReadCom, ReadStr, ReadVar by position: the header, the title,
//             the general parameters, the tip mass (v3 adds cm_axial after cm_loc), id_mat and sec_props_file, the
//             ten property multipliers, the element grid); CertTest/Test01_nonunif_blade.bmi and
//             Test02_blade_with_tip_mass.bmi (v1.03); SMI-Lab-Inha/pyBModes src/pybmodes/io/bmi.py (the same order,
//             sec_props_file relative to the .bmi's folder).
//   ElastoDyn OpenFAST/openfast modules/elastodyn/src/ElastoDyn_IO.f90 (ReadPrimaryFile: VALUE NAME lines, section
//             lines between them; BldFile relative to the main file's folder); OpenFAST/r-test
//             glue-codes/openfast/5MW_Land_DLL_WTurb/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat (OpenFAST) and
//             OpenFAST/openfast UtilityCodes/SimulationToolbox/ConvertFASTversions/TemplateFiles/V8.00.x/
//             ED_Primary.dat (FAST v8, with ENVIRONMENTAL CONDITION's Gravity).
//
// Where the brief of a blade's structure ends, decided so (docs/import.md says it to users):
// - BModes is read by position, as BModes reads it, and each value's label (the word after it) must be the setting
//   BModes reads there: a file in another order would otherwise be read wrong without a word. Every setting up to
//   the multipliers is read and either becomes a scene key, is refused unless it has the value hubbeam's model
//   implies (beam_type 1, hub_conn 1, id_mat 1, every multiplier 1, the tip mass's axial offset and its products of
//   inertia 0), or says how BModes prints (Echo, modepr, TabDelim, mid_node_tw). The element grid
//   (nselt, el_loc) is BModes' discretization, which hubbeam's own replaces, and the tower's wires and platform are
//   no blade's: neither is read.
// - ElastoDyn is read by name within the sections that hold a blade's structure, its mounting and its spin; in
//   those every name must be one this file knows (read, or ignored for a reason below), so that a setting a later
//   ElastoDyn adds there is refused rather than dropped. Other sections (SIMULATION CONTROL, DEGREES OF FREEDOM,
//   ROTOR-TEETER, DRIVETRAIN, FURLING, TOWER, OUTPUT and its channel lists) hold numerics, switches, other bodies and
//   outputs: ignored whole. The blades must be alike (blade k's pitch, precone, tip mass and file those of blade 1):
//   hubbeam takes one blade.
// - The blade file's BldFlDmp(1), BldFlDmp(2), BldEdDmp(1) (percent of critical) become [damping] flap_ratios and
//   edge_ratios (fractions): the modal damping of the blade's own modes. FlStTunr(1), FlStTunr(2) tune ElastoDyn's
//   own modal stiffnesses: refused unless 1. Its mode-shape polynomials are ElastoDyn's discretization: not read.
// - Gravity (FAST v8's ElastoDyn) is written as a commented [gravity]: a rotor turns in a vertical plane, and hubbeam
//   modes about a steady spin are taken without gravity (a blade spinning under its weight moves periodically).
#include <hubbeam/main_input.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/scene_print.hpp>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <tuple>

#include "io/scene_io.hpp"
#include "variant.hpp"

namespace hubbeam {

MainInputError::MainInputError(std::string file_, long line_, std::string setting_, const std::string& expected)
    : std::runtime_error(file_ + (line_ > 0 ? ":" + std::to_string(line_) : std::string()) + ": " +
                         (setting_.empty() ? std::string() : setting_ + ": ") + "expected " + expected),
      file(std::move(file_)),
      line(line_),
      setting(std::move(setting_))
{
}

namespace {

constexpr double degree = std::numbers::pi / 180.0;
constexpr double rpm = std::numbers::pi / 30.0;

/// A main input file read whole, split into lines, and its name as messages give it.
struct InputText {
    std::string label;  // printable
    std::string path;   // as given
    std::vector<std::string> lines;
};

[[noreturn]] void fail(const InputText& t, long line, const std::string& setting, const std::string& expected)
{
    throw MainInputError(t.label, line, printable(setting, 60), expected);
}

/// Reads path (a regular file of at most max_main_input_bytes) into lines, without their ends.
InputText read_input(const std::string& path)
{
    InputText t;
    t.label = printable(path, 400);
    t.path = path;
    std::error_code ec;
    const std::filesystem::file_type type = std::filesystem::status(path, ec).type();
    if (type == std::filesystem::file_type::not_found) fail(t, 0, "", "an existing file");
    if (ec) fail(t, 0, "", "a file it may reach (" + ec.message() + ")");
    // Checked before opening: open() on a FIFO waits for a writer.
    if (type != std::filesystem::file_type::regular) fail(t, 0, "", "a regular file (not a folder, FIFO or device)");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(t, 0, "", "a file it may open");
    std::string text(max_main_input_bytes + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (in.bad()) fail(t, 0, "", "a file it may read");
    if (text.size() > max_main_input_bytes)
        fail(t, 0, "", "a file of at most " + std::to_string(max_main_input_bytes >> 20) + " MiB");
    if (text.starts_with("\xef\xbb\xbf")) text.erase(0, 3);
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        t.lines.push_back(std::move(line));
        pos = end + 1;
    }
    return t;
}

/// A line's fields, separated by blanks, tabs or commas; a field in quotes (a file name) is one field, unquoted.
std::vector<std::string> fields(std::string_view s)
{
    std::vector<std::string> out;
    std::size_t pos = 0;
    while ((pos = s.find_first_not_of(" \t,", pos)) != std::string_view::npos) {
        if (s[pos] == '"' || s[pos] == '\'') {
            const std::size_t close = s.find(s[pos], pos + 1);
            const std::size_t end = close == std::string_view::npos ? s.size() : close;
            out.emplace_back(s.substr(pos + 1, end - pos - 1));
            pos = std::min(end + 1, s.size());
            continue;
        }
        const std::size_t end = std::min(s.find_first_of(" \t,", pos), s.size());
        out.emplace_back(s.substr(pos, end - pos));
        pos = end;
    }
    return out;
}

/// Whether a and b are the same name in any case.
bool same_name(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
           });
}

/// A file named in a main input file, resolved as its program resolves it: relative to the main file's folder.
std::string resolved(const std::string& main_file, const std::string& name)
{
    const std::filesystem::path p(name);
    if (p.is_absolute()) return name;
    return (std::filesystem::path(main_file).parent_path() / p).string();
}

/// Refuses, at the line that names it, a section or blade file that is not there: the message names the setting
/// the user edits, not only the file it could not find.
void check_named_file(const InputText& t, const InputSetting& s, const std::string& path)
{
    std::error_code ec;
    const std::filesystem::file_type type = std::filesystem::status(path, ec).type();
    if (type == std::filesystem::file_type::not_found)
        fail(t, s.line, s.name, "a file that exists, relative to this file's folder, got " + printable(path, 400));
    if (!ec && type != std::filesystem::file_type::regular)
        fail(t, s.line, s.name, "a regular file (not a folder, FIFO or device), got " + printable(path, 400));
}

// ---- BModes ----------------------------------------------------------------------------------------------------

/// Walks a .bmi as BModes' reading routines do: ReadCom takes the next line whatever it holds, ReadVar the next line
/// that is not blank (a list-directed read passes over empty records).
class BmiCursor {
public:
    explicit BmiCursor(const InputText& t) : t_(t) {}

    /// ReadCom: the next line, whatever it holds.
    void skip(const char* what)
    {
        if (next_ >= t_.lines.size()) fail(t_, 0, "", std::string(what) + " after line " + std::to_string(next_));
        ++next_;
    }

    /// The next line that is not blank, without taking it: its fields and number (0 at the end of the file).
    std::vector<std::string> peek(long& line) const
    {
        for (std::size_t k = next_; k < t_.lines.size(); ++k)
            if (std::vector<std::string> f = fields(t_.lines[k]); !f.empty()) {
                line = static_cast<long>(k) + 1;
                return f;
            }
        line = 0;
        return {};
    }

    /// ReadVar of the setting `names` (its labels in BModes versions): the value and the label after it, which must
    /// be one of names (a trailing ':' aside), so that a file in another order is refused rather than misread.
    InputSetting var(std::initializer_list<const char*> names, const char* meaning)
    {
        long line = 0;
        const std::vector<std::string> f = peek(line);
        const std::string name = *names.begin();
        if (line == 0) fail(t_, 0, name, "a line with " + name + " (" + meaning + "), the file ends before it");
        next_ = static_cast<std::size_t>(line);
        std::string label = f.size() >= 2 ? f[1] : std::string();
        if (label.ends_with(':')) label.pop_back();
        if (std::none_of(names.begin(), names.end(), [&](const char* n) { return same_name(label, n); }))
            fail(t_, line, name,
                 "the value of " + name + " (" + meaning + ") followed by its name on this line (BModes reads its " +
                     "settings by position)");
        return {name, line, f[0], 0.0};
    }

    /// var() of a number.
    InputSetting number_var(std::initializer_list<const char*> names, const char* meaning)
    {
        InputSetting s = var(names, meaning);
        if (!fortran_number(s.text, s.value)) fail(t_, s.line, s.name, std::string("a finite number (") + meaning + ")");
        return s;
    }

private:
    const InputText& t_;
    std::size_t next_ = 0;
};

/// Refuses s unless its value is `wanted`, saying why hubbeam needs that value.
void require(const InputText& t, const InputSetting& s, double wanted, const std::string& why)
{
    if (s.value != wanted) {
        std::ostringstream w;
        w << wanted;
        fail(t, s.line, s.name, w.str() + ": " + why);
    }
}

/// A .bmi's general parameters: the rotor's speed and its factor, the radii, precone and pitch; a blade clamped to
/// the hub, and what only BModes' output reads.
void read_bmodes_general(BmiCursor& c, const InputText& t, ImportedBlade& b)
{
    c.skip("the header line");
    c.skip("the title line");
    c.skip("a blank line");
    c.skip("the General parameters line");
    c.var({"Echo"}, "whether BModes echoes its input");  // how BModes reports, not what it models
    const InputSetting beam_type = c.number_var({"beam_type"}, "1: blade, 2: tower");
    require(t, beam_type, 1, "a blade (hubbeam models a rotating blade, not a tower)");
    b.rotor_speed = c.number_var({"romg", "rot_rpm"}, "rotor speed, rpm");
    b.rotor_speed_factor = c.number_var({"romg_mult", "rpm_mult"}, "rotor speed multiplicative factor");
    if (!(b.rotor_speed_factor.value >= 0.0))
        fail(t, b.rotor_speed_factor.line, b.rotor_speed_factor.name,
             "a value >= 0 (the blade spins at romg times it)");
    b.tip_radius = c.number_var({"radius"}, "rotor tip radius along the coned blade axis, m");
    b.hub_radius = c.number_var({"hub_rad", "rroot"}, "hub radius along the coned blade axis, m");
    if (!(b.hub_radius.value >= 0.0)) fail(t, b.hub_radius.line, "hub_rad", "a value >= 0 (the hub radius, m)");
    if (!(b.tip_radius.value > b.hub_radius.value))
        fail(t, b.tip_radius.line, "radius", "a value above hub_rad (the blade's length is radius - hub_rad)");
    b.precone = c.number_var({"precone", "btp"}, "built-in precone angle, deg");
    b.pitch = c.number_var({"bl_thp"}, "blade pitch setting, deg");
    const InputSetting hub_conn = c.number_var({"hub_conn"}, "hub-to-blade connection");
    require(t, hub_conn, 1, "a cantilevered blade (hubbeam clamps the blade to the hub)");
    c.var({"modepr"}, "number of modes printed");  // output only
    c.var({"TabDelim"}, "output format");
    c.var({"mid_node_tw"}, "mid-node twist output");
}

/// A .bmi's tip mass: its mass, its centre of mass's offset along the tip chord, its principal inertias.
void read_bmodes_tip(BmiCursor& c, const InputText& t, ImportedBlade& b)
{
    c.skip("a blank line");
    c.skip("the tip mass properties line");
    b.tip_mass = c.number_var({"tip_mass"}, "blade-tip mass, kg");
    if (!(b.tip_mass.value >= 0.0)) fail(t, b.tip_mass.line, "tip_mass", "a value >= 0 (the tip mass, kg)");
    // cm_loc keeps the sign of the section file's cg_offst (towards the trailing edge; BModes turns both alike).
    b.tip_offset = c.number_var({"cm_loc"}, "tip-mass c.m. offset from the blade axis along the tip chord, m");
    long line = 0;
    const std::vector<std::string> ahead = c.peek(line);
    if (ahead.size() >= 2 && (same_name(ahead[1], "cm_axial") || same_name(ahead[1], "cm_axial:")))  // BModes v3
        require(t, c.number_var({"cm_axial"}, "tip-mass c.m. offset along the blade axis, m"), 0,
                "hubbeam's tip body has its centre of mass in the tip section's plane (tip.offset is cm_loc)");
    // BModes' wind-turbine blade axes: ixx_tip about the flap normal (lag), iyy_tip about the chord (flap), izz_tip
    // about the span axis (torsion); BModes.f90 re-maps them to its own x, y, z, as these keys name them.
    b.tip_inertia = c.number_var({"ixx_tip"}, "blade lag mass moment of inertia of the tip mass, kg m^2");
    b.tip_inertia_flap = c.number_var({"iyy_tip"}, "blade flap mass moment of inertia of the tip mass, kg m^2");
    b.tip_inertia_twist = c.number_var({"izz_tip"}, "torsion mass moment of inertia of the tip mass, kg m^2");
    for (const InputSetting* i : {&b.tip_inertia, &b.tip_inertia_flap, &b.tip_inertia_twist})
        if (!(i->value >= 0.0)) fail(t, i->line, i->name, "a value >= 0 (kg m^2)");
    constexpr const char* principal =
        "hubbeam's tip body has its principal axes along the tip section's (the chord, its normal, the span axis)";
    require(t, c.number_var({"ixy_tip"}, "cross product of inertia of the tip mass, kg m^2"), 0, principal);
    require(t, c.number_var({"izx_tip"}, "cross product of inertia of the tip mass, kg m^2"), 0, principal);
    require(t, c.number_var({"iyz_tip"}, "cross product of inertia of the tip mass, kg m^2"), 0, principal);
}

/// A .bmi's distributed properties: the section file it names and its property multipliers.
void read_bmodes_properties(BmiCursor& c, const InputText& t, ImportedBlade& b)
{
    c.skip("a blank line");
    c.skip("the distributed-property identifiers line");
    require(t, c.number_var({"id_mat"}, "material type"), 1, "an isotropic material (BModes' only one)");
    b.blade_file_setting = c.var({"sec_props_file"}, "the section properties file");
    b.blade_file = resolved(t.path, b.blade_file_setting.text);
    check_named_file(t, b.blade_file_setting, b.blade_file);
    c.skip("a blank line");
    c.skip("the property scaling factors line");
    // The scene's [blade_scale], in the order of blade_scale_fields; the shear centre's offset is read and not used
    // (docs/model.md 12.6), and so is its multiplier.
    constexpr std::array<const char*, 10> multipliers = {
        "sec_mass_mult", "flp_iner_mult",   "lag_iner_mult", "flp_stff_mult", "edge_stff_mult",
        "tor_stff_mult", "axial_stff_mult", "cg_offst_mult", "sc_offst_mult", "tc_offst_mult"};
    for (const char* m : multipliers) {
        InputSetting s = c.number_var({m}, "a property multiplier");
        if (std::string_view(m) != "sc_offst_mult") b.blade_scale.push_back(std::move(s));
    }
    static_assert(multipliers.size() == scene_io::blade_scale_fields.size() + 1);
}

ImportedBlade parse_bmodes(const InputText& t)
{
    BmiCursor c(t);
    ImportedBlade b;
    b.format = main_input_bmodes;
    b.file = t.path;
    read_bmodes_general(c, t, b);
    read_bmodes_tip(c, t, b);
    read_bmodes_properties(c, t, b);
    return b;
}

// ---- ElastoDyn -------------------------------------------------------------------------------------------------

/// What the importer does with a setting of a section it reads.
enum class Use { read, zero, ignored };

/// A setting of ElastoDyn's main file in a section the importer reads: its name (a blade's with (k) stripped),
/// whether it is read, must be 0 (hubbeam cannot start from it), or is ignored, and why (for zero).
struct EdSetting {
    const char* name;
    Use use;
    const char* why = "";
};

/// The sections that concern one blade, and every setting they hold in FAST v8 to OpenFAST v4 (ElastoDyn_IO.f90).
/// Ignored here: other bodies (teeter, nacelle, tower, platform), the rotor's azimuth and the hub's mass (a
/// prescribed spin moves the blade whatever the hub weighs), ElastoDyn's own blade discretization (BldNodes).
const std::map<std::string, std::vector<EdSetting>>& elastodyn_sections()
{
    static const std::map<std::string, std::vector<EdSetting>> sections = {
        {"ENVIRONMENTAL CONDITION", {{"Gravity", Use::read}}},
        {"INITIAL CONDITIONS",
         {{"OoPDefl", Use::zero, "a hubbeam run starts from the undeformed blade"},
          {"IPDefl", Use::zero, "a hubbeam run starts from the undeformed blade"},
          {"BlPitch", Use::read},
          {"RotSpeed", Use::read},
          {"TeetDefl", Use::ignored},
          {"Azimuth", Use::ignored},
          {"NacYaw", Use::ignored},
          {"TTDspFA", Use::ignored},
          {"TTDspSS", Use::ignored},
          {"PtfmSurge", Use::ignored},
          {"PtfmSway", Use::ignored},
          {"PtfmHeave", Use::ignored},
          {"PtfmRoll", Use::ignored},
          {"PtfmPitch", Use::ignored},
          {"PtfmYaw", Use::ignored}}},
        {"TURBINE CONFIGURATION", {{"NumBl", Use::read},       {"TipRad", Use::read},       {"HubRad", Use::read},
                                   {"PreCone", Use::read},     {"HubCM", Use::ignored},     {"UndSling", Use::ignored},
                                   {"Delta3", Use::ignored},   {"AzimB1Up", Use::ignored},  {"OverHang", Use::ignored},
                                   {"ShftGagL", Use::ignored}, {"ShftTilt", Use::ignored},  {"NacCMxn", Use::ignored},
                                   {"NacCMyn", Use::ignored},  {"NacCMzn", Use::ignored},   {"NcIMUxn", Use::ignored},
                                   {"NcIMUyn", Use::ignored},  {"NcIMUzn", Use::ignored},   {"Twr2Shft", Use::ignored},
                                   {"TowerHt", Use::ignored},  {"TowerBsHt", Use::ignored}, {"TwrRBHt", Use::ignored},
                                   {"TwrDraft", Use::ignored}, {"PtfmCMxt", Use::ignored},  {"PtfmCMyt", Use::ignored},
                                   {"PtfmCMzt", Use::ignored}, {"PtfmRefzt", Use::ignored}, {"PtfmRef", Use::ignored}}},
        {"MASS AND INERTIA",
         {{"TipMass", Use::read},
          {"HubMass", Use::ignored},
          {"HubIner", Use::ignored},
          {"GenIner", Use::ignored},
          {"NacMass", Use::ignored},
          {"NacYIner", Use::ignored},
          {"YawBrMass", Use::ignored},
          {"PtfmMass", Use::ignored},
          {"PtfmRIner", Use::ignored},
          {"PtfmPIner", Use::ignored},
          {"PtfmYIner", Use::ignored},
          {"PtfmXYIner", Use::ignored},
          {"PtfmYZIner", Use::ignored},
          {"PtfmXZIner", Use::ignored}}},
        {"BLADE", {{"BldNodes", Use::ignored}, {"BldFile", Use::read}}},
    };
    return sections;
}

/// The section a line opens ("TURBINE CONFIGURATION" of "---- TURBINE CONFIGURATION ----"), or empty for a line that
/// is no section line.
std::string section_of(const std::string& line)
{
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || (line.compare(first, 3, "---") != 0 && line.compare(first, 3, "===") != 0))
        return {};
    std::string words;
    for (char ch : line) {
        if (ch == '-' || ch == '=') ch = ' ';
        if (ch == ' ' && (words.empty() || words.back() == ' ')) continue;
        words += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
    while (!words.empty() && words.back() == ' ') words.pop_back();
    if (words == "ENVIRONMENTAL CONDITIONS") words = "ENVIRONMENTAL CONDITION";
    return words.empty() ? std::string(" ") : words;
}

/// A name without its blade index: "PreCone" and 2 of "PreCone(2)"; k = 0 for a name without one.
std::string base_name(const std::string& name, int& k)
{
    k = 0;
    const std::size_t open = name.find('(');
    if (open == std::string::npos || !name.ends_with(")")) return name;
    const std::string digits = name.substr(open + 1, name.size() - open - 2);
    if (digits.size() != 1 || digits[0] < '1' || digits[0] > '3') return name;
    k = digits[0] - '0';
    return name.substr(0, open);
}

/// The blade file's damping ratios and modal tuners (BLADE PARAMETERS, BLADE ADJUSTMENT FACTORS): the damping into
/// b, the tuners refused unless 1. Its table is read by the scene's own reader (blade_files.cpp).
void read_blade_parameters(const std::string& path, ImportedBlade& b)
{
    const InputText t = read_input(path);
    b.damping_file = printable(std::filesystem::path(path).lexically_normal().string(), 400);
    for (std::size_t k = 0; k < t.lines.size(); ++k) {
        if (section_of(t.lines[k]) == "DISTRIBUTED BLADE PROPERTIES") break;
        const std::vector<std::string> f = fields(t.lines[k]);
        if (f.size() < 2) continue;
        const long line = static_cast<long>(k) + 1;
        const bool damping = f[1] == "BldFlDmp(1)" || f[1] == "BldFlDmp(2)" || f[1] == "BldEdDmp(1)";
        const bool tuner = f[1] == "FlStTunr(1)" || f[1] == "FlStTunr(2)";
        if (!damping && !tuner) continue;
        InputSetting s{f[1], line, f[0], 0.0};
        if (!fortran_number(s.text, s.value) || (damping && !(s.value >= 0.0)))
            fail(t, line, s.name, damping ? "a number >= 0 (structural damping, percent of critical)" : "a number");
        if (tuner)
            require(t, s, 1,
                    "it tunes ElastoDyn's own modal stiffness, which hubbeam does not use (its modes come from the "
                    "section's stiffness itself)");
        else
            b.damping.push_back(s);
    }
}

/// Every setting of an ElastoDyn file's sections that hold a blade's structure, by full name ("PreCone(2)"): each
/// one hubbeam knows, a number (or the blade file's name), 0 where hubbeam models it so; any other is refused.
std::map<std::string, InputSetting> elastodyn_settings(const InputText& t)
{
    const auto& sections = elastodyn_sections();
    std::map<std::string, InputSetting> read;
    std::string section;
    for (std::size_t k = 0; k < t.lines.size(); ++k) {
        const long line = static_cast<long>(k) + 1;
        if (const std::string s = section_of(t.lines[k]); !s.empty()) {
            section = s;
            continue;
        }
        const auto found = sections.find(section);
        if (found == sections.end()) continue;  // a section that holds no blade's structure
        const std::vector<std::string> f = fields(t.lines[k]);
        if (f.empty()) continue;
        if (f.size() < 2) fail(t, line, "", "a line VALUE NAME - description in section " + section);
        int index = 0;
        const std::string base = base_name(f[1], index);
        const auto setting = std::find_if(found->second.begin(), found->second.end(),
                                          [&](const EdSetting& e) { return same_name(base, e.name); });
        if (setting == found->second.end())
            fail(t, line, f[1],
                 "a setting of ElastoDyn's section " + section +
                     " that hubbeam knows (one it does not know is refused rather than dropped)");
        if (setting->use == Use::ignored) continue;
        InputSetting s{f[1], line, f[0], 0.0};
        if (read.count(f[1]) != 0) fail(t, line, f[1], "the setting once, not a second time");
        if (!same_name(base, "BldFile") && !fortran_number(s.text, s.value)) fail(t, line, f[1], "a finite number");
        if (setting->use == Use::zero && s.value != 0.0) fail(t, line, f[1], std::string("0: ") + setting->why);
        read[f[1]] = s;
    }
    return read;
}

ImportedBlade parse_elastodyn(const InputText& t)
{
    ImportedBlade b;
    b.format = main_input_elastodyn;
    b.file = t.path;
    const std::map<std::string, InputSetting> read = elastodyn_settings(t);
    const auto need = [&](const std::string& name, const char* section_name) -> const InputSetting& {
        const auto it = read.find(name);
        if (it == read.end())
            fail(
                t, 0, name,
                std::string("a line with ") + name + " in section " + section_name + " (an ElastoDyn main input file)");
        return it->second;
    };
    const InputSetting& blades = need("NumBl", "TURBINE CONFIGURATION");
    if (blades.value != 1 && blades.value != 2 && blades.value != 3) fail(t, blades.line, "NumBl", "1, 2 or 3 blades");
    b.tip_radius = need("TipRad", "TURBINE CONFIGURATION");
    b.hub_radius = need("HubRad", "TURBINE CONFIGURATION");
    if (!(b.hub_radius.value >= 0.0)) fail(t, b.hub_radius.line, "HubRad", "a value >= 0 (the hub radius, m)");
    if (!(b.tip_radius.value > b.hub_radius.value))
        fail(t, b.tip_radius.line, "TipRad", "a value above HubRad (the blade's length is TipRad - HubRad)");
    b.rotor_speed = need("RotSpeed", "INITIAL CONDITIONS");
    b.precone = need("PreCone(1)", "TURBINE CONFIGURATION");
    b.pitch = need("BlPitch(1)", "INITIAL CONDITIONS");
    b.tip_mass = need("TipMass(1)", "MASS AND INERTIA");
    if (!(b.tip_mass.value >= 0.0)) fail(t, b.tip_mass.line, "TipMass(1)", "a value >= 0 (the tip mass, kg)");
    b.tip_inertia = {"", 0, "0", 0.0};
    b.tip_inertia_flap = b.tip_inertia_twist = b.tip_offset = b.tip_inertia;
    b.blade_file_setting = need("BldFile(1)", "BLADE");
    b.blade_file = resolved(t.path, b.blade_file_setting.text);
    check_named_file(t, b.blade_file_setting, b.blade_file);
    // hubbeam takes one blade; the others must be that blade, or the rotor the scene stands for is not the file's.
    for (int k = 2; k <= static_cast<int>(blades.value); ++k)
        for (const auto& [name, section_name] : {std::pair<const char*, const char*>{"BlPitch", "INITIAL CONDITIONS"},
                                                 {"PreCone", "TURBINE CONFIGURATION"},
                                                 {"TipMass", "MASS AND INERTIA"},
                                                 {"BldFile", "BLADE"}}) {
            const std::string kth = std::string(name) + "(" + std::to_string(k) + ")";
            const InputSetting& first = need(std::string(name) + "(1)", section_name);
            const InputSetting& other = need(kth, section_name);
            const bool file = std::string(name) == "BldFile";
            if (file ? other.text != first.text : other.value != first.value)
                fail(t, other.line, kth,
                     "the " + std::string(file ? "file" : "value") + " of " + first.name + " (line " +
                         std::to_string(first.line) + "): hubbeam imports one blade of a rotor whose blades are alike");
        }
    if (const auto g = read.find("Gravity"); g != read.end()) {
        b.has_gravity = true;
        b.gravity = g->second;
    }
    read_blade_parameters(b.blade_file, b);
    return b;
}

// ---- The scene -------------------------------------------------------------------------------------------------

/// "NAME = VALUE (FILE:LINE)" of a setting, for the comment beside the key it became.
std::string origin(const ImportedBlade& b, const InputSetting& s, const std::string& unit)
{
    return s.name + " = " + printable(s.text, 60) + (unit.empty() ? "" : " " + unit) + " (" +
           printable(std::filesystem::path(b.file).filename().string(), 80) + ":" + std::to_string(s.line) + ")";
}

/// One `key = value   # comment` line.
std::string key_line(const std::string& key, const std::string& value, const std::string& comment)
{
    std::string line = key + " = " + value;
    if (!comment.empty())
        line +=
            std::string(std::max<std::size_t>(1, 32 - std::min<std::size_t>(line.size(), 31)), ' ') + "# " + comment;
    return line + "\n";
}

/// The [blade_scale] table of BModes' property multipliers other than 1, each naming its line; empty if none.
std::string blade_scale_table(const ImportedBlade& b)
{
    std::string s;
    for (std::size_t k = 0; k < b.blade_scale.size(); ++k)
        if (b.blade_scale[k].value != 1.0)
            s += key_line(scene_io::blade_scale_fields[k].key, toml_number(b.blade_scale[k].value),
                          origin(b, b.blade_scale[k], ""));
    return s.empty() ? s : "\n[blade_scale]                   # factors on the section file's columns\n" + s;
}

/// [tip] from the tip mass and its inertias and offset (each key only where the file gives it and it is not 0, but
/// the mass and lag inertia as before); empty without a tip body.
std::string tip_table(const ImportedBlade& b)
{
    const bool body = b.tip_mass.value > 0.0 || b.tip_inertia.value > 0.0 || b.tip_inertia_flap.value > 0.0 ||
                      b.tip_inertia_twist.value > 0.0 || b.tip_offset.value != 0.0;
    if (!body) return {};
    std::string s = "\n[tip]\n";
    s += key_line("mass", toml_number(b.tip_mass.value), "kg: " + origin(b, b.tip_mass, "kg"));
    if (b.tip_inertia.line > 0)
        s += key_line("inertia", toml_number(b.tip_inertia.value), "kg m^2, lag: " + origin(b, b.tip_inertia, "kg m^2"));
    for (const auto& [key, v, what] : {std::tuple{"inertia_flap", &b.tip_inertia_flap, "kg m^2, flap: "},
                                       {"inertia_twist", &b.tip_inertia_twist, "kg m^2, torsion: "},
                                       {"offset", &b.tip_offset, "m, along the chord towards the trailing edge: "}})
        if (v->line > 0 && v->value != 0.0)
            s += key_line(key, toml_number(v->value), what + origin(b, *v, key[0] == 'o' ? "m" : "kg m^2"));
    return s;
}

/// [damping]'s modal ratios from the blade file's BldFlDmp(1), BldFlDmp(2) and BldEdDmp(1) (percent of critical
/// over 100: docs/model.md section 11.5), each array as far as its settings run from (1); empty without them.
std::string damping_table(const ImportedBlade& b)
{
    const std::string file = printable(std::filesystem::path(b.damping_file).filename().string(), 80);
    std::string out;
    for (const auto& [key, name, count] : {std::tuple{"flap_ratios", "BldFlDmp", 2}, {"edge_ratios", "BldEdDmp", 1}}) {
        std::string values, from;
        for (int k = 1; k <= count; ++k) {
            const std::string setting = std::string(name) + "(" + std::to_string(k) + ")";
            const auto d = std::find_if(b.damping.begin(), b.damping.end(),
                                        [&](const InputSetting& x) { return x.name == setting; });
            if (d == b.damping.end()) break;
            values += (values.empty() ? "" : ", ") + toml_number(d->value / 100.0);
            from += (from.empty() ? "" : ", ") + setting + " = " + printable(d->text, 40) + " %";
            from += " (" + file + ":" + std::to_string(d->line) + ")";
        }
        if (!values.empty()) out += key_line(key, "[" + values + "]", "of critical: " + from);
    }
    return out.empty() ? out : "\n[damping]\n" + out;
}

/// The blade file's name as the scene gives it: relative to the scene's folder when it can be, else absolute.
std::string name_from_scene(const std::string& blade_file, const std::string& scene_path)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path blade = fs::weakly_canonical(fs::absolute(blade_file), ec);
    if (ec) return fs::absolute(blade_file).lexically_normal().string();
    fs::path folder = fs::path(scene_path).parent_path();
    if (folder.empty()) folder = ".";
    const fs::path base = fs::weakly_canonical(fs::absolute(folder), ec);
    if (ec) return blade.string();
    // Relative when the two share a folder below the root (a project's tree, which moves as a whole); a path that
    // climbs to the root and down again is clearer absolute.
    const auto top = [](const fs::path& p) {
        return p.relative_path().empty() ? fs::path() : *p.relative_path().begin();
    };
    const fs::path relative = blade.lexically_relative(base);
    return relative.empty() || top(blade) != top(base) ? blade.string() : relative.string();
}

/// The scene's key that each input setting set, to report a scene refusal against the file's line.
using Origins = std::map<std::string, const InputSetting*>;

}  // namespace

ImportedBlade read_bmodes_main(const std::string& path)
{
    return parse_bmodes(read_input(path));
}

ImportedBlade read_elastodyn_main(const std::string& path)
{
    return parse_elastodyn(read_input(path));
}

ImportedBlade read_main_input(const std::string& path)
{
    const InputText t = read_input(path);
    if (!t.lines.empty() && t.lines[0].find("BModes") != std::string::npos) return parse_bmodes(t);
    for (const std::string& line : t.lines)
        if (section_of(line) == "TURBINE CONFIGURATION") return parse_elastodyn(t);
    fail(t, 0, "",
         "a BModes main input file (a first line naming BModes) or an ElastoDyn main input file (a TURBINE "
         "CONFIGURATION section)");
}

namespace {

/// The scene's opening comment: where the blade comes from, and how to take its modes.
std::string scene_intro(const ImportedBlade& b, const std::string& scene_path, double speed, double omega)
{
    const std::string input = printable(std::filesystem::path(b.file).filename().string(), 200);
    std::string s;
    s += "# One blade of the rotor in " + input + " (" + b.format + "), written by hubbeam import:\n";
    s += "# clamped to the hub, spun up from rest to the file's rotor speed, its section from the file it names.\n";
    s += "#\n";
    s += "# Its natural modes about the steady spin of " + toml_number(speed) + " rpm (" +
         toml_number(omega) + " rad/s):\n";
    s += "#   hubbeam modes " + quoted_string(scene_path) + " --omega " + toml_number(omega) + "\n";
    if (omega > 0.0)  // a range up to twice the speed, in steps that resolve a blade's first modes
        s += "# (or --omega 0:" + toml_number(std::ceil(2.0 * omega * 10.0) / 10.0) + ":0.1 for a Campbell diagram).\n";
    s += "# Every value below names the setting it came from.\n";
    return s;
}

/// [discretization]: FEM, 16 elements each way, axial coordinates where a tension centre's offset needs them, twist
/// where the section file gives its stiffness and mass moments.
std::string discretization_table(const BladeTable& table)
{
    const bool twist_field = !table.GJ.empty() && !table.mass_moment_flap.empty() && [&] {
        for (std::size_t k = 0; k < table.x_over_L.size(); ++k)
            if (!(table.mass_moment_flap[k] + table.mass_moment_edge[k] > 0.0)) return false;
        return true;
    }();
    std::string s = "\n[discretization]\n";
    s += key_line("method", "\"fem\"", "finite elements along the span");
    // 16 elements each way: the first bending and twist modes within a fraction of a percent of a converged mesh
    // (docs/import.md), for a few seconds of modes; twist's linear elements need as many as bending's.
    s += key_line("ny", "16", "edgewise (in the plane of rotation)");
    // A tension centre off the axis couples the stretch to bending: the axis must stretch (docs/model.md 12.6).
    const bool tension = std::any_of(table.tc_offset.begin(), table.tc_offset.end(), [](double d) { return d != 0.0; });
    if (tension)
        s += key_line("nx", "16", "axial: the tension centre's offset (tc_offst) couples the stretch to bending");
    else
        s += key_line("nx", "0", "no axial coordinates: their modes are far above the blade's");
    s += key_line("nz", "16", "flapwise");
    s += key_line("nt", twist_field ? "16" : "0",
                  twist_field ? "twist" : "no twist: the section file gives no torsional stiffness or mass moments");
    return s;
}

/// s checked by hubbeam's own reader, as `hubbeam run` will read it: a value out of the scene's range is refused
/// here, against the input's line, before anything is written.
void check_scene(const ImportedBlade& b, const std::string& s, const std::string& scene_path)
{
    Origins origins = {{"beam.length", &b.tip_radius},   {"beam.pitch", &b.pitch},
                       {"beam.precone", &b.precone},     {"hub.radius", &b.hub_radius},
                       {"tip.mass", &b.tip_mass},        {"tip.inertia", &b.tip_inertia},
                       {"tip.inertia_flap", &b.tip_inertia_flap}, {"tip.inertia_twist", &b.tip_inertia_twist},
                       {"tip.offset", &b.tip_offset},    {"motion.omega0", &b.rotor_speed}};
    for (std::size_t k = 0; k < b.blade_scale.size(); ++k)
        origins[std::string("blade_scale.") + scene_io::blade_scale_fields[k].key] = &b.blade_scale[k];
    try {
        (void)parse_scene(s, scene_path);
    } catch (const SceneError& e) {
        const auto it = origins.find(e.key);
        if (it == origins.end() || it->second->line == 0) throw;
        throw MainInputError(printable(b.file, 400), it->second->line, printable(it->second->name, 60),
                             "a value whose " + e.key + " hubbeam accepts: " + e.problem());
    }
}

}  // namespace

std::string imported_scene_toml(const ImportedBlade& b, const std::string& scene_path)
{
    const bool bmodes = b.format == main_input_bmodes;
    // The section file first: a refusal of it names its own line and column (blade_files.cpp).
    BladeTable table = read_blade_file(b.blade_file);
    BladeScale scale;  // the multipliers, as the scene's [blade_scale] will apply them
    for (std::size_t k = 0; k < b.blade_scale.size(); ++k)
        scale.*scene_io::blade_scale_fields[k].factor = b.blade_scale[k].value;
    scene_io::scale_columns(table, scale);
    // The speed BModes analyses: romg times romg_mult (the field's ImportedBlade::rotor_speed_factor).
    const double speed = b.rotor_speed.value * b.rotor_speed_factor.value, omega = speed * rpm;
    const std::string speed_origin =
        origin(b, b.rotor_speed, "rpm") +
        (b.rotor_speed_factor.line > 0 ? " times " + origin(b, b.rotor_speed_factor, "") : std::string());
    const std::string radius_names = bmodes ? "radius - hub_rad" : "TipRad - HubRad";

    std::string s = scene_intro(b, scene_path, speed, omega);
    s += "\n[beam]\n";
    const double length = b.tip_radius.value - b.hub_radius.value;
    s += key_line("length", toml_number(length),
                  "m: " + radius_names + " (lines " + std::to_string(b.tip_radius.line) + ", " +
                      std::to_string(b.hub_radius.line) + ")");
    s += key_line("blade_file", quoted_string(name_from_scene(b.blade_file, scene_path)),
                  origin(b, b.blade_file_setting, ""));
    s += key_line("pitch", toml_number(b.pitch.value * degree), "rad: " + origin(b, b.pitch, "deg"));
    s += key_line("precone", toml_number(b.precone.value * degree), "rad: " + origin(b, b.precone, "deg"));
    s += "\n[hub]\n";
    s += key_line("radius", toml_number(b.hub_radius.value), "m: " + origin(b, b.hub_radius, "m"));
    s += tip_table(b);
    s += blade_scale_table(b);
    s += damping_table(b);
    if (b.has_gravity) {
        s += "\n# " + origin(b, b.gravity, "m/s^2") + ": the rotor turns in a vertical plane. hubbeam modes takes\n";
        s +=
            "# the modes about a steady spin without gravity (under its weight a spinning blade moves periodically);\n";
        s += "# for hubbeam run, uncomment:\n";
        s += "# [gravity]\n# g = " + toml_number(b.gravity.value) + "\n";
    }
    s += "\n[motion]\n";
    s += key_line("kind", "\"spin-up\"", "from rest to omega0 (hubbeam run); modes take the steady spin");
    s += key_line("omega0", toml_number(omega), "rad/s: " + speed_origin);
    s += key_line("duration", "20.0", "s to reach omega0");
    s += discretization_table(table);
    s += "\n[output]\n";
    s += key_line("t_end", "40.0", "s (hubbeam run)");
    s += key_line("dt_out", "0.05", "s");
    check_scene(b, s, scene_path);
    return s;
}

}  // namespace hubbeam
