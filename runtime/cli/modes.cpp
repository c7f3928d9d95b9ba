// hubbeam modes and hubbeam linearize: the linearization of linearize.hpp applied to a scene's variants, as tables.
#include "modes.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <hubbeam/csv_columns.hpp>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/metadata.hpp>
#include <hubbeam/mode_shapes.hpp>
#include <hubbeam/npz.hpp>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>
#include <map>
#include <memory>
#include <ostream>
#include <span>
#include <utility>

#include "plot.hpp"
#include "terms.hpp"

namespace hubbeam {

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& expected, const std::string& got)
{
    bad_option<ModesOptionError>(option, expected, got);
}

constexpr std::size_t max_spin_rates = 10000;

/// The angle a gravity scene's hub is held at for its modes (rad): the scene's angle at t = 0 (a held hub's
/// angle, theta0 of the other drives; 0 is a horizontal beam).
double held_angle(const Scene& scene)
{
    return scene.motion.initial_theta();
}

/// Refuses, before anything is computed, a spin rate about which the scene has no steady state (unsteady_spin):
/// linearize's always; with periodic, modes', which takes the periodic motion's Floquet modes there, only where that
/// analysis cannot take the scene (a controlled hub, quasi-static axial coordinates).
void check_steady(const Scene& scene, const std::vector<double>& omegas, Frame frame, bool periodic = false)
{
    for (const double omega : omegas) {
        if (unsteady_spin(scene.key(), scene.parameters.packed(), omega).empty() || multiblade(scene, frame)) continue;
        const bool quasi_static = scene.axial == Axial::quasi_static && scene.variant.nx > 0;
        if (periodic && !scene.control && !quasi_static) continue;
        if (periodic)
            throw ModesOptionError(
                "--omega: with gravity in the plane of rotation only 0 (the hub held) " +
                std::string(scene.control ? "under [control] (the closed loop's periodic modes are not computed)"
                                          : "with model.axial = \"quasi-static\" (the Floquet analysis of the "
                                            "periodic motion needs dynamic axial coordinates)") +
                ", got " + shortest(omega));
        if (scene.variant.extras.hub)
            throw ModesOptionError("--omega: " + unsteady_spin(scene.key(), scene.parameters.packed(), omega) +
                                   (frame == Frame::rotating ? "" : " (" + multiblade_refusal(scene) + ")") +
                                   ", got " + shortest(omega));
        throw ModesOptionError(
            "--omega: with gravity in the plane of rotation only 0 (the hub held; at a spin rate the motion is "
            "periodic, not steady), got " +
            shortest(omega));
    }
}

/// Every (method, Ny, Nz, Nt) of the request must be a variant of the scene, checked before anything is computed.
/// A count the method cannot take is named by its option: the first of --ny, --nz and --nt whose value alone (the
/// other counts the scene's) the method refuses; where none does, the method cannot take the scene's own counts (an
/// odd Nz for FEM), and --methods is named. A combination the scene refuses otherwise (a twist field without
/// beam.shear_modulus) is the scene's message, naming its file and key.
void check_variants(const Scene& scene, const ModesRequest& o)
{
    struct Count {
        const char* option;
        int VariantKey::* member;
    };
    const Count counts[] = {{"--ny", &VariantKey::ny}, {"--nz", &VariantKey::nz}, {"--nt", &VariantKey::nt}};
    for (const Method m : o.methods)
        for (const int ny : o.ny)
            for (const int nz : o.nz)
                for (const int nt : o.nt) {
                    Scene s = scene;
                    s.variant.method = m;
                    s.variant.ny = ny;
                    s.variant.nz = nz;
                    s.variant.nt = nt;
                    if (const std::string why = s.variant.dof_problem(); !why.empty()) {
                        VariantKey own_counts = scene.variant;
                        own_counts.method = m;
                        for (const Count& c : own_counts.dof_problem().empty() ? std::span<const Count>(counts) : std::span<const Count>()) {
                            VariantKey alone = scene.variant;
                            alone.method = m;
                            alone.*c.member = s.variant.*c.member;
                            if (const std::string own = alone.dof_problem(); !own.empty())
                                throw ModesOptionError(std::string(c.option) + ": " + own);
                        }
                        throw ModesOptionError("--methods: " + why);
                    }
                    try {
                        validate(s);
                    } catch (const SceneError& e) {
                        throw ModesOptionError(e.what());
                    }
                }
}

}  // namespace

std::vector<double> parse_spin_rates(const std::string& option, const std::string& text)
{
    const std::string expected = "a comma-separated list of spin rates >= 0 (rad/s) or ranges FIRST:LAST:STEP";
    std::vector<double> rates;
    for (const std::string& item : split_list(text)) {
        const std::size_t c1 = item.find(':');
        if (c1 == std::string::npos) {
            double v = 0.0;
            if (!parse_non_negative(item, v)) bad(option, expected, item);
            add_unique(rates, v);
            continue;
        }
        const std::size_t c2 = item.find(':', c1 + 1);
        double first = 0.0, last = 0.0, step = 0.0;
        if (c2 == std::string::npos || !parse_non_negative(item.substr(0, c1), first) ||
            !parse_non_negative(item.substr(c1 + 1, c2 - c1 - 1), last) || !parse_positive(item.substr(c2 + 1), step) ||
            last < first || (last - first) / step > static_cast<double>(max_spin_rates))
            bad(option, expected, item);
        const auto count = static_cast<long>(std::floor((last - first) / step * (1.0 + 1e-12)));
        for (long k = 0; k <= count; ++k) add_unique(rates, first + static_cast<double>(k) * step);
    }
    if (rates.size() > max_spin_rates)
        bad(option, "at most 10000 spin rates", std::to_string(rates.size()) + " of them");
    std::sort(rates.begin(), rates.end());  // a Campbell table reads, and its modes are tracked, by increasing rate
    return rates;
}

Frame parse_frame(const std::string& text, const Scene& scene)
{
    Frame frame = Frame::fixed;
    if (text.empty()) return frame;
    if (!parse(text, frame)) bad("--frame", "fixed or rotating", text);
    if (frame == Frame::fixed)
        if (const std::string why = fixed_frame_refusal(scene); !why.empty())
            throw ModesOptionError("--frame fixed: " + why);
    return frame;
}

ModesOptions parse_modes_options(const ModesArgs& args, const Scene& scene)
{
    ModesOptions o;
    o.frame = parse_frame(args.frame, scene);
    if (args.omega.empty()) {
        o.omegas = {0.0};
        if (scene.motion.kind == Motion::Kind::spin_up && scene.motion.omega0 != 0.0 && scene.parameters.g == 0.0)
            o.omegas.push_back(std::abs(scene.motion.omega0));
    } else {
        o.omegas = parse_spin_rates("--omega", args.omega);
        check_steady(scene, o.omegas, o.frame, true);
    }
    o.methods = args.methods.empty() ? std::vector<Method>{scene.variant.method}
                                     : parse_method_list<ModesOptionError>("--methods", args.methods);
    o.ny = args.ny.empty() ? std::vector<int>{scene.variant.ny} : parse_dof_list<ModesOptionError>("--ny", args.ny, 1);
    o.nz = args.nz.empty() ? std::vector<int>{scene.variant.nz} : parse_dof_list<ModesOptionError>("--nz", args.nz, 0);
    o.nt = args.nt.empty() ? std::vector<int>{scene.variant.nt} : parse_dof_list<ModesOptionError>("--nt", args.nt, 0);
    check_variants(scene, o);
    if (!parse_int(args.count, 1, 64, o.count)) bad("--count", "an integer from 1 to 64", args.count);
    o.harmonics = parse_harmonics<ModesOptionError>("--harmonics", args.harmonics);
    o.output = args.output;
    o.plot = args.plot;
    o.critical = args.critical;
    o.elastodyn = args.elastodyn;
    o.quiet = args.quiet;
    if (!o.elastodyn.empty()) {
        // One variant, and a blade that leaves the plane: its flap modes are u_z's.
        const std::size_t variants = o.methods.size() * o.ny.size() * o.nz.size() * o.nt.size();
        if (variants != 1)
            bad("--elastodyn", "one variant (one method, Ny, Nz and Nt) whose mode shapes it holds",
                std::to_string(variants) + " variants");
        if (o.nz.front() == 0)
            bad("--elastodyn",
                "a blade with flapwise coordinates (discretization.nz or --nz > 0: the flap modes' shapes are u_z)",
                "nz = 0");
    }
    if (!o.critical.empty() && o.harmonics.empty())
        bad("--critical", "harmonics whose critical speeds it holds (--harmonics none searches none)",
            printable(o.critical));
    if (!o.plot.empty() && o.output.empty())
        bad("--plot", "-o FILE as well (the diagram is drawn from that CSV)", printable(o.plot));
    // Every output checked before anything is computed: none may be the scene or another output.
    std::vector<NamedPath> outputs = {{o.output, "-o"}, {o.critical, "--critical"}, {o.elastodyn, "--elastodyn"}};
    const std::vector<NamedPath> asked = outputs;
    for (const NamedPath& file : asked)
        if (!file.path.empty()) outputs.push_back({metadata_path(file.path), file.name + "'s metadata"});
    if (!o.plot.empty()) {
        check_prefix("--plot", o.plot);  // before the table is computed and written, not when the figure is drawn
        for (const char* ext : {".png", ".svg", ".gp"}) outputs.push_back({o.plot + ext, "--plot"});
    }
    check_outputs(scene_inputs(scene), outputs);
    return o;
}

namespace {

/// Below this MAC a line's pairing from one rate to the next is in doubt: the shapes changed more than between
/// grid points that resolve them (a crossing's or veering's modes are about 0.5 apart when stepped over halfway).
constexpr double doubtful_mac = 0.8;

/// The least certain pairing of a line from one rate to the next among modes, or nullptr if none is in doubt.
const SpinMode* least_certain(const std::vector<SpinMode>& modes)
{
    const SpinMode* least = nullptr;
    for (const SpinMode& r : modes)
        if (r.mac < (least ? least->mac : doubtful_mac)) least = &r;
    return least;
}

/// What hubbeam modes makes of the table, variant by variant as its blocks come: the printed table, the CSVs
/// (written only when asked for, and put in place only when complete), and after the table each variant's
/// critical speeds and doubtful pairings, the files' names and the figure.
class ModesReport {
public:
    ModesReport(const Scene& scene, const ModesOptions& o, std::ostream& out);
    /// The printed table's column heads.
    void heading() const;
    /// A variant's block: its modes and critical speeds to the CSVs, its first `count` modes of each kind printed.
    void add(const ModesBlock& block);
    /// The CSVs dropped (the table could not be computed): the targets left as they were.
    void discard();
    /// After the last block: the critical speeds and notes printed, the CSVs put in place, the figure drawn.
    void finish();

private:
    void add_modes(const ModesBlock& block);
    void print_mode(const ModesBlock& block, const SpinMode& r) const;
    /// A printed line's variant: method, Ny, Nx, and Nz and Nt where several are asked for.
    std::string counts(const VariantKey& key) const;
    void add_critical(const ModesBlock& block);
    void print_ending() const;
    void draw() const;
    /// The metadata beside each CSV written: the scene, the rates, methods, Ny and harmonics, the variants.
    void write_metadata_files() const;

    const Scene& scene_;
    const ModesOptions& o_;
    std::ostream& out_;
    bool damped_;  // damping adds the undamped frequency |lambda| and the damping ratio to the printed table
    bool counts_;  // several Nz or Nt asked for: the printed lines name them, to tell the variants apart
    bool multiblade_;  // a rotor in multi-blade coordinates: its kinds and labels are longer
    std::unique_ptr<CsvWriter> csv_, critical_csv_;
    std::unique_ptr<MetadataFile> csv_metadata_, critical_metadata_;  // opened with their CSVs, before the modes
    long rows_ = 0, crossings_ = 0;
    std::string harmonics_;               // as typed for --plot, and for the table's heading
    std::string speeds_text_, warnings_;  // after the table: each variant's critical speeds and doubtful pairings
    std::vector<std::string> variants_;   // each block's variant, for the metadata
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

ModesReport::ModesReport(const Scene& scene, const ModesOptions& o, std::ostream& out)
    : scene_(scene), o_(o), out_(out), damped_(scene.damped() || scene.control),
      counts_(o.nz.size() > 1 || o.nt.size() > 1), multiblade_(multiblade(scene, o.frame))
{
    try {
        if (!o.output.empty()) {
            csv_ = std::make_unique<CsvWriter>(o.output, modes_header());
            csv_metadata_ = std::make_unique<MetadataFile>(o.output);
        }
        if (!o.critical.empty()) {
            critical_csv_ = std::make_unique<CsvWriter>(o.critical, critical_header());
            critical_metadata_ = std::make_unique<MetadataFile>(o.critical);
        }
    } catch (const std::exception& e) {  // an output refused or that cannot be created: bad input, nothing replaced
        discard();
        throw OutputRefused(e.what());
    }
    for (const int n : o.harmonics) {
        if (!harmonics_.empty()) harmonics_ += ',';
        harmonics_ += std::to_string(n);
    }
    if (harmonics_.empty()) harmonics_ = "none";  // as typed: the diagram draws no excitation line either
}

void ModesReport::heading() const
{
    if (o_.quiet) return;
    // Spin rates without a steady state (weight in the plane of rotation): their modes are the periodic motion's.
    std::vector<double> periodic;
    for (const double omega : o_.omegas)
        if (!unsteady_spin(scene_.key(), scene_.parameters.packed(), omega).empty() && !multiblade_)
            periodic.push_back(omega);
    if (multiblade_)
        out_ << "frame       fixed: multi-blade coordinates of the " << scene_.rotor.blades
             << " blades (collective, cyclic pairs as forward and backward whirls FW and BW"
             << (scene_.rotor.blades % 2 == 0 ? ", differential" : "")
             << "), the hub's own; --frame rotating gives each blade's modes in its own frame\n";
    if (!periodic.empty()) {
        const auto period = [](double omega) {
            char text[40];
            std::snprintf(text, sizeof text, "%.6g", 2.0 * M_PI / omega);
            return std::string(text);
        };
        out_ << "analysis    Floquet over one revolution "
             << (periodic.size() == 1 ? "(period " + period(periodic[0]) + " s at " + shortest(periodic[0]) + " rad/s)"
                                      : "(period 2 pi/Omega, " + period(periodic.back()) + " to " + period(periodic[0]) +
                                            " s, at the " + std::to_string(periodic.size()) + " rates > 0)")
             << (scene_.variant.extras.hub ? ": the support is fixed and the blade turns, the motion is periodic\n"
                                           : ": the weight turns with the plane of rotation, the motion is periodic\n")
             << "            frequency Im(ln mu)/T + k Omega, k the harmonic that dominates the mode; a mode that "
                "decays by more than about 1e8 in a revolution is not resolved, nor listed\n";
    }
    out_ << "method  Ny  Nx" << (counts_ ? "  Nz  Nt" : "") << "  order  Omega rad/s  mode  "
         << (multiblade_ ? "kind               tracked                     rad/s"
                         : "kind        tracked              rad/s")
         << "          Hz  dimensionless  growth 1/s"
         << (damped_ ? "  undamped rad/s     zeta" : "") << "\n";
}

void ModesReport::add(const ModesBlock& block)
{
    variants_.push_back(block.key.name());
    add_modes(block);
    add_critical(block);
    for (const UnstableRange& r : unstable_ranges(block)) {
        std::string labels;
        for (const std::string& l : r.labels) labels += (labels.empty() ? "" : ", ") + l;
        warnings_ += "unstable: " + block.key.name() + ": " + labels + " grow" + (r.labels.size() == 1 ? "s" : "") +
                     (r.from == r.to ? " at Omega = " + shortest(r.from)
                                     : " from Omega = " + shortest(r.from) + " to " + shortest(r.to)) +
                     " rad/s (the band's edges lie within a step of the rates outside it)\n";
    }
    if (const SpinMode* least = least_certain(block.modes))
        warnings_ += "note: " + block.key.name() + ": " + least->label +
                     " continues at Omega = " + shortest(least->omega) + " rad/s with a MAC of only " +
                     shortest(least->mac) +
                     " to its shape at the rate before: the rates may step over a crossing or a veering; "
                     "refine --omega there to follow it\n";
}

void ModesReport::add_modes(const ModesBlock& block)
{
    // Printed: the first `count` modes of each kind (bending or edge and flap, twist, axial, hub, overdamped) of each
    // spin rate.
    std::map<std::string, int> shown;  // by kind, at the current rate
    for (const SpinMode& r : block.modes) {
        if (r.number == 1) shown.clear();
        if (csv_) csv_->write_line(modes_line(block, r));
        ++rows_;
        if (o_.quiet || shown[r.mode.kind]++ >= o_.count) continue;
        print_mode(block, r);
    }
}

std::string ModesReport::counts(const VariantKey& key) const
{
    char line[100];
    if (counts_)
        std::snprintf(line, sizeof line, "%-6s %3d %3d %3d %3d", to_string(key.method).c_str(), key.ny, key.nx, key.nz,
                      key.nt);
    else
        std::snprintf(line, sizeof line, "%-6s %3d %3d", to_string(key.method).c_str(), key.ny, key.nx);
    return line;
}

void ModesReport::print_mode(const ModesBlock& block, const SpinMode& r) const
{
    const VariantKey& key = block.key;
    const NaturalMode& mode = r.mode;
    char line[400];
    out_ << counts(key);
    // A rotor's multi-blade kinds ("differential flap", "collective edge 12") are wider than a blade's.
    const int kind_width = multiblade_ ? 17 : 10, label_width = multiblade_ ? 20 : 13;
    std::snprintf(line, sizeof line, "  %-5s %12.4g  %4d  %-*s  %-*s %11.6g %11.6g %14.6g  %10.3g",
                  to_string(key.order).c_str(), r.omega, r.number, kind_width, mode.kind.c_str(), label_width,
                  r.label.c_str(), mode.rad_s, mode.rad_s / (2.0 * M_PI), mode.rad_s / block.unit, mode.growth);
    out_ << line;
    if (damped_) {
        std::snprintf(line, sizeof line, "  %14.6g %8.4g", mode.undamped_rad_s, mode.damping_ratio);
        out_ << line;
    }
    out_ << '\n';
}

void ModesReport::add_critical(const ModesBlock& block)
{
    const VariantKey& key = block.key;
    crossings_ += static_cast<long>(block.critical.size());
    for (const CriticalSpeed& c : block.critical) {
        if (critical_csv_) critical_csv_->write_line(critical_line(block, c));
        char line[400];
        std::snprintf(line, sizeof line, "  %-13s meets %3dP at Omega = %-12.6g rad/s (%.6g Hz)\n", c.label.c_str(),
                      c.harmonic, c.omega, c.rad_s / (2.0 * M_PI));
        speeds_text_ += counts(key) + line;
    }
}

void ModesReport::discard()
{
    if (csv_) csv_->discard();
    if (critical_csv_) critical_csv_->discard();
}

void ModesReport::finish()
{
    print_ending();
    for (CsvWriter* file : {csv_.get(), critical_csv_.get()})
        if (file && !file->finish()) throw std::runtime_error(file->error());
    write_metadata_files();
    if (csv_) out_ << "modes: " << o_.output << "\n";
    if (critical_csv_) out_ << "critical speeds: " << o_.critical << "\n";
    if (!o_.plot.empty()) draw();
}

void ModesReport::write_metadata_files() const
{
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::vector<std::string> methods;
    for (const Method m : o_.methods) methods.push_back(to_string(m));
    std::vector<double> ny(o_.ny.begin(), o_.ny.end()), harmonics(o_.harmonics.begin(), o_.harmonics.end());
    const std::vector<double> nz(o_.nz.begin(), o_.nz.end()), nt(o_.nt.begin(), o_.nt.end());
    for (const auto& [file, metadata] : {std::pair{csv_.get(), csv_metadata_.get()},
                                         std::pair{critical_csv_.get(), critical_metadata_.get()}}) {
        if (!file) continue;
        JsonObject m = scene_metadata("modes", scene_);
        m.text("output", std::filesystem::path(file->path()).filename().string())
            .integer("rows", file->rows())
            .texts("variants", variants_)
            .numbers("omega", o_.omegas)
            .texts("methods", methods)
            .numbers("ny", ny)
            .numbers("nz", nz)
            .numbers("nt", nt)
            .numbers("harmonics", harmonics)
            .number("wall_seconds", wall);
        if (const std::string why = metadata->write(m.str() + "\n"); !why.empty()) throw std::runtime_error(why);
    }
}

void ModesReport::print_ending() const
{
    const bool searched = !o_.harmonics.empty();  // --harmonics none: no critical speed searched, none printed
    if (o_.quiet)
        out_ << rows_ << " modes of " << variants_.size()
             << " variant(s) at " << o_.omegas.size()
             << " spin rate(s); "
             << (searched ? std::to_string(crossings_) + " critical speed(s)" : "critical speeds not searched") << "\n";
    else if (o_.omegas.size() > 1 && searched)
        out_ << "\ncritical speeds (a tracked mode meets the excitation n x the spin rate, n = " << harmonics_
             << "): " << (crossings_ == 0 ? "none between the rates\n" : "\n") << speeds_text_;
    out_ << warnings_;
}

void ModesReport::draw() const
{
    PlotArgs figure;
    figure.kind = "campbell";
    figure.files = {o_.output};
    figure.prefix = o_.plot;
    figure.harmonics = harmonics_;
    if (const std::string why = draw_plot(figure); !why.empty()) throw std::runtime_error(why);
    out_ << "figure: " << o_.plot << ".{png,svg}\n";
}

}  // namespace

namespace {

/// --elastodyn's file and its metadata: opened (locks taken, temporary files made) before anything is computed,
/// written once the shapes are, and put in place together after the table.
class ElastoDynFile {
public:
    ElastoDynFile(const Scene& scene, const ModesOptions& o) : scene_(scene), o_(o)
    {
        if (o.elastodyn.empty()) return;
        try {
            file_ = std::make_unique<OutputFile>(o.elastodyn);
            metadata_ = std::make_unique<MetadataFile>(o.elastodyn);
        } catch (const std::exception& e) {  // refused, or cannot be created: bad input, nothing replaced
            file_.reset();
            throw OutputRefused(e.what());
        }
    }

    /// The shapes at the first spin rate of the one variant asked for, before the table is computed: a blade whose
    /// modes lack one of them stops here, with nothing written.
    void compute()
    {
        if (!file_) return;
        VariantKey key = scene_.key();
        key.method = o_.methods.front();
        key.ny = o_.ny.front();
        key.nz = o_.nz.front();
        key.nt = o_.nt.front();
        const std::unique_ptr<Model> model = make_scene_model(scene_, key);
        shapes_ = elastodyn_mode_shapes(*model, scene_.parameters, o_.omegas.front(), scene_.axial,
                                        held_angle(scene_));
        variant_ = key.name();
    }

    /// The section and the metadata in place, together; what was written printed to out.
    void finish(std::ostream& out)
    {
        if (!file_) return;
        (void)file_->write(elastodyn_section(shapes_));  // a failed write is reported by commit_together
        std::vector<std::string> names;
        std::vector<double> hz, residuals;
        for (const BladeModeShape* s : {&shapes_.flap1, &shapes_.flap2, &shapes_.edge1}) {
            names.push_back(s->name);
            hz.push_back(s->rad_s / (2.0 * M_PI));
            residuals.push_back(s->fit.residual);
        }
        JsonObject m = scene_metadata("modes", scene_);
        m.text("output", std::filesystem::path(o_.elastodyn).filename().string())
            .text("variant", variant_)
            .number("omega", shapes_.omega)
            .texts("modes", names)
            .numbers("hz", hz)
            .numbers("residuals", residuals);
        if (const std::string why = metadata_->write(m.str() + "\n"); !why.empty()) throw std::runtime_error(why);
        if (const std::string why = file_->commit(); !why.empty()) throw std::runtime_error(why);
        out << "elastodyn: " << o_.elastodyn << " (BLADE MODE SHAPES of " << variant_ << " at Omega = "
            << shortest(shapes_.omega) << " rad/s" << (o_.omegas.size() > 1 ? ", the first spin rate" : "") << ")\n";
        const char* file_names[] = {"BldFl1Sh", "BldFl2Sh", "BldEdgSh"};
        for (std::size_t i = 0; i < 3; ++i) {
            char line[200];
            std::snprintf(line, sizeof line, "  %s  %-7s %11.6g Hz  fit residual %.3g of the tip deflection\n",
                          file_names[i], names[i].c_str(), hz[i], residuals[i]);
            out << line;
        }
    }

private:
    const Scene& scene_;
    const ModesOptions& o_;
    std::unique_ptr<OutputFile> file_;
    std::unique_ptr<MetadataFile> metadata_;
    ElastoDynShapes shapes_;
    std::string variant_;
};

}  // namespace

void run_modes(const Scene& scene, const ModesOptions& o, std::ostream& out)
{
    ElastoDynFile elastodyn(scene, o);
    elastodyn.compute();
    ModesReport report(scene, o, out);
    try {
        report.heading();
        modes_table(scene, o, [&report](const ModesBlock& block) { report.add(block); });
    } catch (...) {
        report.discard();
        throw;
    }
    report.finish();
    elastodyn.finish(out);
}

namespace {

/// linearize's files: the four matrices' CSVs of each system (the closed loop's, then a controlled hub's open loop's),
/// then each system's .npz; csv_count says where the archives start.
struct LinearizeFiles {
    std::vector<NamedPath> outputs;
    std::size_t csv_count = 0;
};

/// The files linearize writes under prefix for scene.
LinearizeFiles linearize_files(const Scene& scene, const std::string& prefix)
{
    // A controlled hub: the closed loop (input: a torque added to the controller's) in PREFIX-*.csv, and the open
    // loop (input tau), what a control design starts from, in PREFIX-open-*.csv.
    std::vector<std::string> prefixes = {prefix};
    if (scene.control) prefixes.push_back(prefix + "-open");
    LinearizeFiles files;
    std::vector<NamedPath>& outputs = files.outputs;
    for (const std::string& p : prefixes)
        for (const char* name : {"A", "B", "C", "D"}) outputs.push_back({p + "-" + name + ".csv", "-o"});
    files.csv_count = outputs.size();
    for (const std::string& p : prefixes) outputs.push_back({p + ".npz", "-o"});  // the same model for numpy
    return files;
}

/// Matrix m (0 to 3: A, B, C, D) of sys as CSV: a header of column names, then each row led by its name.
std::string matrix_csv(const StateSpace& sys, std::size_t m)
{
    const Eigen::MatrixXd* X = std::array<const Eigen::MatrixXd*, 4>{&sys.A, &sys.B, &sys.C, &sys.D}[m];
    const bool state_rows = m < 2, state_columns = m % 2 == 0;
    const std::vector<std::string>& rows = state_rows ? sys.states : sys.outputs;
    std::string bytes = std::string(1, "ABCD"[m]);
    for (const std::string& c : state_columns ? sys.states : sys.inputs) bytes += "," + c;
    bytes += '\n';
    for (Eigen::Index i = 0; i < X->rows(); ++i) {
        bytes += rows[static_cast<std::size_t>(i)];
        for (Eigen::Index j = 0; j < X->cols(); ++j) {
            bytes += ',';
            append_shortest(bytes, (*X)(i, j));
        }
        bytes += '\n';
    }
    return bytes;
}

/// sys as a numpy archive: its matrices and the names of its states, inputs and outputs.
std::string state_space_npz(const StateSpace& sys)
{
    return npz_archive({{"A", npy_matrix(sys.A)},
                        {"B", npy_matrix(sys.B)},
                        {"C", npy_matrix(sys.C)},
                        {"D", npy_matrix(sys.D)},
                        {"states", npy_strings(sys.states)},
                        {"inputs", npy_strings(sys.inputs)},
                        {"outputs", npy_strings(sys.outputs)}});
}

/// linearize's files and their metadata, opened (locks taken, temporary files made) before anything is computed;
/// one that is refused or cannot be created is bad input (OutputRefused), and nothing is written.
struct LinearizeOutputs {
    std::vector<std::unique_ptr<OutputFile>> files;  // as LinearizeFiles::outputs
    std::unique_ptr<MetadataFile> metadata;
};
LinearizeOutputs open_linearize_outputs(const LinearizeFiles& files, const std::string& prefix)
{
    LinearizeOutputs out;
    try {
        for (const NamedPath& f : files.outputs) out.files.push_back(std::make_unique<OutputFile>(f.path));
        out.metadata = std::make_unique<MetadataFile>(prefix);
    } catch (const std::exception& e) {  // those opened already are discarded with out
        throw OutputRefused(e.what());
    }
    return out;
}

/// The systems' CSVs and archives into written (open_linearize_outputs), put in place together (commit_together) once
/// all are written: a full disk leaves the old set whole.
void write_state_spaces(const std::vector<std::unique_ptr<OutputFile>>& written, const LinearizeFiles& files,
                        const std::vector<const StateSpace*>& systems)
{
    for (std::size_t f = 0; f < files.outputs.size(); ++f) {
        const std::string bytes =
            f < files.csv_count ? matrix_csv(*systems[f / 4], f % 4) : state_space_npz(*systems[f - files.csv_count]);
        (void)written[f]->write(bytes);  // a failed write is reported by commit_together, before any rename
    }
    std::vector<OutputFile*> set;
    for (const auto& f : written) set.push_back(f.get());
    if (const std::string why = commit_together(set); !why.empty()) throw std::runtime_error(why);
}

/// linearize's metadata beside its files: the scene, the spin, the model's source and the system's names.
void write_linearize_metadata(MetadataFile& metadata, const Scene& scene, const LinearizeFiles& files,
                              double omega, const SteadySpin& steady, const Model& model, const StateSpace& ss,
                              std::chrono::steady_clock::time_point start, bool coleman)
{
    std::vector<std::string> names;
    for (const NamedPath& f : files.outputs) names.push_back(std::filesystem::path(f.path).filename().string());
    JsonObject m = scene_metadata("linearize", scene);
    m.texts("files", names)
        .number("omega", omega)
        .boolean("held", steady.held)
        .text("source", model.source())
        .texts("states", ss.states)
        .texts("inputs", ss.inputs)
        .texts("outputs", ss.outputs);
    if (coleman) m.text("frame", "fixed: multi-blade coordinates");
    m.number("wall_seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (const std::string why = metadata.write(m.str() + "\n"); !why.empty()) throw std::runtime_error(why);
}

/// What linearize reports: the variant, the steady state, the system's sizes and names, and where its files are.
void print_linearization(std::ostream& out, const Scene& scene, const Model& model, const SteadySpin& steady,
                         double omega, const StateSpace& ss, const std::string& prefix, const std::string& metadata,
                         bool coleman)
{
    const VariantKey key = scene.key();
    out << "variant     " << key.name() << " (" << model.source() << ")\n";
    if (steady.held)
        out << "held        at theta = " << shortest(steady.u.theta) << " rad under gravity, tip_uy "
            << shortest(model.tip(steady.q.data()).uy) << " m"
            << (key.drive == Drive::torque ? ", holding torque " + shortest(steady.u.tau) + " N m" : std::string());
    else
        out << "steady spin " << shortest(omega) << " rad/s";
    if (model.coordinates().count(FieldKind::axial) > 0)
        out << ", axial stretch at the tip " << shortest(model.tip(steady.q.data()).ux1) << " m";
    out << "\nstates      " << ss.states.size() << " (" << joined(ss.states) << ")\n"
        << "input       " << ss.inputs[0] << (key.drive == Drive::torque ? " (N m)" : " (rad/s^2)") << "\n"
        << (coleman ? "frame       fixed: multi-blade coordinates of the " + std::to_string(scene.rotor.blades) +
                          " blades (_coll collective, _cosN and _sinN cyclic, _diff differential) and the hub's own\n"
                    : std::string())
        << "outputs     " << (coleman ? joined(ss.outputs) + " (m, rad)" : std::string("tip_uy (m), theta (rad)"))
        << "\n"
        << "matrices    " << prefix << "-{A,B,C,D}.csv (x' = A x + B v, y = C x + D v, deviations from the "
        << (steady.held ? "equilibrium" : "steady spin") << (scene.control ? "; the closed loop" : "") << ")\n"
        << "numpy       " << prefix << ".npz (A, B, C, D, states, inputs, outputs)\n"
        << "metadata    " << metadata << "\n";
    if (scene.control)
        out << "open loop   " << prefix << "-open-{A,B,C,D}.csv and " << prefix
            << "-open.npz (input tau, N m: the hub without its controller)\n";
}

}  // namespace

void run_linearize(const Scene& scene, double omega, const std::string& prefix, std::ostream& out, Frame frame)
{
    const LinearizeFiles files = linearize_files(scene, prefix);
    const std::string metadata = metadata_path(prefix);
    check_outputs(scene_inputs(scene), [&] {
        std::vector<NamedPath> all = files.outputs;
        all.push_back({metadata, "-o's metadata"});
        return all;
    }());  // before anything is computed
    const auto start = std::chrono::steady_clock::now();
    check_steady(scene, {omega}, frame);
    const LinearizeOutputs outputs = open_linearize_outputs(files, prefix);
    const VariantKey key = scene.key();
    const std::unique_ptr<Model> model = make_scene_model(scene, key);
    const SteadySpin steady = steady_spin(*model, omega, held_angle(scene));
    const bool coleman = multiblade(scene, frame);
    const StateSpace open = coleman ? multiblade_state_space(*model, steady) : state_space(*model, steady);
    const StateSpace ss = scene.control ? closed_loop(open, *scene.control) : open;
    std::vector<const StateSpace*> systems = {&ss};
    if (scene.control) systems.push_back(&open);
    write_state_spaces(outputs.files, files, systems);
    write_linearize_metadata(*outputs.metadata, scene, files, omega, steady, *model, ss, start, coleman);
    print_linearization(out, scene, *model, steady, omega, ss, prefix, metadata, coleman);
}

}  // namespace hubbeam
