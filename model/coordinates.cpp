// The order of a variant's generalized coordinates and the look-ups over it.
#include "coordinates.hpp"

#include <stdexcept>

namespace hubbeam {

std::string CoordinateField::name(int k) const
{
    return !basis ? symbol : symbol + std::to_string(k + 1) + suffix;
}

int CoordinateLayout::size() const
{
    return fields.empty() ? 0 : fields.back().end();
}

const CoordinateField* CoordinateLayout::find(FieldKind kind, int beam) const
{
    for (const CoordinateField& f : fields)
        if (f.kind == kind && f.beam == beam) return &f;
    return nullptr;
}

int CoordinateLayout::count(FieldKind kind, int beam) const
{
    const CoordinateField* f = find(kind, beam);
    return f ? f->count : 0;
}

int CoordinateLayout::first(FieldKind kind, int beam) const
{
    if (const CoordinateField* f = find(kind, beam)) return f->first;
    throw std::logic_error("coordinate_layout: the variant has no such field");
}

int CoordinateLayout::first_elastic() const
{
    const CoordinateField* hub = find(FieldKind::hub_angle);
    return hub ? hub->end() : 0;
}

int CoordinateLayout::first_beam() const
{
    for (const CoordinateField& f : fields)
        if (f.basis) return f.first;
    return size();
}

const CoordinateField& CoordinateLayout::field_of(int i) const
{
    for (const CoordinateField& f : fields)
        if (f.holds(i)) return f;
    throw std::out_of_range("coordinate_layout: no coordinate " + std::to_string(i));
}

std::vector<std::string> CoordinateLayout::names() const
{
    std::vector<std::string> n;
    for (const CoordinateField& f : fields)
        for (int k = 0; k < f.count; ++k) n.push_back(f.name(k));
    return n;
}

CoordinateLayout coordinate_layout(const VariantKey& key, int blades)
{
    if (blades < 1) throw std::invalid_argument("coordinate_layout: a rotor has at least one blade");
    CoordinateLayout layout;
    int beam = 0;
    std::string suffix;
    const auto add = [&](FieldKind kind, std::optional<FieldBasis> basis, int count, const char* symbol) {
        layout.fields.push_back({kind, beam, std::move(basis), count, layout.size(), symbol, suffix});
    };
    // The hub angle is a coordinate only under an applied torque; a prescribed theta(t) is an input.
    if (key.drive == Drive::torque) add(FieldKind::hub_angle, std::nullopt, 1, "theta");
    if (key.extras.hub) {
        add(FieldKind::hub_x, std::nullopt, 1, "x_h");
        add(FieldKind::hub_y, std::nullopt, 1, "y_h");
    }
    for (beam = 0; beam < blades; ++beam) {
        suffix = blades > 1 ? "_" + std::to_string(beam + 1) : "";
        add(FieldKind::axial, key.axial_basis(), key.nx, "A");
        add(FieldKind::inplane, key.transverse_basis(), key.ny, "B");
        // The out-of-plane fields are listed only where they hold coordinates: a planar variant's layout is the
        // paper's.
        if (key.nz > 0) add(FieldKind::flap, key.flap_basis(), key.nz, "Z");
        if (key.nt > 0) add(FieldKind::twist, key.twist_basis(), key.nt, "P");
    }
    return layout;
}

}  // namespace hubbeam
