// hubbeam bench's CSV (one table of columns: its header and how a row fills each) and the numbers of its messages.
#include "bench_parts.hpp"

#include <cstdio>

#include <hubbeam/output.hpp>
#include <hubbeam/shortest.hpp>

namespace hubbeam {

using namespace bench_parts;

std::string bench_parts::number(double x) { return x < 0.0 ? std::string() : shortest(x); }

namespace {

/// The bench CSV's columns: the one definition of its header and of how a row fills each column.
struct BenchColumn {
    const char* name;
    std::string (*text)(const BenchRow&);
};

const std::vector<BenchColumn>& bench_columns()
{
    static const std::vector<BenchColumn> columns{
        {"method", [](const BenchRow& r) { return to_string(r.key.method); }},
        {"nx", [](const BenchRow& r) { return std::to_string(r.key.nx); }},
        {"ny", [](const BenchRow& r) { return std::to_string(r.key.ny); }},
        {"order", [](const BenchRow& r) { return to_string(r.key.order); }},
        {"stepper", [](const BenchRow& r) { return r.stepper; }},
        {"chosen", [](const BenchRow& r) { return r.chosen; }},
        {"rtol", [](const BenchRow& r) { return shortest(r.rtol); }},
        {"atol", [](const BenchRow& r) { return shortest(r.atol); }},
        {"time_error", [](const BenchRow& r) { return number(r.time_error); }},
        {"disc_error", [](const BenchRow& r) { return number(r.disc_error); }},
        {"jacobi_drift", [](const BenchRow& r) { return number(r.jacobi_drift); }},
        {"wall_median", [](const BenchRow& r) { return number(r.wall_median); }},
        {"wall_min", [](const BenchRow& r) { return number(r.wall_min); }},
        {"wall_max", [](const BenchRow& r) { return number(r.wall_max); }},
        {"repeats", [](const BenchRow& r) { return std::to_string(r.repeats); }},
        {"steps", [](const BenchRow& r) { return std::to_string(r.steps); }},
        {"rhs_evals", [](const BenchRow& r) { return std::to_string(r.rhs_evals); }},
        {"jacobian_evals", [](const BenchRow& r) { return std::to_string(r.jacobian_evals); }},
        {"status", [](const BenchRow& r) { return csv_field(r.status); }},
    };
    return columns;
}

}  // namespace

std::string bench_parts::csv_row(const BenchRow& r)
{
    std::string line;
    for (const BenchColumn& c : bench_columns()) {
        if (&c != &bench_columns().front()) line += ',';
        line += c.text(r);
    }
    return line;
}

std::string bench_parts::seconds_text(double s)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, s < 1.0 ? "%.1f ms" : s < 120.0 ? "%.1f s" : "%.0f min", s < 1.0 ? s * 1e3 : s < 120.0 ? s : s / 60.0);
    return buf;
}

std::string bench_parts::three_digits(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

const char* bench_header()
{
    static const std::string header = [] {
        std::string h;
        for (const BenchColumn& c : bench_columns()) h += (h.empty() ? "" : ",") + std::string(c.name);
        return h;
    }();
    return header.c_str();
}

}  // namespace hubbeam
