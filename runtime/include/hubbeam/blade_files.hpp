// Readers for the blade-property files rotor-blade engineers already have: NREL BModes' section-properties file and
// the distributed blade properties of an OpenFAST (or FAST v7) ElastoDyn blade file, each into one BladeTable.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hubbeam {

/// A blade's section properties at its stations, in SI units with the twist in radians, as a file gave them (its
/// adjustment factors applied, its mass moments about their principal axes at their own angle). All vectors have one
/// entry per station; an optional one is empty when the file's format has no such column.
struct BladeTable {
    std::vector<double> x_over_L;          // station: 0 at the root to 1 at the tip, strictly increasing
    std::vector<double> mass_per_length;   // kg/m
    std::vector<double> EI_flap;           // N m^2: bending out of the chord's plane (flapwise)
    std::vector<double> EI_edge;           // N m^2: bending along the chord (edgewise)
    std::vector<double> GJ;                // N m^2: torsional stiffness (optional)
    std::vector<double> EA;                // N: axial stiffness (optional)
    std::vector<double> twist;             // rad: structural pre-twist, with the file's sign (both formats share it)
    std::vector<double> mass_moment_flap;  // kg m: mass moment of inertia per length about the principal inertia
                                           // axis nearer the chord (the chord where inertia_twist is empty; optional)
    std::vector<double> mass_moment_edge;  // kg m: the same about the other principal axis (optional)
    std::vector<double> inertia_twist;     // rad: the principal inertia axes' angle (optional: the twist's)
    std::vector<double> cg_offset;         // m: the centre of mass off the reference axis along the chord, towards
                                           // the trailing edge (optional)
    std::vector<double> tc_offset;         // m: the tension centre off the reference axis likewise (optional)
    std::string source;                    // the format read: bmodes_source or elastodyn_source
};

/// BladeTable::source of a BModes section-properties file.
inline constexpr const char* bmodes_source = "BModes section properties";
/// BladeTable::source of an ElastoDyn blade file (FAST v7, FAST v8 to OpenFAST v4, OpenFAST v5 columns alike).
inline constexpr const char* elastodyn_source = "ElastoDyn blade";

/// The largest blade file read (bytes): a blade of thousands of stations is a few hundred kilobytes.
inline constexpr std::size_t max_blade_file_bytes = 16u << 20;
/// The longest line read (bytes): the formats' longest lines (FAST v7's 17 columns, a parameter with its
/// description and a comment) are a few hundred bytes.
inline constexpr std::size_t max_blade_line_bytes = 4096;

/// A blade file that cannot be read, or holds what hubbeam does not model: where and what was expected, never what
/// the file holds (the path named may be any file its reader can read, and the message may reach someone who cannot).
/// what() is one line: "FILE[:LINE]: [column NAME[, station K]: ]expected ...".
struct BladeFileError : std::runtime_error {
    std::string file;      // the path, made printable
    long line = 0;         // 1-based; 0 when the file as a whole is at fault
    std::string column;    // the column's name in the file's format, or empty
    long station = 0;      // 1-based row of the table, or 0
    std::string expected;  // what was expected there, and why when hubbeam refuses a value

    BladeFileError(std::string file, long line, std::string column, long station, std::string expected);
};

/// Reads a BModes section-properties file (the sec_props_file of a .bmi): a title, n_secs, a line BModes skips, the
/// column titles sec_loc (or span_loc) str_tw tw_iner mass_den flp_iner edge_iner flp_stff edge_stff tor_stff
/// axial_stff cg_offst sc_offst tc_offst, their units, then n_secs rows. Throws BladeFileError.
BladeTable read_bmodes_sections(const std::string& path);

/// Reads the DISTRIBUTED BLADE PROPERTIES of an ElastoDyn blade file, its columns found by name (BlFract, StrcTwst,
/// BMassDen, FlpStff, EdgStff; PitchAxis up to OpenFAST v4; FAST v7's AeroCent, GJStff, EAStff, FlpIner, EdgIner and
/// offsets), with AdjBlMs, AdjFlSt and AdjEdSt applied as ElastoDyn applies them. Throws BladeFileError.
BladeTable read_elastodyn_blade(const std::string& path);

/// Reads a blade file of either format, recognised from its content (an ElastoDyn file has a DISTRIBUTED BLADE
/// PROPERTIES section, a BModes file the column titles str_tw ... mass_den). Throws BladeFileError.
BladeTable read_blade_file(const std::string& path);

/// A field of the field's input files as a finite number, in Fortran's forms too (1.5D+03, +2., .5); false when it is
/// none (BModes' and ElastoDyn's blade and main files alike).
bool fortran_number(std::string_view field, double& x);

}  // namespace hubbeam
