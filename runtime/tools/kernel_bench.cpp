// hubbeam kernels: times FirstOrderSystem::rhs and ::jacobian at one fixed state, per variant and model source.
#include "kernel_bench.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <hubbeam/make_model.hpp>
#include <hubbeam/motion.hpp>
#include <hubbeam/option_lists.hpp>
#include <hubbeam/output.hpp>
#include <memory>
#include <ostream>
#include <sstream>
#include <string_view>

#include "dynamics/integrate.hpp"

namespace hubbeam {

namespace {

using Clock = std::chrono::steady_clock;

// A sample long enough that steady_clock's resolution and the loop overhead vanish, short enough that the
// default grid (about 160 timings of 7 samples) finishes in well under a minute.
constexpr double sample_seconds = 0.020;
// Above this a call is timed alone, a few times: the finite-difference Jacobian of the assembled path at
// nq ~ 65 is thousands of right-hand sides, and 7 samples of 20 ms would not hold it anyway.
constexpr double slow_call_seconds = 0.010;
constexpr int capped_samples = 3;
// Every timed result ends up here, so the compiler must make every call (the outputs are read).
volatile double sink = 0.0;

[[noreturn]] void bad(const std::string& option, const std::string& expected, const std::string& got)
{
    bad_option<KernelOptionError>(option, expected, got);
}

/// The drive of a benchmark row, at an instant mid-way through it: the spin-up still accelerating (theta_ddot
/// != 0, so the prescribed forces have every term), the torque pulse still on.
struct BenchDrive {
    Motion motion;
    double t;
};

BenchDrive bench_drive(Drive d)
{
    BenchDrive b;
    if (d == Drive::prescribed) {
        b.motion.kind = Motion::Kind::spin_up;
        b.motion.omega0 = 4.0;
        b.motion.spin_time = 15.0;
        b.t = 6.3;
    } else {
        b.motion.kind = Motion::Kind::torque;
        b.motion.tau0 = 10.0;
        b.motion.torque_time = 10.0;
        b.t = 3.1;
    }
    return b;
}

/// y = (q, qd) of a deflected, moving beam. The values do not change the operation count; they only have to
/// be a valid state (M positive definite, finite results) of the size a real run sees.
std::vector<double> bench_state(const VariantKey& key)
{
    const CoordinateLayout layout = coordinate_layout(key);
    const int n = layout.size();
    std::vector<double> y(2 * static_cast<std::size_t>(n));
    for (const CoordinateField& f : layout.fields) {
        // The hub turned and turning; the axial field stiff, its rates small; a bending field deflected.
        const double size = f.kind == FieldKind::hub_angle ? 1.0 : f.kind == FieldKind::axial ? 1e-4 : 0.1;
        const double rate = f.kind == FieldKind::hub_angle ? 1.0 : f.kind == FieldKind::axial ? 1e-3 : 1.0;
        for (int i = 0; i < f.count; ++i) {
            const double fall = f.kind == FieldKind::hub_angle ? 1.0 : i + 1.0;
            y[static_cast<std::size_t>(f.first + i)] = size / fall;
            y[static_cast<std::size_t>(n + f.first + i)] = rate / fall;
        }
    }
    return y;
}

/// Seconds for reps calls; call() returns one number of each result, summed into the sink.
template <class Call>
double seconds_for(Call& call, long reps)
{
    double acc = 0.0;
    const Clock::time_point start = Clock::now();
    for (long i = 0; i < reps; ++i) acc += call();
    const Clock::time_point stop = Clock::now();
    sink = sink + acc;
    return std::chrono::duration<double>(stop - start).count();
}

/// Calibrates the repetitions to ~sample_seconds per sample, then the median and range of samples samples.
template <class Call>
CallTiming time_calls(Call call, int samples)
{
    CallTiming t;
    seconds_for(call, 1);  // warm-up: caches, first-touch pages, the one-time factorization of a constant M
    const double one = seconds_for(call, 1);
    if (one > slow_call_seconds) {
        t.capped = true;
        t.repetitions = 1;
        samples = std::min(samples, capped_samples);
    } else {
        long reps = 1;
        double s = 0.0;
        while ((s = seconds_for(call, reps)) < sample_seconds / 8) reps *= 2;  // at least 2.5 ms to scale from
        t.repetitions = std::max(1L, std::lround(static_cast<double>(reps) * sample_seconds / s));
    }
    std::vector<double> ns(static_cast<std::size_t>(samples));
    for (double& x : ns) x = seconds_for(call, t.repetitions) / static_cast<double>(t.repetitions) * 1e9;
    std::sort(ns.begin(), ns.end());
    const std::size_t m = ns.size() / 2;
    t.median = ns.size() % 2 ? ns[m] : 0.5 * (ns[m - 1] + ns[m]);
    t.min = ns.front();
    t.max = ns.back();
    t.samples = samples;
    return t;
}

/// Times the model of key from source into row; false when the build has no generated model of key.
bool measure(const VariantKey& key, ModelSource source, int samples, KernelBenchRow& row)
{
    const Parameters p;  // the paper's beam (docs/model.md section 6)
    std::unique_ptr<Model> model;
    try {
        model = make_model(key, p, source);
    } catch (const std::invalid_argument&) {
        if (source == ModelSource::generated) return false;  // not generated into this build: the "-" cells
        throw;
    }
    const BenchDrive d = bench_drive(key.drive);
    FirstOrderSystem system(*model, d.motion);
    const std::vector<double> y = bench_state(key);
    const int m = system.size();
    std::vector<double> dydt(static_cast<std::size_t>(m)), dfdy(static_cast<std::size_t>(m) * m), dfdt(dydt);
    row.key = key;
    row.source = model->source();
    row.exact_jacobian = model->jacobian() != nullptr;
    // A model that cannot evaluate here (e.g. M numerically indefinite) would time an early return: report it.
    if (system.rhs(d.t, y.data(), dydt.data()) != 0 || system.jacobian(d.t, y.data(), dfdy.data(), dfdt.data()) != 0) {
        row.failure = "M is not positive definite (Cholesky fails) or a result is not finite at the benchmark state";
        return true;
    }
    // Two alternating times, so that every call evaluates the drive as a Runge-Kutta stage does (the system
    // remembers the drive of the last t, which serves a multistep corrector's repeated calls).
    bool other = false;
    const auto next_t = [&] { return (other = !other) ? d.t + 1e-3 : d.t; };
    row.rhs = time_calls(
        [&] {
            system.rhs(next_t(), y.data(), dydt.data());
            return dydt[m - 1];
        },
        samples);
    row.jacobian = time_calls(
        [&] {
            system.jacobian(next_t(), y.data(), dfdy.data(), dfdt.data());
            return dfdy[static_cast<std::size_t>(m) * m - 1];
        },
        samples);
    return true;
}

/// ns for the table: integers from 100 up, one decimal below (the fast generated right-hand sides).
std::string ns_text(double ns)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, ns >= 100.0 ? "%.0f" : "%.1f", ns);
    return buf;
}

std::string spread_text(const CallTiming& t)
{
    return ns_text(t.min) + "-" + ns_text(t.max) + (t.capped ? " *" : "");
}

std::string pad_left(const std::string& s, std::size_t w)
{
    return std::string(w > s.size() ? w - s.size() : 0, ' ') + s;
}
std::string pad_right(const std::string& s, std::size_t w)
{
    return s + std::string(w > s.size() ? w - s.size() : 0, ' ');
}

// Fixed widths, so that rows can be printed as they are measured: a long grid shows its progress.
constexpr std::size_t w_ns = 10, w_spread = 20;

/// The table's two header lines.
void print_header(std::ostream& out)
{
    out << pad_right("method", 7) << pad_right("drive", 11) << pad_right("order", 6) << pad_left("nx", 4) << pad_left("ny", 4)
        << pad_left("nq", 4) << "  " << pad_left("rhs gen", w_ns) << "  " << pad_right("(min-max)", w_spread)
        << pad_left("rhs asm", w_ns) << "  " << pad_right("(min-max)", w_spread) << pad_left("asm/gen", 8) << "  "
        << pad_left("jac gen", w_ns) << "  " << pad_right("(min-max)", w_spread) << pad_left("jac asm", w_ns) << "  "
        << "(min-max)\n";
}

/// One table line per variant: the generated row (or "-") beside the assembled one.
void print_line(std::ostream& out, const VariantKey& key, const KernelBenchRow* gen, const KernelBenchRow* as)
{
    const auto cells = [&](const KernelBenchRow* r, const CallTiming KernelBenchRow::*which) {
        if (r == nullptr) return pad_left("-", w_ns) + "  " + pad_right("", w_spread);
        if (!r->failure.empty()) return pad_left("fails", w_ns) + "  " + pad_right("", w_spread);
        return pad_left(ns_text((r->*which).median), w_ns) + "  " + pad_right(spread_text(r->*which), w_spread);
    };
    char ratio[32] = "-";
    if (gen != nullptr && gen->failure.empty() && as != nullptr && as->failure.empty())
        std::snprintf(ratio, sizeof ratio, "%.2f", as->rhs.median / gen->rhs.median);
    std::ostringstream line;
    line << pad_right(to_string(key.method), 7) << pad_right(to_string(key.drive), 11) << pad_right(to_string(key.order), 6)
         << pad_left(std::to_string(key.nx), 4) << pad_left(std::to_string(key.ny), 4)
         << pad_left(std::to_string(key.nq()), 4) << "  " << cells(gen, &KernelBenchRow::rhs)
         << cells(as, &KernelBenchRow::rhs) << pad_left(ratio, 8) << "  " << cells(gen, &KernelBenchRow::jacobian)
         << cells(as, &KernelBenchRow::jacobian);
    std::string text = line.str();
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << "\n" << std::flush;
}

void write_csv_row(CsvWriter& csv, const KernelBenchRow& r)
{
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%d,%d,%d,%s,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f", to_string(r.key.method).c_str(),
                  to_string(r.key.drive).c_str(), to_string(r.key.order).c_str(), r.key.nx, r.key.ny, r.key.nq(), r.source.c_str(), r.rhs.median,
                  r.rhs.min, r.rhs.max, r.jacobian.median, r.jacobian.min, r.jacobian.max);
    csv.write_line(buf);
}

}  // namespace

KernelBenchOptions parse_kernel_options(const KernelArgs& args)
{
    KernelBenchOptions o;
    o.ny = parse_dof_list<KernelOptionError>("--ny", args.ny, 1);
    o.methods = parse_method_list<KernelOptionError>("--methods", args.methods);
    for (const std::string& s : split_list(args.orders)) {
        Order v{};
        if (!parse(s, v)) bad("--orders", "a comma-separated list of " + joined(words<Order>()), s);
        add_unique(o.orders, v);
    }
    for (const std::string& s : split_list(args.drives)) {
        Drive v{};
        if (!parse(s, v)) bad("--drives", "a comma-separated list of prescribed, torque", s);
        add_unique(o.drives, v);
    }
    if (args.nx_equal_ny)
        o.nx = {nx_equal_ny};
    else if (args.nx0)
        o.nx = {0};
    else
        for (const std::string& s : split_list(args.nx))
            add_unique(o.nx, s == "ny" ? nx_equal_ny : parse_dof_list<KernelOptionError>("--nx", s, 0, "ny").front());
    if (!parse_int(args.samples, 1, 1000, o.samples)) bad("--samples", "an integer from 1 to 1000", args.samples);
    o.output = args.output;
    return o;
}

namespace {

/// What the grid's loop gathers besides the rows, for the notes under the table.
struct KernelNotes {
    std::vector<std::string> skipped, failed;
    bool any_capped = false;
};

/// Measures key generated and assembled (the assembled path has no order full), prints its line, and keeps the rows
/// that measured.
void bench_variant(const VariantKey& key, const KernelBenchOptions& options, std::ostream& out, CsvWriter* csv,
                   std::vector<KernelBenchRow>& rows, KernelNotes& notes)
{
    KernelBenchRow gen, as;
    const bool has_gen = measure(key, ModelSource::generated, options.samples, gen);
    const bool has_asm = key.order != Order::full && measure(key, ModelSource::assembled, options.samples, as);
    print_line(out, key, has_gen ? &gen : nullptr, has_asm ? &as : nullptr);
    for (const KernelBenchRow* r : {has_gen ? &gen : nullptr, has_asm ? &as : nullptr}) {
        if (r == nullptr) continue;
        if (!r->failure.empty()) {
            notes.failed.push_back(key.name() + " (" + r->source + "): " + r->failure);
            continue;
        }
        notes.any_capped = notes.any_capped || r->rhs.capped || r->jacobian.capped;
        if (csv != nullptr) write_csv_row(*csv, *r);
        rows.push_back(*r);
    }
}

}  // namespace

std::vector<KernelBenchRow> run_kernel_bench(const KernelBenchOptions& options, std::ostream& out)
{
    // The CSV is created first so that a bad path costs nothing; it replaces the target when the table is complete.
    std::unique_ptr<CsvWriter> csv;
    if (!options.output.empty()) {
        try {
            csv = std::make_unique<CsvWriter>(options.output,
                                              "method,drive,order,nx,ny,nq,source,ns_rhs,ns_rhs_min,ns_rhs_max,ns_jac,"
                                              "ns_jac_min,ns_jac_max");
        } catch (const std::runtime_error& e) {
            throw KernelOptionError(std::string("-o: ") + e.what());
        }
    }
    out << "ns per call: median of " << options.samples << " samples of ~" << sample_seconds * 1e3
        << " ms each, (min-max) over the samples.\n"
           "rhs = FirstOrderSystem::rhs (M factored once when it is constant, as in a run); jac = "
           "FirstOrderSystem::jacobian\n(generated: the exact derivative kernels; assembled: the exact derivatives of its "
           "blocks).\n\n";
    print_header(out);

    std::vector<KernelBenchRow> rows;
    KernelNotes notes;
    for (const Order order : options.orders)
        for (const Method method : options.methods)
            for (const Drive drive : options.drives)
                for (const int ny : options.ny) {
                    std::vector<int> nxs;
                    for (const int nx : options.nx) add_unique(nxs, nx == nx_equal_ny ? ny : nx);
                    for (const int nx : nxs) {
                        const VariantKey key{.method = method, .nx = nx, .ny = ny, .order = order, .drive = drive, .extras = {}};
                        if (const std::string why = key.dof_problem(); !why.empty())
                            notes.skipped.push_back(key.name() + ": " + why);
                        else
                            bench_variant(key, options, out, csv.get(), rows, notes);
                    }
                }

    out << "\nasm/gen = assembled rhs / generated rhs; \"-\": no such model (no compiler for generated code; no "
           "assembled order full).\n";
    if (notes.any_capped)
        out << "* a single call took over " << slow_call_seconds * 1e3 << " ms: timed one call at a time, at most "
            << capped_samples << " samples.\n";
    for (const std::string& s : notes.skipped) out << "skipped " << s << "\n";
    for (const std::string& s : notes.failed) out << "fails " << s << "\n";
    if (csv) {
        if (!csv->finish()) throw std::runtime_error(csv->error());
        out << "CSV: " << options.output << "\n";
    }
    return rows;
}

}  // namespace hubbeam
