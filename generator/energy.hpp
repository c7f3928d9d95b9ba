// Stage "energy": T and U of docs/model.md sections 2-3 as GiNaC expressions in the generalized coordinates,
// rates and physical parameters, for any method (through ShapeIntegrals) and model order.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <memory>
#include <string_view>
#include <vector>

#include "coordinates.hpp"
#include "integrals.hpp"
#include "interface.hpp"
#include "poly.hpp"
#include "variant.hpp"

namespace hubbeam::gen {

/// A run-time section integral: int_0^1 xi^power d(xi) prod(factors) dxi of distribution d (SectionDistribution),
/// factors sorted and free of the section.
struct SectionKey {
    int distribution = 0, power = 0;
    std::vector<Factor> factors;
    auto operator<=>(const SectionKey&) const = default;
};

/// A run-time input of a term's energies (generator_terms.hpp): its symbol's name, as docs/model.md and the emitted
/// code say it, and the parameter the coefficients kernel makes it from once, as the value itself or its cosine or sine.
struct TermInput {
    enum class Of { value, cos, sin };
    const char* symbol;
    Param param;
    Of of = Of::value;
};

/// Every symbol a variant's equations can contain, named as in docs/model.md and in the emitted code.
struct Symbols {
    // Physical parameters; m = rho S, EI and ES are formed from p = (L, rho, S, I, E, a, J_oh).
    GiNaC::symbol L{"L"}, m{"m"}, EI{"EI"}, ES{"ES"}, a{"a"}, J_oh{"J_oh"};
    // The extra terms' parameters (docs/model.md section 11), read only by variants that carry the terms.
    GiNaC::symbol m_tip{"m_tip"}, J_tip{"J_tip"}, g{"g"}, alpha{"alpha"}, beta{"beta"}, tip_ratio{"tip_ratio"};
    // A gravity variant's sin(theta) and cos(theta): inputs, or under torque functions of the coordinate theta.
    GiNaC::symbol sin_theta{"sin_theta"}, cos_theta{"cos_theta"};
    // The drive u = (tau, theta_dot, theta_ddot).
    GiNaC::symbol tau{"tau"}, theta_dot{"theta_dot"}, theta_ddot{"theta_ddot"};
    GiNaC::symbol theta{"theta"};
    // The beam fields' coordinates and rates (axial A, in-plane B), named by their CoordinateField's symbol.
    std::vector<GiNaC::symbol> A, B, A_dot, B_dot;
    // The variant's coordinates and rates in the order of coordinate_layout(key) (theta under torque, A, B, Z, P).
    std::vector<GiNaC::symbol> q, qd;
    // The flapwise (Z) and twist (P) coordinates and rates (docs/model.md section 12).
    std::vector<GiNaC::symbol> Z, P, Z_dot, P_dot;
    /// The out-of-plane model's parameters: the flapwise and torsional stiffness, the section's mass moments per
    /// length about the chord's normal (j_n) and the chord (j_c), cos and sin of twice the pitch and of the precone,
    /// the pre-twist (tip minus root), gravity's weight along -k.
    struct OutOfPlane {
        GiNaC::symbol EI_flap{"EI_flap"}, GJ{"GJ"}, j_n{"j_n"}, j_c{"j_c"};
        GiNaC::symbol cos_2pitch{"cos_2pitch"}, sin_2pitch{"sin_2pitch"}, twist{"twist"};
        GiNaC::symbol cos_cone{"cos_cone"}, sin_cone{"sin_cone"}, g_axis{"g_axis"};
    };
    /// Created last and only for a variant that leaves the plane (VariantKey::out_of_plane): GiNaC orders terms by
    /// the symbols' serial numbers, so a planar variant's symbols and emitted code stay as they were.
    std::shared_ptr<const OutOfPlane> o;
    /// A moving hub's coordinates and rates (docs/model.md section 13), created after o and only for a variant that
    /// carries it (Extras::hub), for the same reason.
    struct MovingHub {
        GiNaC::symbol x{"x_h"}, y{"y_h"}, x_dot{"x_h_dot"}, y_dot{"y_h_dot"};
    };
    std::shared_ptr<const MovingHub> h;
    /// The inputs of the terms the variant carries (GeneratorTerm::inputs), created after h, term by term in registry
    /// order, for the same reason; input(name) finds one.
    std::vector<std::pair<TermInput, GiNaC::symbol>> inputs;
    /// A profile variant's run-time section integrals (generated_abi.h's SectionIntegral), in the order of their index
    /// n, and their symbols s_n, which the coefficients kernel reads at p[param_count + n]; empty without a profile.
    /// Found by a first pass over the energies (the integrals a variant needs are those its energies meet).
    std::vector<SectionKey> section_keys;
    std::vector<GiNaC::symbol> section;
    std::map<SectionKey, std::size_t> section_index;

    explicit Symbols(const VariantKey& key);

    /// The symbol of a carried term's input; throws std::logic_error for a name no carried term has.
    const GiNaC::symbol& input(std::string_view name) const;

    /// Every parameter symbol the energies can hold: the beam's, the terms', the out-of-plane model's (where it has
    /// one) and the section integrals' (a profile's).
    std::vector<GiNaC::symbol> parameters() const;

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
    // A tabulated profile's distributions m(x), EI(x), ES(x), linear between its stations (run-time data).
    GiNaC::symbol m_x{"m_x"}, EI_x{"EI_x"}, ES_x{"ES_x"};
    // The flapwise deflection u_z with its rate, slope and curvature (and their rates), the twist phi with its rate and
    // derivative (docs/model.md section 12).
    GiNaC::symbol uz{"u_z"}, uz_dot{"u_z_dot"}, uz_x{"u_z_x"}, uz_xx{"u_z_xx"}, uz_xx_dot{"u_z_xx_dot"};
    GiNaC::symbol phi{"phi"}, phi_dot{"phi_dot"}, phi_x{"phi_x"}, phi_x_dot{"phi_x_dot"};
    // A tabulated blade's distributions (docs/model.md section 12.4): EI_flap(x), GJ(x), j_c + j_n, and the deviators
    // (EI - EI_flap)/2 and (j_n - j_c)/2 times cos and sin of twice the tabulated chord angle, each linear between
    // stations (SectionDistribution).
    GiNaC::symbol EI_flap_x{"EI_flap_x"}, GJ_x{"GJ_x"}, j_p_x{"j_p_x"}, EI_cos_x{"EI_cos_x"}, EI_sin_x{"EI_sin_x"},
        j_cos_x{"j_cos_x"}, j_sin_x{"j_sin_x"};
    // A uniform blade's pre-twist: cos 2 twist xi and sin 2 twist xi (section distributions).
    GiNaC::symbol cos_2twist_x{"cos_2twist_x"}, sin_2twist_x{"sin_2twist_x"};
    /// A blade's section offsets (docs/model.md sections 12.5 and 12.6): the flapwise slope's rate, the mass's first
    /// moment along the chord and the axial stiffness times the tension centre's offset, each times cos and sin of the
    /// chord's angle, and the mass times the offset squared, alone and times cos and sin of twice the angle (section
    /// distributions). Made only for a variant with offsets or a tip body in the blade's axes
    /// (which reads the slope's rate), so that the others' symbols and
    /// emitted code stay as they were.
    struct Offsets {
        GiNaC::symbol uz_x_dot{"u_z_x_dot"}, mass_offset_cos_x{"mass_offset_cos_x"},
            mass_offset_sin_x{"mass_offset_sin_x"}, tension_offset_cos_x{"tension_offset_cos_x"},
            tension_offset_sin_x{"tension_offset_sin_x"}, mass_offset2_x{"mass_offset2_x"},
            mass_offset2_cos_x{"mass_offset2_cos_x"}, mass_offset2_sin_x{"mass_offset2_sin_x"};
    };
    std::shared_ptr<const Offsets> offsets;
};

/// The beam's distributions along the span, in x (or xi): mass per length, axial and (edgewise) bending stiffness.
/// Out of the plane (docs/model.md section 12) also the bending stiffness's mean (EI + EI_flap)/2 and its deviator
/// (EI - EI_flap)/2 turned by the chord's angle beta, as its cos 2 beta and sin 2 beta parts; the torsional stiffness
/// GJ; the section's polar mass moment j_c + j_n and its deviator (j_n - j_c)/2 turned alike. 0 in the plane.
struct BeamSection {
    GiNaC::ex mass, axial, bending;
    GiNaC::ex bend_mean = 0, bend_cos = 0, bend_sin = 0, torsion = 0, polar = 0, inertia_cos = 0, inertia_sin = 0;
};

/// The bending energy's density (twice it) for the curvatures y2 = u_y'' and z2 = u_z'' (or their rates, for damping):
/// EI y2^2 in the plane; out of it EI_edge kappa_c^2 + EI_flap kappa_n^2 with the chord turned (docs/model.md 12).
GiNaC::ex bending_density(const VariantKey& key, const BeamSection& b, const GiNaC::ex& y2, const GiNaC::ex& z2);
/// The section's rotary kinetic energy density T_sec (docs/model.md section 12), 0 without a twist field.
GiNaC::ex section_rotation(const VariantKey& key, const Symbols& s, const FieldSymbols& f, const BeamSection& b);

/// The beam's axis tilted by the precone beta_c (docs/model.md section 12): cos and sin of beta_c, and the hub
/// radius a (the root stays at a i). {1, 0, 0}: no precone.
struct Cone {
    GiNaC::ex cos, sin, a;
};
/// A point's position p = a i + (x + u_x) e1 + u_y e2 + u_z e3 in the hub frame (i, j, k), and its rate in that frame.
struct Position {
    GiNaC::ex i, j, k, i_dot, j_dot, k_dot;
};
/// p and its rate in field symbols; order zero has no foreshortening u_x2.
Position position(Order order, const FieldSymbols& f, const Cone& cone = {1, 0, 0});
GiNaC::ex velocity_squared(Order order, const FieldSymbols& f, const GiNaC::ex& theta_dot,
                           const Cone& cone = {1, 0, 0});

/// The precone of a variant's symbols, {1, 0, 0} where it carries none.
Cone cone_of(const VariantKey& key, const Symbols& s);

/// (c, s) = (cos 2 beta, sin 2 beta), or a deviator's parts proportional to them, turned further by the section's
/// pitch: cos 2 (pitch + beta) and sin 2 (pitch + beta); (c, s) itself without a pitch.
std::pair<GiNaC::ex, GiNaC::ex> turned_by_pitch(const VariantKey& key, const Symbols& s, const GiNaC::ex& c,
                                                const GiNaC::ex& sn);
/// cos 2 beta(xi) and sin 2 beta(xi) of a uniform section's chord angle beta = pitch + twist xi (docs/model.md
/// section 12): {1, 0} without either; the pre-twist's part is the section distributions cos 2 twist xi and sin 2
/// twist xi, whose integrals are run-time data.
std::pair<GiNaC::ex, GiNaC::ex> chord_angle(const VariantKey& key, const Symbols& s, const FieldSymbols& f);

/// Whether a variant's kernels read section integrals: a profile's, or a pre-twist's.
bool has_section_integrals(const VariantKey& key);

/// T = 1/2 J_oh theta_dot^2 + 1/2 int m |r_dot|^2 dx and U = 1/2 int (ES u_x1'^2 + EI u_y''^2) dx, over the
/// parameter and variable symbols of read; with the key's extras, the tip body's, gravity's, the taper's and the
/// dissipation function's terms of docs/model.md section 11. without_point_terms: T without the terms of order
/// full beyond order first (|r_dot|^2 of order first), which the points stage adds at quadrature points.
Energies derive_energies(const VariantKey& key, const Symbols& s, const PolyReader& read,
                         bool without_point_terms = false);

}  // namespace hubbeam::gen
