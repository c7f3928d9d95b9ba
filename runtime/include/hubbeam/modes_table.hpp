// The modes table of a scene (hubbeam modes, hubbeam.modes): each variant's natural modes at each spin rate, tracked
// from rate to rate, and the critical speeds of its tracked modes; with the one list of each table's columns, from
// which the CSV headers, the CSV lines and the Python module's keys are all read.
#pragma once

#include <functional>
#include <string>
#include <variant>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/linearize.hpp>

namespace hubbeam {

/// What a modes table covers: each method of methods with each Ny of ny, Nz of nz and Nt of nt in place of the
/// scene's own (by method, then Ny, Nz, Nt), at each spin rate of omegas (increasing: the modes are tracked in that
/// order), and the harmonics n whose excitation lines omega = n Omega give the critical speeds (none: empty). An
/// empty nz or nt list stands for the scene's own count.
struct ModesRequest {
    std::vector<double> omegas;
    std::vector<Method> methods;
    std::vector<int> ny, nz, nt;
    std::vector<int> harmonics;
    /// A rotor's frame (multi-blade coordinates where they apply, with Frame::fixed).
    Frame frame = Frame::fixed;
};

/// multiblade_refusal for the scene's blades (Rotor::blade's parameters of each): why its modes and linear model have
/// no multi-blade form, or empty.
std::string multiblade_refusal(const Scene& scene);
/// Why the fixed frame, asked for by name, does not fit the scene, or empty: multiblade_refusal's reason, or the
/// [control] that may feed back blade 1's tip (the command line's --frame fixed, hubbeam.modes' frame="fixed").
std::string fixed_frame_refusal(const Scene& scene);
/// Whether the scene's modes and linear model are in multi-blade coordinates in frame: Frame::fixed, no [control]
/// (a controller may feed back blade 1's tip), and multiblade_refusal empty.
bool multiblade(const Scene& scene, Frame frame);

/// One variant's part of the table: campbell's rows (rate by rate, each rate's by frequency) and the critical
/// speeds of its tracked modes; unit is the scene's frequency_unit, by which the dimensionless column divides.
struct ModesBlock {
    VariantKey key;
    double unit = 1.0;
    std::vector<SpinMode> modes;
    std::vector<CriticalSpeed> critical;
};

/// The block of the variant key, whose model is given: about the steady spin at each rate, under gravity about the
/// hub held at the scene's angle at t = 0, with [control] the closed loop's modes; a rotor's in frame. check as
/// campbell's. Throws what campbell and critical_speeds throw.
ModesBlock modes_block(const Model& model, const VariantKey& key, const Scene& scene,
                       const std::vector<double>& omegas, const std::vector<int>& harmonics,
                       const std::function<void()>& check = {}, Frame frame = Frame::fixed);

/// The table: each variant's block in turn, its model made and dropped, handed to done as soon as it is complete
/// (hubbeam modes prints a variant's lines before the next variant is computed) and kept by none here: a block of
/// many spin rates holds every mode's shape.
void modes_table(const Scene& scene, const ModesRequest& request, const std::function<void(const ModesBlock&)>& done);

/// A table's cell: a number (written in its shortest round-trip form), an integer or a text. A column's kind is
/// that of its cell of an empty row.
using TableCell = std::variant<double, int, std::string>;

/// A column of the modes table (Row SpinMode) or of the critical speeds (Row CriticalSpeed): its name, in the CSV
/// header and as the Python module's key, and its cell of a block's row. The variant's columns (method, ny, nx, nz,
/// nt, order, drive) lead either table's lines; the Python module gives the variant's name instead.
template <class Row>
struct TableColumn {
    const char* name;
    TableCell (*cell)(const ModesBlock& block, const Row& row);
    bool of_variant = false;
};

/// The modes CSV's columns, in order (modes_header joins their names).
const std::vector<TableColumn<SpinMode>>& modes_columns();
/// The critical speeds CSV's columns, in order: the variant, the tracked mode, the harmonic n, the spin rate and
/// the mode's frequency there.
const std::vector<TableColumn<CriticalSpeed>>& critical_columns();

/// The CSV header of the critical speeds (hubbeam modes --critical).
const char* critical_header();

/// A mode's line of the modes CSV (no newline).
std::string modes_line(const ModesBlock& block, const SpinMode& row);
/// A critical speed's line of the critical speeds CSV (no newline).
std::string critical_line(const ModesBlock& block, const CriticalSpeed& row);

/// A run of consecutive spin rates of a table at each of which some mode grows: from the first such rate to the last
/// (the band's edges lie within a step of the rates outside them), and the labels of the lines that grow there.
struct UnstableRange {
    double from = 0.0, to = 0.0;
    std::vector<std::string> labels;
};
/// The block's unstable ranges, by increasing spin: a mode grows where its growth rate exceeds 1e-8 of its undamped
/// frequency (the round-off of a marginal one, which a conservative model reports as 0, stays below it).
std::vector<UnstableRange> unstable_ranges(const ModesBlock& block);

}  // namespace hubbeam
