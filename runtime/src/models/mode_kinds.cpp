// The kind of a mode by the field that holds most of its kinetic energy (mode_kinds.hpp).
#include "models/mode_kinds.hpp"

#include <complex>

namespace hubbeam {

std::vector<double> energy_by_field(const Model& model, const Eigen::MatrixXd& M, const std::vector<int>& coordinates,
                                    const Eigen::VectorXcd& rates)
{
    const CoordinateLayout& layout = model.coordinates();
    // Each coordinate's field looked up once, not once per pair (a tenth of a Campbell table's time at Ny = 64).
    std::vector<std::size_t> field(coordinates.size());
    for (std::size_t i = 0; i < coordinates.size(); ++i)
        field[i] = static_cast<std::size_t>(&layout.field_of(coordinates[i]) - layout.fields.data());
    std::vector<double> energy(layout.fields.size(), 0.0);
    for (std::size_t i = 0; i < coordinates.size(); ++i) {
        const std::complex<double> ri = rates(static_cast<Eigen::Index>(i));
        for (std::size_t j = 0; j < coordinates.size(); ++j) {
            if (field[i] != field[j]) continue;
            const std::complex<double> rj = rates(static_cast<Eigen::Index>(j));
            // Re(conj(ri) M rj), written out: std::complex's product checks for NaN at every call.
            energy[field[i]] += M(coordinates[i], coordinates[j]) * (ri.real() * rj.real() + ri.imag() * rj.imag());
        }
    }
    return energy;
}





const char* mode_kind(FieldKind kind, const VariantKey& key)
{
    switch (kind) {
        case FieldKind::hub_angle:
            return "hub";
        case FieldKind::hub_x:
            return "hub x";
        case FieldKind::hub_y:
            return "hub y";
        case FieldKind::axial:
            return "axial";
        case FieldKind::flap:
            return "flap";
        case FieldKind::twist:
            return "twist";
        case FieldKind::inplane:
            break;
    }
    return key.out_of_plane() ? "edge" : "bending";
}



FieldKind dominant_field(const Model& model, const Eigen::MatrixXd& M, const std::vector<int>& R,
                         const Eigen::VectorXcd& rates)
{
    const std::vector<double> e = energy_by_field(model, M, R, rates);
    FieldKind dominant = FieldKind::inplane;
    double largest = -1.0;
    for (std::size_t f = 0; f < e.size(); ++f) {
        const FieldKind kind = model.coordinates().fields[f].kind;
        // Ties (a planar mode with no axial energy) go to the in-plane field, as before the axial one.
        if (kind != FieldKind::hub_angle && (e[f] > largest || (e[f] == largest && kind == FieldKind::inplane))) {
            largest = e[f];
            dominant = kind;
        }
    }
    return dominant;
}

}  // namespace hubbeam
