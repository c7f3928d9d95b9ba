// FieldRecorder: BeamFields' values at a row's state, written through the one writer (CsvWriter).
#include "io/field_recorder.hpp"

#include <algorithm>

#include "io/output.hpp"
#include "text/shortest.hpp"

namespace hubbeam {

FieldRecorder::FieldRecorder(const VariantKey& key, const Parameters& p, std::vector<double> times, int points,
                             const std::string& path)
    : coordinates_(coordinate_layout(key)), fields_(key, p), times_(std::move(times))
{
    std::sort(times_.begin(), times_.end());
    for (int i = 0; i < points; ++i) xs_.push_back(p.L * i / (points - 1));
    // Both sides of each piece boundary, 1e-9 L apart: the moment's jump at FEM's nodes shows as a step.
    for (double b : fields_.piece_boundaries()) {
        xs_.push_back(b * (1.0 - 1e-9));
        xs_.push_back(b * (1.0 + 1e-9));
    }
    std::sort(xs_.begin(), xs_.end());
    xs_.erase(std::unique(xs_.begin(), xs_.end()), xs_.end());
    csv_ = std::make_unique<CsvWriter>(path, header());
}

FieldRecorder::~FieldRecorder() = default;

void FieldRecorder::state(double t, const double* q)
{
    if (next_ >= times_.size() || t < times_[next_] * (1.0 - 1e-12)) return;
    while (next_ < times_.size() && times_[next_] <= t * (1.0 + 1e-12)) ++next_;  // one record for times a row covers
    const CoordinateField& axial = *coordinates_.find(FieldKind::axial);
    const CoordinateField& inplane = *coordinates_.find(FieldKind::inplane);
    const double* A = axial.count > 0 ? q + axial.first : nullptr;
    const double* B = q + inplane.first;
    const std::vector<double> ux = fields_.ux(A, B, xs_);
    for (std::size_t i = 0; i < xs_.size(); ++i) {
        const double x = xs_[i];
        std::string line;
        for (double v : {t, x, fields_.uy(B, x), ux[i], fields_.slope(B, x), fields_.curvature(B, x),
                         fields_.bending_moment(B, x), fields_.axial_force(A, x)}) {
            if (!line.empty()) line += ',';
            append_shortest(line, v);
        }
        csv_->write_line(line);
    }
}

bool FieldRecorder::finish() { return csv_->finish(); }

const std::string& FieldRecorder::error() const { return csv_->error(); }

const std::string& FieldRecorder::path() const { return csv_->path(); }

}  // namespace hubbeam
