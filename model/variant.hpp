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

/// The largest DOF count (each of nx, ny, nz and nt) a method supports, and why (docs/scene.md "Every key").
int max_dof(Method m);
std::string max_dof_reason(Method m);

/// Model order of docs/model.md section 3.
enum class Order { zero, first, full };
/// Prescribed hub rotation theta(t) (no hub equation) or applied hub torque tau(t) (theta is a coordinate).
enum class Drive { prescribed, torque };

/// How the beam's section varies along the span (docs/model.md section 11): uniform, or a linear taper of its
/// width (S and I both linear in x) or of its depth (S linear, I cubic).
enum class Taper { uniform, width, depth };

/// The terms beyond the paper's beam a variant carries (docs/model.md section 11). Each is structure: it adds
/// terms to T, U or the dissipation function D, whose values (Param::m_tip, ...) are read at run time. A scene
/// that does not use a term runs the variant without it.
struct Extras {
    bool tip = false;      // tip body: m_tip at x = L, J_tip turning with the slope there
    bool gravity = false;  // weight along -j of a vertical plane of motion (g)
    bool damping = false;  // Rayleigh damping of the elastic coordinates (alpha, beta)
    Taper taper = Taper::uniform;
    bool pitch = false;  // the section's chord turned out of the plane by the pitch (docs/model.md section 12)
    bool twist = false;  // and by a linear pre-twist, twist x/L
    bool cone = false;   // the beam's axis tilted out of the plane by the precone
    // A tabulated profile (docs/model.md section 11.2): the section's distributions are a table's values, linear
    // between its stations. Only that there is a table is structure; its stations and values are run-time data
    // (Parameters::stations, Parameters::profile) that reach the kernels as the integrals of the section data times
    // the basis (Variant::section_integrals).
    bool tabulated = false;
    // A tabulated blade's section offsets (docs/model.md section 12.5): the centre of mass off the reference axis along
    // the chord. Only that the table has offsets is structure; their values are run-time data (Parameters::offsets).
    bool offsets = false;
    // A hub that translates in the plane of rotation on a support (docs/model.md section 13): coordinates x_h, y_h.
    bool hub = false;
    // The tip body as a rigid body carried by the tip section (docs/model.md section 11.1): its flap and torsion
    // inertias and its centre of mass's offset along the chord, with J_tip about the chord's normal. A tip body
    // without them keeps the tip term's own form (m_tip, J_tip turning with the in-plane slope).
    bool tip_body = false;

    bool profile() const { return tabulated; }
    bool any() const
    {
        return tip || gravity || damping || taper != Taper::uniform || profile() || offsets || pitch || twist || cone ||
               hub || tip_body;
    }
    bool operator==(const Extras&) const = default;
};

/// Why stations x/L are not a profile's (empty if they are): at least 2, 0 first, 1 last, strictly increasing.
std::string stations_problem(const std::vector<double>& x);

/// The grammar of a variant's name, as VariantKey::parse reads it (its messages and hubbeam-gen --help say it).
inline constexpr const char* variant_name_grammar =
    "METHOD_nxN_nyN[_nzN][_ntN]_DRIVE_ORDER[_open][_tip][_gravity][_damped][_width|_depth][_profile]"
    "[_offsets][_pitched][_twisted][_coned][_hub][_tipbody]";

struct VariantKey {
    Method method = Method::amm;
    int nx = 0, ny = 4;  // the coordinate counts of the axial and in-plane fields (coordinates.hpp)
    int nz = 0, nt = 0;  // of the flapwise and twist fields (docs/model.md section 12); 0 0: the planar model
    Order order = Order::first;
    Drive drive = Drive::prescribed;
    SplineBasis spline = SplineBasis::paper;  // BSIM transverse basis; ignored by other methods
    Extras extras;

    /// Number of generalized coordinates, the size of coordinate_layout(*this) (coordinates.hpp), which says
    /// their order.
    int nq() const;

    /// e.g. "bim_nx4_ny4_torque_first", "bsim_nx0_ny4_prescribed_first_open", "amm_nx0_ny4_torque_first_tip_gravity",
    /// "fem_nx0_ny8_nz8_nt2_torque_first_pitched": a C identifier; nz and nt only where nonzero; the extras follow in
    /// the order tip, gravity, damped, width|depth, profile,
    /// offsets, pitched, twisted, coned, hub, tipbody.
    std::string name() const;
    /// Inverse of name(); throws std::invalid_argument.
    static VariantKey parse(std::string_view name);

    /// Empty if the method can take these DOF counts, else why not (e.g. "FEM needs an even ny").
    std::string dof_problem() const;
    /// Why the variant cannot carry the tip body in the blade's axes (empty if it can or does not carry it).
    std::string tip_body_problem() const;

    FieldBasis axial_basis() const { return {method, Field::axial, nx, SplineBasis::open}; }
    FieldBasis transverse_basis() const { return {method, Field::transverse, ny, spline}; }
    FieldBasis flap_basis() const { return {method, Field::transverse, nz, spline}; }
    FieldBasis twist_basis() const { return {method, Field::axial, nt, SplineBasis::open}; }
    /// Whether the beam leaves the plane: a flapwise or twist field, a pitch or a precone.
    bool out_of_plane() const { return nz > 0 || nt > 0 || extras.pitch || extras.twist || extras.cone; }

    /// How many entries of p (model/interface.hpp) its kernels read: the paper's seven, or every Param (and then a
    /// profile's values) for a variant with terms or fields beyond the paper's.
    std::size_t params_read() const;

    bool operator==(const VariantKey&) const = default;
};

/// Every word of enum E, in table order (e.g. words<Method>() = amm, fem, bim, bsim).
template <class E>
std::vector<std::string> words();
template <>
std::vector<std::string> words<Method>();
template <>
std::vector<std::string> words<Order>();
template <>
std::vector<std::string> words<SplineBasis>();
template <>
std::vector<std::string> words<Taper>();

std::string to_string(Method);
std::string to_string(Order);
std::string to_string(Drive);
std::string to_string(SplineBasis);
std::string to_string(Taper);
/// Parsers for the names above; return false for an unknown word.
bool parse(std::string_view, Method&);
bool parse(std::string_view, Order&);
bool parse(std::string_view, Drive&);
bool parse(std::string_view, SplineBasis&);
bool parse(std::string_view, Taper&);

}  // namespace hubbeam
