// The generalized coordinates' layout (model/coordinates.hpp): the order of the fields, their offsets, counts and
// bases, and that q in that order is what both model sources read (a unit coordinate moves the tip as its field
// alone would).
#include <catch2/catch.hpp>

#include <string>
#include <tuple>
#include <vector>

#include <hubbeam/make_model.hpp>
#include "coordinates.hpp"

using namespace hubbeam;

namespace {

/// (kind, first, count) of every field, in order.
std::vector<std::tuple<FieldKind, int, int>> placements(const CoordinateLayout& layout)
{
    std::vector<std::tuple<FieldKind, int, int>> p;
    for (const CoordinateField& f : layout.fields) p.emplace_back(f.kind, f.first, f.count);
    return p;
}

}  // namespace

TEST_CASE("coordinates: q is (theta under torque, A, B) with the key's counts and bases", "[coordinates]")
{
    using P = std::vector<std::tuple<FieldKind, int, int>>;
    const VariantKey torque{.method = Method::bsim, .nx = 4, .ny = 6, .drive = Drive::torque, .spline = SplineBasis::open};
    const CoordinateLayout t = coordinate_layout(torque);
    CHECK(placements(t) == P{{FieldKind::hub_angle, 0, 1}, {FieldKind::axial, 1, 4}, {FieldKind::inplane, 5, 6}});
    CHECK(t.size() == 11);
    CHECK(torque.nq() == 11);
    CHECK(t.first_elastic() == 1);
    CHECK(t.names() == std::vector<std::string>{"theta", "A1", "A2", "A3", "A4", "B1", "B2", "B3", "B4", "B5", "B6"});
    CHECK(t.field_of(0).kind == FieldKind::hub_angle);
    CHECK(t.field_of(4).kind == FieldKind::axial);
    CHECK(t.field_of(5).kind == FieldKind::inplane);
    CHECK_THROWS(t.field_of(11));
    // The hub angle has no shape functions; the beam fields have their method's, the axial one always open-knot.
    CHECK(!t.find(FieldKind::hub_angle)->basis);
    const FieldBasis& a = *t.find(FieldKind::axial)->basis;
    const FieldBasis& b = *t.find(FieldKind::inplane)->basis;
    CHECK((a.method() == Method::bsim && a.field() == Field::axial && a.size() == 4));
    CHECK((b.method() == Method::bsim && b.field() == Field::transverse && b.size() == 6));

    // Prescribed and without axial coordinates: theta is an input, A is listed empty, B starts q.
    const VariantKey prescribed{.method = Method::fem, .nx = 0, .ny = 4, .drive = Drive::prescribed};
    const CoordinateLayout p = coordinate_layout(prescribed);
    CHECK(placements(p) == P{{FieldKind::axial, 0, 0}, {FieldKind::inplane, 0, 4}});
    CHECK(p.find(FieldKind::hub_angle) == nullptr);
    CHECK(p.count(FieldKind::hub_angle) == 0);
    CHECK_THROWS(p.first(FieldKind::hub_angle));
    CHECK(p.first_elastic() == 0);
    CHECK(p.names() == std::vector<std::string>{"B1", "B2", "B3", "B4"});
    CHECK(p.field_of(0).kind == FieldKind::inplane);

    // The other two combinations.
    CHECK(placements(coordinate_layout({.method = Method::amm, .nx = 0, .ny = 4, .drive = Drive::torque})) ==
          P{{FieldKind::hub_angle, 0, 1}, {FieldKind::axial, 1, 0}, {FieldKind::inplane, 1, 4}});
    CHECK(placements(coordinate_layout({.method = Method::bim, .nx = 3, .ny = 5, .drive = Drive::prescribed})) ==
          P{{FieldKind::axial, 0, 3}, {FieldKind::inplane, 3, 5}});
}

TEST_CASE("coordinates: both model sources read q in the layout's order", "[coordinates]")
{
    // A unit coordinate of the axial field stretches the tip (u_x1) and leaves u_y at 0; one of the in-plane field
    // deflects it (u_y) and leaves u_x1 at 0; the hub angle moves neither. Built-in generated variants and the
    // assembled path, both drives.
    const Parameters parameters;
    for (const Drive drive : {Drive::prescribed, Drive::torque})
        for (const ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
            const VariantKey key{.method = Method::amm, .nx = 4, .ny = 4, .drive = drive};  // every mode moves the tip
            const auto model = make_model(key, parameters, source);
            const CoordinateLayout& layout = model->coordinates();
            for (int i = 0; i < model->nq(); ++i) {
                std::vector<double> q(static_cast<std::size_t>(model->nq()), 0.0);
                q[static_cast<std::size_t>(i)] = 1e-3;
                const Tip tip = model->tip(q.data());
                const FieldKind kind = layout.field_of(i).kind;
                INFO(key.name() << " (" << model->source() << ") q[" << i << "] = " << layout.names()[static_cast<std::size_t>(i)]);
                CHECK((tip.ux1 != 0.0) == (kind == FieldKind::axial));
                CHECK((tip.uy != 0.0) == (kind == FieldKind::inplane));
            }
        }
}
