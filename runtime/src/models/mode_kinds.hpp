// The kind of a mode (hub, axial, bending, edge, flap, twist) by the field that holds most of its kinetic energy: the
// one rule the linearization's modes (docs/model.md section 10) and the modal damping's named modes (section 11.5)
// share.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include <hubbeam/model.hpp>

namespace hubbeam {

/// The kinetic energy of a mode's rates, v^H M v, split by the fields of q (model.coordinates().fields, in their
/// order); coordinates[i] is the index in q of rates[i], and cross terms between fields are left out.
std::vector<double> energy_by_field(const Model& model, const Eigen::MatrixXd& M, const std::vector<int>& coordinates,
                                    const Eigen::VectorXcd& rates);

/// The kind of a real, decaying eigenvalue (a mode that does not oscillate: frequency 0, zeta 1), whatever field
/// holds its energy: it has no place on a Campbell diagram and meets no excitation line, and its kind says so
/// rather than pass it for the next bending, edge or flap mode.
inline constexpr const char* overdamped_kind = "overdamped";

/// A mode's kind (the modes CSV's column) when most of its kinetic energy is in a field of this kind: a planar
/// beam's in-plane modes are "bending", a beam that leaves the plane (VariantKey::out_of_plane: flap or twist
/// coordinates, a pitch, a pre-twist or a precone) has "edge" (lead-lag) and "flap" modes.
const char* mode_kind(FieldKind kind, const VariantKey& key);

/// The elastic field that holds the largest part of the kinetic energy of a mode with these rates (of the
/// coordinates R); the in-plane field where the rates hold none.
FieldKind dominant_field(const Model& model, const Eigen::MatrixXd& M, const std::vector<int>& R,
                         const Eigen::VectorXcd& rates);

/// Within each set of repeated eigenvalues (a uniform blade at rest: flap and lead-lag modes of one frequency), the
/// eigen solver's vectors are any basis of the eigenspace; turns them into the basis that splits the in-plane field's
/// kinetic energy from the rest, so that each mode is a pure flap or lead-lag mode and keeps its kind. lambda and rates:
/// the first-order system's eigenvalues and complex rates, or (K, M)'s eigenvalues omega^2 and real shapes.
template <class Values, class Vectors>
void separate_repeated(const Model& model, const Eigen::MatrixXd& M, const std::vector<int>& R, const Values& lambda,
                       Vectors& rates)
{
    const CoordinateLayout& layout = model.coordinates();
    const auto n = static_cast<Eigen::Index>(R.size());
    Eigen::MatrixXd inplane = Eigen::MatrixXd::Zero(n, n);  // M over R, the in-plane field's block only
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
            if (layout.field_of(R[static_cast<std::size_t>(i)]).kind == FieldKind::inplane &&
                layout.field_of(R[static_cast<std::size_t>(j)]).kind == FieldKind::inplane)
                inplane(i, j) = M(R[static_cast<std::size_t>(i)], R[static_cast<std::size_t>(j)]);
    std::vector<bool> done(static_cast<std::size_t>(lambda.size()), false);
    for (Eigen::Index k = 0; k < lambda.size(); ++k) {
        if (done[static_cast<std::size_t>(k)]) continue;
        std::vector<Eigen::Index> group;
        for (Eigen::Index j = k; j < lambda.size(); ++j)
            // Repeated to 1e-6: the eigen solver resolves a repeated pair to about 1e-9 of its value (BIM, Ny 12).
            if (std::abs(lambda[j] - lambda[k]) <= 1e-6 * std::abs(lambda[k])) {
                group.push_back(j);
                done[static_cast<std::size_t>(j)] = true;
            }
        if (group.size() < 2) continue;
        Vectors V(n, static_cast<Eigen::Index>(group.size()));
        for (std::size_t g = 0; g < group.size(); ++g) V.col(static_cast<Eigen::Index>(g)) = rates.col(group[g]);
        const Vectors E = V.adjoint() * inplane * V;
        const Eigen::SelfAdjointEigenSolver<Vectors> split(E);
        const Vectors turned = V * split.eigenvectors();
        for (std::size_t g = 0; g < group.size(); ++g) rates.col(group[g]) = turned.col(static_cast<Eigen::Index>(g));
    }
}

}  // namespace hubbeam
