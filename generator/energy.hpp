// Stage "energy": T and U of docs/model.md sections 2-3 as GiNaC expressions in the generalized coordinates,
// rates and physical parameters, for any method (through ShapeIntegrals) and model order.
#pragma once

#include <vector>

#include <ginac/ginac.h>

#include "coordinates.hpp"
#include "integrals.hpp"
#include "poly.hpp"
#include "variant.hpp"

namespace hubbeam::gen {

/// Every symbol a variant's equations can contain, named as in docs/model.md and in the emitted code.
struct Symbols {
    // Physical parameters; m = rho S, EI and ES are formed from p = (L, rho, S, I, E, a, J_oh).
    GiNaC::symbol L{"L"}, m{"m"}, EI{"EI"}, ES{"ES"}, a{"a"}, J_oh{"J_oh"};
    // The extra terms' parameters (docs/model.md section 11), read only by variants that carry the terms.
    GiNaC::symbol m_tip{"m_tip"}, J_tip{"J_tip"}, g{"g"}, alpha{"alpha"}, beta{"beta"}, tip_ratio{"tip_ratio"};
    // A gravity variant's sin(theta) and cos(theta): inputs, or under torque functions of the coordinate theta.
    GiNaC::symbol sin_theta{"sin_theta"}, cos_theta{"cos_theta"};
    // The drive u = (tau, theta_dot, theta_ddot).
    // A tabulated profile's values at station k: mass per length, EI and ES (p[13 + 3k], p[14 + 3k], p[15 + 3k]).
    std::vector<GiNaC::symbol> m_k, EI_k, ES_k;
    GiNaC::symbol tau{"tau"}, theta_dot{"theta_dot"}, theta_ddot{"theta_ddot"};
    GiNaC::symbol theta{"theta"};
    // The beam fields' coordinates and rates (axial A, in-plane B), named by their CoordinateField's symbol.
    std::vector<GiNaC::symbol> A, B, A_dot, B_dot;
    // The variant's coordinates and rates in the order of coordinate_layout(key) (theta under torque, A, B).
    std::vector<GiNaC::symbol> q, qd;

    explicit Symbols(const VariantKey& key);

private:
    /// The coordinates and rates of a beam field of this kind.
    std::vector<GiNaC::symbol>& coordinates(FieldKind kind);
    std::vector<GiNaC::symbol>& rates(FieldKind kind);
};

/// T, U and the dissipation function D (zero without damping) as polynomials in the variables of the reader
/// (the kernels' run-time inputs).
struct Energies {
    Poly T, U, D;
};

/// |r_dot|^2 of docs/model.md section 2 in terms of field symbols, truncated to the model order (section 3).
/// Exposed for tests; the fields are X = a + x, u_x1, u_y, u_x2 and their rates.
struct FieldSymbols {
    GiNaC::symbol X{"X"}, ux1{"u_x1"}, uy{"u_y"}, ux2{"u_x2"}, ux1_dot{"u_x1_dot"}, uy_dot{"u_y_dot"},
        ux2_dot{"u_x2_dot"}, ux1_x{"u_x1_x"}, uy_xx{"u_y_xx"};
    // The slope and its rate (a tip body's rotation), the strain rates (stiffness-proportional damping), and
    // the span coordinate xi = x / L that a taper's section varies with.
    GiNaC::symbol uy_x{"u_y_x"}, uy_x_dot{"u_y_x_dot"}, ux1_x_dot{"u_x1_x_dot"}, uy_xx_dot{"u_y_xx_dot"}, xi{"xi"};
    // A tabulated profile's distributions m(x), EI(x), ES(x): sum_k value_k N_k(xi) over the stations' hat functions.
    GiNaC::symbol m_x{"m_x"}, EI_x{"EI_x"}, ES_x{"ES_x"};
};
GiNaC::ex velocity_squared(Order order, const FieldSymbols& f, const GiNaC::ex& theta_dot);

/// T = 1/2 J_oh theta_dot^2 + 1/2 int m |r_dot|^2 dx and U = 1/2 int (ES u_x1'^2 + EI u_y''^2) dx, over the
/// parameter and variable symbols of read; with the key's extras, the tip body's, gravity's, the taper's and the
/// dissipation function's terms of docs/model.md section 11. without_point_terms: T without the terms of order
/// full beyond order first (|r_dot|^2 of order first), which the points stage adds at quadrature points.
Energies derive_energies(const VariantKey& key, const Symbols& s, const PolyReader& read, bool without_point_terms = false);

}  // namespace hubbeam::gen
