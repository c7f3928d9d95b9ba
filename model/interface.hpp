// The numbers every variant's kernels take at run time, defined once: the packed physical parameters p and
// the drive u. The generator prints its reads and comments from these tables, the runtime packs from them.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace hubbeam {

/// Index of each physical parameter in the packed vector p (SI units; docs/model.md section 1).
/// The paper's seven come first; the rest (tip body, gravity, Rayleigh damping, taper; docs/model.md section 11)
/// are read only by the variants that carry those terms, so the paper's variants read p[0..6] only. The out-of-plane
/// model's (docs/model.md section 12) follow: the flapwise second moment, the shear modulus and torsion constant, the
/// pitch and pre-twist (tip minus root) of the section, the precone, and gravity's weight along the spin axis. Then a
/// moving hub's (docs/model.md section 13), and last the tip body's in the blade's axes at the tip (docs/model.md section
/// 11.1): its flap and torsion inertias about its centre of mass and that centre's offset along the chord.
enum class Param : std::size_t {
    L,
    rho,
    S,
    I,
    E,
    a,
    J_oh,
    m_tip,
    J_tip,
    g,
    alpha,
    beta,
    tip_ratio,
    I_flap,
    G,
    J_t,
    pitch,
    twist,
    precone,
    g_axis,
    m_hub,
    k_x,
    k_y,
    c_x,
    c_y,
    J_tip_flap,
    J_tip_twist,
    tip_offset
};
inline constexpr std::size_t param_count = 28;
/// A tabulated profile's values at each station (docs/model.md sections 11.2 and 12.4): a planar beam's m, EI, ES;
/// a blade's also its flapwise and torsional stiffness, the chord's angle (pre-twist, added to the pitch), the mass
/// moments per length about the section's principal inertia axes (j_c about the one nearer the chord, j_n about its
/// normal) and the angle of those axes (the chord's angle where a table gives none).
enum class ProfileValue : std::size_t { m, EI, ES, EI_flap, GJ, twist, j_c, j_n, inertia_twist };
inline constexpr std::size_t max_profile_value_count = 9;
inline constexpr std::array<const char*, max_profile_value_count> profile_value_names = {
    "m", "EI", "ES", "EI_flap", "GJ", "twist", "j_c", "j_n", "inertia_twist"};
/// The values per station of a variant's profile: the first 3 in the plane, all 9 for a beam that leaves it.
constexpr std::size_t profile_value_count(bool out_of_plane)
{
    return out_of_plane ? max_profile_value_count : 3;
}
/// The distributions along the span a profile variant's kernels integrate (docs/model.md sections 11.2 and 12.4), each
/// linear between the table's stations: mass per length, EI, ES; out of the plane EI_flap, GJ, the polar mass moment
/// j_c + j_n, and the deviators (EI - EI_flap)/2 and (j_n - j_c)/2 times cos and sin of twice the chord's angle. Then
/// a uniform blade's linear pre-twist (Param::twist, docs/model.md section 12): cos 2 twist xi and sin 2 twist xi.
/// Then a blade's section offsets (docs/model.md sections 12.5 and 12.6): the mass per length times the centre of mass's
/// offset towards the leading edge, times cos and sin of the chord's angle (pitch and tabulated twist), linear between
/// stations; the axial stiffness times the tension centre's offset likewise; and the mass per length times the square
/// of the centre of mass's offset, alone and times cos and sin of twice the chord's angle (the offset mass's rotary
/// inertia as the bent axis turns the chord).
enum class SectionDistribution : int {
    m,
    EI,
    ES,
    EI_flap,
    GJ,
    j_p,
    EI_cos,
    EI_sin,
    j_cos,
    j_sin,
    cos_2twist,
    sin_2twist,
    mass_offset_cos,
    mass_offset_sin,
    tension_offset_cos,
    tension_offset_sin,
    mass_offset2,
    mass_offset2_cos,
    mass_offset2_sin
};
inline constexpr std::size_t section_distribution_count = 19;
inline constexpr std::array<const char*, section_distribution_count> section_distribution_names = {
    "m", "EI", "ES", "EI_flap", "GJ", "j_p", "EI_cos", "EI_sin", "j_cos", "j_sin", "cos_2twist", "sin_2twist",
    "mass_offset_cos", "mass_offset_sin", "tension_offset_cos", "tension_offset_sin", "mass_offset2",
    "mass_offset2_cos", "mass_offset2_sin"};
/// Whether a distribution is a table's (linear between its stations), not the pre-twist's.
constexpr bool tabulated(SectionDistribution d)
{
    return d != SectionDistribution::cos_2twist && d != SectionDistribution::sin_2twist;
}

/// A blade's section offsets at each station (docs/model.md sections 12.5 and 12.6), along the chord from the reference
/// axis, positive towards the trailing edge (m): the centre of mass's (BModes' cg_offst) and the tension centre's
/// (BModes' tc_offst).
enum class SectionOffset : std::size_t { mass, tension };
inline constexpr std::size_t section_offset_count = 2;
inline constexpr std::array<const char*, section_offset_count> section_offset_names = {"cg_offset", "tc_offset"};

/// A profile variant's kernels read its section integrals after the parameters: p[param_count + n] is
/// Variant::section_integrals[n] of the run's table (runtime/src/models/section_integrals.hpp computes them).

/// The paper's parameters: a variant without extra terms reads these only.
inline constexpr std::size_t paper_param_count = 7;
/// Names of p's entries in the order of Param, as they read in docs/model.md and in generated code.
inline constexpr std::array<const char*, param_count> param_names = {
    "L",     "rho",  "S",         "I",      "E", "a",   "J_oh",  "m_tip", "J_tip",   "g",
    "alpha", "beta", "tip_ratio", "I_flap", "G", "J_t", "pitch", "twist", "precone", "g_axis",
    "m_hub", "k_x",  "k_y",       "c_x",    "c_y", "J_tip_flap", "J_tip_twist", "tip_offset"};

/// The parameters of the out-of-plane fields (docs/model.md section 12), owned by no term: the flapwise field reads
/// I_flap, the twist field all three.
inline constexpr std::array<Param, 3> field_params = {Param::I_flap, Param::G, Param::J_t};

/// Index of each drive value in u: a torque variant reads tau, a prescribed variant theta_dot, theta_ddot.
enum class DriveValue : std::size_t { tau, theta_dot, theta_ddot };
inline constexpr std::size_t drive_value_count = 3;
inline constexpr std::array<const char*, drive_value_count> drive_value_names = {"tau", "theta_dot", "theta_ddot"};
/// A gravity variant's kernels also read sin(theta) and cos(theta), after the drive values: u[3], u[4]. The
/// Jacobian's dQ/du covers the drive values only (dQ/dtheta is Model::forces_theta).
enum class AngleValue : std::size_t { sin_theta = drive_value_count, cos_theta };
inline constexpr std::size_t kernel_input_count = drive_value_count + 2;
inline constexpr std::array<const char*, 2> angle_value_names = {"sin_theta", "cos_theta"};

constexpr std::size_t index(Param p)
{
    return static_cast<std::size_t>(p);
}
constexpr std::size_t index(DriveValue u)
{
    return static_cast<std::size_t>(u);
}
constexpr std::size_t index(AngleValue u)
{
    return static_cast<std::size_t>(u);
}

/// Physical parameters (SI): beam length, density, cross-section, second moment, Young's modulus, hub
/// radius, hub inertia. The defaults are the beam of Kane, Ryan & Banerjee (docs/model.md section 6). Then the
/// extra terms' values (docs/model.md section 11): tip mass and rotary inertia, gravity, Rayleigh damping
/// (alpha 1/s, beta s) and the taper's tip-to-root ratio of the tapered dimension; at these defaults a variant
/// that carries the terms equals one that does not. Then the out-of-plane section's (docs/model.md section 12): the
/// flapwise second moment (m^4; the scene's default is I), shear modulus (Pa), torsion constant (m^4), pitch, pre-twist
/// and precone (rad), and gravity along -k (m/s^2; g is along -j of the inertial plane). Then a moving hub's (docs/model.md
/// section 13): its translating mass (kg), the support's stiffness (N/m) and damping (N s/m) along the inertial x and y.
/// Then the tip body's (docs/model.md section 11.1): its mass moments about its centre of mass about the chord (flap)
/// and the span axis (torsion), kg m^2, and that centre's offset along the chord from the beam's end, positive towards
/// the trailing edge (m); J_tip is its moment about the chord's normal (lag).
struct Parameters {
    double L = 8.0, rho = 2.7667e3, S = 7.2968e-5, I = 8.2189e-9, E = 6.8952e10, a = 0.0, J_oh = 30.0;
    double m_tip = 0.0, J_tip = 0.0, g = 0.0, alpha = 0.0, beta = 0.0, tip_ratio = 1.0;
    double I_flap = 8.2189e-9, G = 0.0, J_t = 0.0, pitch = 0.0, twist = 0.0, precone = 0.0, g_axis = 0.0;
    double m_hub = 0.0, k_x = 0.0, k_y = 0.0, c_x = 0.0, c_y = 0.0;
    double J_tip_flap = 0.0, J_tip_twist = 0.0, tip_offset = 0.0;
    /// A tabulated profile's stations x/L (from 0 to 1, increasing; empty without a profile) and its values there:
    /// mass per length (kg/m), EI (N m^2), ES (N) and, for a beam that leaves the plane, EI_flap, GJ (N m^2), the
    /// chord's angle (rad), j_c and j_n (kg m), indexed by station then ProfileValue.
    std::vector<double> stations = {};
    std::vector<double> profile = {};
    /// A blade's section offsets at the stations (m; indexed by station then SectionOffset), empty where the section
    /// has none: what a variant with offsets reads (Extras::offsets).
    std::vector<double> offsets = {};

    /// p, indexed by Param (a profile variant's kernels read its section integrals after these).
    std::vector<double> packed() const
    {
        std::vector<double> p(param_count);
        p[index(Param::L)] = L;
        p[index(Param::rho)] = rho;
        p[index(Param::S)] = S;
        p[index(Param::I)] = I;
        p[index(Param::E)] = E;
        p[index(Param::a)] = a;
        p[index(Param::J_oh)] = J_oh;
        p[index(Param::m_tip)] = m_tip;
        p[index(Param::J_tip)] = J_tip;
        p[index(Param::g)] = g;
        p[index(Param::alpha)] = alpha;
        p[index(Param::beta)] = beta;
        p[index(Param::tip_ratio)] = tip_ratio;
        p[index(Param::I_flap)] = I_flap;
        p[index(Param::G)] = G;
        p[index(Param::J_t)] = J_t;
        p[index(Param::pitch)] = pitch;
        p[index(Param::twist)] = twist;
        p[index(Param::precone)] = precone;
        p[index(Param::g_axis)] = g_axis;
        p[index(Param::m_hub)] = m_hub;
        p[index(Param::k_x)] = k_x;
        p[index(Param::k_y)] = k_y;
        p[index(Param::c_x)] = c_x;
        p[index(Param::c_y)] = c_y;
        p[index(Param::J_tip_flap)] = J_tip_flap;
        p[index(Param::J_tip_twist)] = J_tip_twist;
        p[index(Param::tip_offset)] = tip_offset;
        return p;
    }
};

/// The value of parameter k in p (a reference into it): what a caller that moves one parameter changes.
inline double& value(Parameters& p, Param k)
{
    double* const members[] = {&p.L,     &p.rho,   &p.S,     &p.I,     &p.E,       &p.a,         &p.J_oh,
                               &p.m_tip, &p.J_tip, &p.g,     &p.alpha, &p.beta,    &p.tip_ratio, &p.I_flap,
                               &p.G,     &p.J_t,   &p.pitch, &p.twist, &p.precone, &p.g_axis,
                               &p.m_hub, &p.k_x,   &p.k_y,   &p.c_x,   &p.c_y,     &p.J_tip_flap, &p.J_tip_twist,
                               &p.tip_offset};
    static_assert(sizeof members / sizeof members[0] == param_count);
    return *members[index(k)];
}
/// The value of parameter k in p.
inline double value(const Parameters& p, Param k)
{
    return value(const_cast<Parameters&>(p), k);
}

/// The drive at one instant. theta is the prescribed angle, read only by a prescribed variant with gravity (a
/// torque variant's angle is its coordinate q[0]).
struct HubInput {
    double tau = 0.0, theta_dot = 0.0, theta_ddot = 0.0;
    double theta = 0.0;

    /// u, indexed by DriveValue.
    std::array<double, drive_value_count> packed() const
    {
        std::array<double, drive_value_count> u{};
        u[index(DriveValue::tau)] = tau;
        u[index(DriveValue::theta_dot)] = theta_dot;
        u[index(DriveValue::theta_ddot)] = theta_ddot;
        return u;
    }
};

}  // namespace hubbeam
