// FieldRecorder: BeamFields' values at a row's state, written through the one writer (CsvWriter).
#include <hubbeam/field_recorder.hpp>

#include <algorithm>
#include <cmath>
#include <hubbeam/output.hpp>
#include <hubbeam/shortest.hpp>

#include "profile.hpp"

namespace hubbeam {

FieldRecorder::FieldRecorder(const VariantKey& key, const Parameters& p, std::vector<double> times, int points,
                             const std::string& path, const Rotor& rotor)
    : coordinates_(coordinate_layout(key, rotor.blades)),
      fields_(key, p),
      out_of_plane_(key.out_of_plane()),
      foreshortened_(key.order != Order::zero),
      stations_(p.stations),
      p_(p),
      blades_(rotor.blades),
      times_(std::move(times))
{
    for (int b = 0; b < blades_; ++b) pitches_.push_back(rotor.blade(p, b).pitch);
    std::sort(times_.begin(), times_.end());
    for (int i = 0; i < points; ++i) xs_.push_back(p.L * i / (points - 1));
    // Both sides of each piece boundary, 1e-9 L apart: the moment's jump at FEM's nodes shows as a step.
    for (double b : fields_.piece_boundaries()) {
        xs_.push_back(b * (1.0 - 1e-9));
        xs_.push_back(b * (1.0 + 1e-9));
    }
    std::sort(xs_.begin(), xs_.end());
    xs_.erase(std::unique(xs_.begin(), xs_.end()), xs_.end());
    csv_ = std::make_unique<CsvWriter>(path, blades_ > 1       ? header_of_rotor(out_of_plane_)
                                             : out_of_plane_ ? header_out_of_plane()
                                                             : header());
}

FieldRecorder::~FieldRecorder() = default;

void FieldRecorder::state(double t, const double* q)
{
    if (next_ >= times_.size() || t < times_[next_] * (1.0 - 1e-12)) return;
    while (next_ < times_.size() && times_[next_] <= t * (1.0 + 1e-12)) ++next_;  // one record for times a row covers
    for (int b = 0; b < blades_; ++b) write_blade(t, q, b);
}

void FieldRecorder::write_blade(double t, const double* q, int blade)
{
    const CoordinateField& axial = *coordinates_.find(FieldKind::axial, blade);
    const CoordinateField& inplane = *coordinates_.find(FieldKind::inplane, blade);
    const double* A = axial.count > 0 ? q + axial.first : nullptr;
    const double* B = q + inplane.first;
    std::vector<double> ux = fields_.ux(A, B, xs_);
    const CoordinateField* flap = coordinates_.find(FieldKind::flap, blade);
    if (flap != nullptr && foreshortened_) {  // both slopes shorten the beam (not in order zero, the linear model)
        const std::vector<double> shortening = fields_.foreshortening(FieldKind::flap, q + flap->first, xs_);
        for (std::size_t i = 0; i < xs_.size(); ++i) ux[i] += shortening[i];
    }
    for (std::size_t i = 0; i < xs_.size(); ++i) {
        const double x = xs_[i], curvature = fields_.curvature(B, x);
        const BladeValues values = out_of_plane_ ? blade_at(q, blade, x, curvature) : BladeValues{};
        const double moment = out_of_plane_ ? values.edge_moment : fields_.bending_moment(B, x);
        std::string line;
        append_shortest(line, t);
        if (blades_ > 1) line += "," + std::to_string(blade + 1);
        for (double v : {x, fields_.uy(B, x), ux[i], fields_.slope(B, x), curvature, moment, fields_.axial_force(A, x)}) {
            line += ',';
            append_shortest(line, v);
        }
        if (out_of_plane_)
            for (double v : {values.uz, values.phi, values.flap_moment, values.torque}) {
                line += ',';
                append_shortest(line, v);
            }
        csv_->write_line(line);
    }
}

FieldRecorder::BladeValues FieldRecorder::blade_at(const double* q, int blade, double x, double y2) const
{
    const CoordinateField* flap = coordinates_.find(FieldKind::flap, blade);
    const CoordinateField* twist = coordinates_.find(FieldKind::twist, blade);
    const double* Z = flap != nullptr ? q + flap->first : nullptr;
    const double* P = twist != nullptr ? q + twist->first : nullptr;
    const double z2 = fields_.field(FieldKind::flap, Z, x, 2);
    // The section at x: uniform, or a profile's columns each linear between stations (docs/model.md section 12.4).
    const double xi = x / p_.L;
    // A taper's edgewise and flapwise ratios (docs/model.md section 12).
    const double i_e = fields_.moment_ratio(x), i_f = fields_.flap_moment_ratio(x);
    const auto section = [&](ProfileValue v, double uniform) {
        return stations_.empty() ? uniform : profile_value(stations_, p_.profile, v, xi);
    };
    const double beta = pitches_[static_cast<std::size_t>(blade)] + section(ProfileValue::twist, p_.twist * xi);
    const double EI_edge = section(ProfileValue::EI, p_.E * p_.I * i_e),
                 EI_flap = section(ProfileValue::EI_flap, p_.E * p_.I_flap * i_f);
    BladeValues b;
    b.edge_moment = EI_edge * (std::cos(beta) * y2 + std::sin(beta) * z2);   // EI_edge kappa_c
    b.flap_moment = EI_flap * (-std::sin(beta) * y2 + std::cos(beta) * z2);  // EI_flap kappa_n
    b.uz = fields_.field(FieldKind::flap, Z, x);
    b.phi = fields_.field(FieldKind::twist, P, x);
    b.torque = section(ProfileValue::GJ, p_.G * p_.J_t * i_f) * fields_.field(FieldKind::twist, P, x, 1);
    return b;
}

bool FieldRecorder::finish()
{
    return csv_->finish();
}

const std::string& FieldRecorder::error() const
{
    return csv_->error();
}

const std::string& FieldRecorder::path() const
{
    return csv_->path();
}

}  // namespace hubbeam
