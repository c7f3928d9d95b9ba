// VariantKey: what a model is specialised on (method, DOF counts, order, drive, spline basis), its
// canonical name (which names generated kernels), the DOF counts each method can take, and the words of
// its enums.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "basis/basis.hpp"
#include "words.hpp"

namespace hubbeam {

/// The largest DOF count (each of nx and ny) a method supports, and why (docs/scene.md "Every key").
int max_dof(Method m);
std::string max_dof_reason(Method m);

/// Model order of docs/model.md section 3.
enum class Order { zero, first, full };
/// Prescribed hub rotation theta(t) (no hub equation) or applied hub torque tau(t) (theta is a coordinate).
enum class Drive { prescribed, torque };

struct VariantKey {
    Method method = Method::amm;
    int nx = 0, ny = 4;
    Order order = Order::first;
    Drive drive = Drive::prescribed;
    SplineBasis spline = SplineBasis::paper;  // BSIM transverse basis; ignored by other methods

    /// Number of generalized coordinates: theta (torque only), A (nx), B (ny).
    int nq() const { return (drive == Drive::torque ? 1 : 0) + nx + ny; }
    /// Index of A_1 and B_1 in q.
    int first_a() const { return drive == Drive::torque ? 1 : 0; }
    int first_b() const { return first_a() + nx; }

    /// e.g. "bim_nx4_ny4_torque_first", "bsim_nx0_ny4_prescribed_first_open": a C identifier.
    std::string name() const;
    /// Inverse of name(); throws std::invalid_argument.
    static VariantKey parse(std::string_view name);

    /// Empty if the method can take these DOF counts, else why not (e.g. "FEM needs an even ny").
    std::string dof_problem() const;

    FieldBasis axial_basis() const { return {method, Field::axial, nx, SplineBasis::open}; }
    FieldBasis transverse_basis() const { return {method, Field::transverse, ny, spline}; }

    bool operator==(const VariantKey&) const = default;
};

/// Every word of enum E, in table order (e.g. words<Method>() = amm, fem, bim, bsim).
template <class E>
std::vector<std::string> words();
template <> std::vector<std::string> words<Method>();
template <> std::vector<std::string> words<Order>();
template <> std::vector<std::string> words<SplineBasis>();

std::string to_string(Method);
std::string to_string(Order);
std::string to_string(Drive);
std::string to_string(SplineBasis);
/// Parsers for the names above; return false for an unknown word.
bool parse(std::string_view, Method&);
bool parse(std::string_view, Order&);
bool parse(std::string_view, Drive&);
bool parse(std::string_view, SplineBasis&);

}  // namespace hubbeam
