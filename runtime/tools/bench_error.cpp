// hubbeam bench's error measure: the largest tip-deflection difference between two runs, a row's error against
// the converged solution, and the Pareto front of the work-precision plane.
#include "bench_parts.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include <hubbeam/shortest.hpp>

namespace hubbeam {

using namespace bench_parts;

double bench_parts::max_difference(const std::vector<Row>& a, const std::vector<Row>& b)
{
    double d = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, std::abs(a[i].tip_uy - b[i].tip_uy));
    return d;
}

double bench_parts::overall_error(const BenchRow& r) { return std::max(r.time_error, r.disc_error); }


void bench_parts::print_front(const std::vector<BenchRow>& rows, double resolution, std::ostream& out)
{
    std::vector<WorkPoint> points;
    std::vector<const BenchRow*> ok;
    for (const BenchRow& r : rows)
        if (r.status == "ok") {
            points.push_back({r.wall_median, overall_error(r)});
            ok.push_back(&r);
        }
    if (points.empty()) return;
    out << "Pareto front (errors within " << three_digits(resolution) << " m of each other are ties):\n";
    for (const std::size_t i : pareto_front(points, resolution)) {
        const BenchRow& r = *ok[i];
        out << "  " << r.key.name() << " " << r.stepper << " rtol " << shortest(r.rtol) << ": "
            << seconds_text(r.wall_median) << ", error " << three_digits(overall_error(r)) << " m\n";
    }
}

std::vector<std::size_t> pareto_front(const std::vector<WorkPoint>& points, double resolution)
{
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return points[a].wall != points[b].wall ? points[a].wall < points[b].wall : points[a].error < points[b].error;
    });
    std::vector<std::size_t> front;
    for (const std::size_t i : order)
        // a slower point is on the front only if it beats the front's best error by more than a tie
        if (front.empty() || points[i].error < points[front.back()].error - resolution) front.push_back(i);
    return front;
}

}  // namespace hubbeam
