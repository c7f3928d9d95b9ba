// A model's generalized coordinates as data: the list of its fields (the hub angle under torque; each beam's
// axial, in-plane, flapwise and twist fields), each with its basis, count and place in q. coordinate_layout() is the
// one place that decides their order; the generator, the kernels' table, the assembled path and the outputs read it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "basis/basis.hpp"
#include "variant.hpp"

namespace hubbeam {

/// What a field of coordinates describes (docs/model.md sections 2 and 12): the hub angle, and a beam's axial,
/// in-plane (lead-lag, u_y), flapwise (u_z) and twist (phi) fields.
/// A moving hub's translation x_h, y_h (docs/model.md section 13) follows the hub angle.
enum class FieldKind { hub_angle, hub_x, hub_y, axial, inplane, flap, twist };

/// One field of q: its coordinates q[first] .. q[first + count - 1].
struct CoordinateField {
    FieldKind kind;
    int beam = 0;                     // the beam it belongs to (0 for the hub angle)
    std::optional<FieldBasis> basis;  // the shape functions of a beam field; none for the hub angle
    int count = 0;                    // may be 0 (nx = 0): the field is listed but holds no coordinate
    int first = 0;
    std::string symbol;  // the letter of its coordinates in names and code: "theta", "A", "B", "Z", "P"
    std::string suffix;  // a rotor's blade in names: "_2" for blade 2 of several blades; "" for one blade


    int end() const { return first + count; }
    bool holds(int i) const { return i >= first && i < end(); }
    /// The name of its coordinate k (0-based): "theta", "A3", "B2_3" (blade 3 of a rotor).
    std::string name(int k) const;
};

/// The fields in q's order.
struct CoordinateLayout {
    std::vector<CoordinateField> fields;

    /// nq: the coordinates of all fields.
    int size() const;
    /// The field of this kind and beam, or nullptr when the variant has none (the hub angle of a prescribed drive).
    const CoordinateField* find(FieldKind kind, int beam = 0) const;
    /// Its count, 0 when absent.
    int count(FieldKind kind, int beam = 0) const;
    /// Its first index; throws std::logic_error when absent.
    int first(FieldKind kind, int beam = 0) const;
    /// The first coordinate that is not the hub angle's (the elastic coordinates run from here to size()).
    int first_elastic() const;
    /// The first coordinate of a beam's field: after the hub's angle and a moving hub's translation.
    int first_beam() const;
    /// The field that holds coordinate i.
    const CoordinateField& field_of(int i) const;
    /// Every coordinate's name in q's order ("theta", "A1", ..., "B1", ...).
    std::vector<std::string> names() const;
};

/// The layout of a variant's q: the single place where the order of fields is decided. A rotor of `blades` blades
/// (docs/model.md section 13) lists the hub angle once, then each blade's fields in turn (beam b - 1 for blade b,
/// their names suffixed "_b"); one blade is the variant's own layout.
CoordinateLayout coordinate_layout(const VariantKey& key, int blades = 1);

}  // namespace hubbeam
