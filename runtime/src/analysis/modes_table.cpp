// The modes table's one assembly (modes_table.hpp): hubbeam modes writes and prints it, hubbeam.modes converts it.
#include <hubbeam/modes_table.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>

#include <hubbeam/make_model.hpp>
#include <hubbeam/shortest.hpp>

namespace hubbeam {

std::string multiblade_refusal(const Scene& scene)
{
    std::vector<std::vector<double>> blades;
    for (int b = 0; b < scene.rotor.blades; ++b) blades.push_back(scene.rotor.blade(scene.parameters, b).packed());
    return multiblade_refusal(scene.key(), blades);
}

std::string fixed_frame_refusal(const Scene& scene)
{
    if (scene.control)
        return "the scene's [control] may feed back blade 1's tip, which no multi-blade coordinate holds; the frame "
               "rotating gives each blade's modes in its own frame";
    const std::string why = multiblade_refusal(scene);
    return why.empty() ? why : why + "; the frame rotating gives each blade's modes in its own frame";
}

bool multiblade(const Scene& scene, Frame frame)
{
    return frame == Frame::fixed && !scene.control && multiblade_refusal(scene).empty();
}

ModesBlock modes_block(const Model& model, const VariantKey& key, const Scene& scene,
                       const std::vector<double>& omegas, const std::vector<int>& harmonics,
                       const std::function<void()>& check, Frame frame)
{
    ModesBlock block{key, frequency_unit(scene.parameters), {}, {}};
    const double theta = scene.motion.initial_theta();  // the held angle of a gravity variant
    block.modes = campbell(model, omegas, scene.axial, theta, scene.controller(), check, frame);
    block.critical =
        critical_speeds(model, block.modes, harmonics, scene.axial, theta, scene.controller(), check, frame);
    return block;
}

void modes_table(const Scene& scene, const ModesRequest& request, const std::function<void(const ModesBlock&)>& done)
{
    const auto or_scene = [](const std::vector<int>& counts, int own) {
        return counts.empty() ? std::vector<int>{own} : counts;
    };
    for (const Method method : request.methods)
        for (const int ny : request.ny)
            for (const int nz : or_scene(request.nz, scene.variant.nz))
                for (const int nt : or_scene(request.nt, scene.variant.nt)) {
                    VariantKey key = scene.key();
                    key.method = method;
                    key.ny = ny;
                    key.nz = nz;
                    key.nt = nt;
                    const std::unique_ptr<Model> model = make_scene_model(scene, key);
                    done(modes_block(*model, key, scene, request.omegas, request.harmonics, {}, request.frame));
                }
}

namespace {

/// The variant's columns, then a table's own.
template <class Row>
std::vector<TableColumn<Row>> after_variant(std::initializer_list<TableColumn<Row>> own)
{
    using B = const ModesBlock&;
    using R = const Row&;
    std::vector<TableColumn<Row>> columns = {
        {"method", [](B b, R) -> TableCell { return to_string(b.key.method); }, true},
        {"ny", [](B b, R) -> TableCell { return b.key.ny; }, true},
        {"nx", [](B b, R) -> TableCell { return b.key.nx; }, true},
        {"nz", [](B b, R) -> TableCell { return b.key.nz; }, true},
        {"nt", [](B b, R) -> TableCell { return b.key.nt; }, true},
        {"order", [](B b, R) -> TableCell { return to_string(b.key.order); }, true},
        {"drive", [](B b, R) -> TableCell { return to_string(b.key.drive); }, true}};
    columns.insert(columns.end(), own);
    return columns;
}

/// The header line of columns.
template <class Row>
std::string header_of(const std::vector<TableColumn<Row>>& columns)
{
    std::string header;
    for (const TableColumn<Row>& column : columns) {
        if (!header.empty()) header += ',';
        header += column.name;
    }
    return header;
}

/// The CSV line of a block's row.
template <class Row>
std::string line_of(const std::vector<TableColumn<Row>>& columns, const ModesBlock& block, const Row& row)
{
    std::string line;
    for (std::size_t i = 0; i < columns.size(); ++i) {
        if (i > 0) line += ',';
        const TableCell cell = columns[i].cell(block, row);
        if (const double* v = std::get_if<double>(&cell))
            append_shortest(line, *v);
        else if (const int* n = std::get_if<int>(&cell))
            line += std::to_string(*n);
        else
            line += std::get<std::string>(cell);
    }
    return line;
}

}  // namespace

const std::vector<TableColumn<SpinMode>>& modes_columns()
{
    using B = const ModesBlock&;
    using R = const SpinMode&;
    // Never destroyed: a thread still computing while the process exits (a Python daemon thread) may read it.
    static const std::vector<TableColumn<SpinMode>>& columns = *new std::vector<TableColumn<SpinMode>>(after_variant<SpinMode>({
        {"omega", [](B, R r) -> TableCell { return r.omega; }},
        {"mode", [](B, R r) -> TableCell { return r.number; }},
        {"kind", [](B, R r) -> TableCell { return r.mode.kind; }},
        {"rad_s", [](B, R r) -> TableCell { return r.mode.rad_s; }},
        {"hz", [](B, R r) -> TableCell { return r.mode.rad_s / (2.0 * M_PI); }},
        {"dimensionless", [](B b, R r) -> TableCell { return r.mode.rad_s / b.unit; }},
        {"growth", [](B, R r) -> TableCell { return r.mode.growth; }},
        {"undamped_rad_s", [](B, R r) -> TableCell { return r.mode.undamped_rad_s; }},
        {"damping_ratio", [](B, R r) -> TableCell { return r.mode.damping_ratio; }},
        {"label", [](B, R r) -> TableCell { return r.label; }},
        {"mac", [](B, R r) -> TableCell { return r.mac; }},
    }));
    return columns;
}

const std::vector<TableColumn<CriticalSpeed>>& critical_columns()
{
    using B = const ModesBlock&;
    using R = const CriticalSpeed&;
    // Never destroyed: a thread still computing while the process exits (a Python daemon thread) may read it.
    static const std::vector<TableColumn<CriticalSpeed>>& columns = *new std::vector<TableColumn<CriticalSpeed>>(after_variant<CriticalSpeed>({
        {"label", [](B, R c) -> TableCell { return c.label; }},
        {"harmonic", [](B, R c) -> TableCell { return c.harmonic; }},
        {"omega", [](B, R c) -> TableCell { return c.omega; }},
        {"rad_s", [](B, R c) -> TableCell { return c.rad_s; }},
        {"hz", [](B, R c) -> TableCell { return c.rad_s / (2.0 * M_PI); }},
    }));
    return columns;
}

const char* modes_header()
{
    static const std::string h = header_of(modes_columns());
    return h.c_str();
}

const char* critical_header()
{
    static const std::string h = header_of(critical_columns());
    return h.c_str();
}

std::string modes_line(const ModesBlock& block, const SpinMode& row) { return line_of(modes_columns(), block, row); }

std::vector<UnstableRange> unstable_ranges(const ModesBlock& block)
{
    std::vector<UnstableRange> out;
    bool open = false;  // the last rate seen had a growing mode: its range is out.back()
    for (std::size_t i = 0; i < block.modes.size();) {
        const double omega = block.modes[i].omega;
        std::vector<std::string> growing;
        for (; i < block.modes.size() && block.modes[i].omega == omega; ++i) {
            const NaturalMode& m = block.modes[i].mode;
            if (m.growth > 1e-8 * std::max(m.undamped_rad_s, 1e-300)) growing.push_back(block.modes[i].label);
        }
        if (growing.empty()) {
            open = false;
            continue;
        }
        if (!open) out.push_back({omega, omega, {}});
        open = true;
        UnstableRange& r = out.back();
        r.to = omega;
        for (std::string& label : growing)
            if (std::find(r.labels.begin(), r.labels.end(), label) == r.labels.end()) r.labels.push_back(std::move(label));
    }
    return out;
}

std::string critical_line(const ModesBlock& block, const CriticalSpeed& row)
{
    return line_of(critical_columns(), block, row);
}

}  // namespace hubbeam
