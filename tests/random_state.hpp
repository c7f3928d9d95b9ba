// A random state of the size deformations reach in the paper's cases, shared by the tests that compare two
// computations of the same quantity at random states.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "coordinates.hpp"
#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam::test {

struct State {
    Eigen::VectorXd q, qd;
    HubInput u;
};

/// theta ~ 2 rad, A ~ 1 mm, B ~ 0.1 m, rates three times that per second; a random drive.
inline State random_state(const VariantKey& key, std::mt19937& rng)
{
    std::uniform_real_distribution<double> r(-1.0, 1.0);
    State s{Eigen::VectorXd(key.nq()), Eigen::VectorXd(key.nq()), {0.7 * r(rng), 3.0 * r(rng), 0.5 * r(rng)}};
    const CoordinateLayout layout = coordinate_layout(key);
    for (int i = 0; i < key.nq(); ++i) {
        const FieldKind kind = layout.field_of(i).kind;
        const double size = kind == FieldKind::hub_angle ? 2.0 : kind == FieldKind::axial ? 1e-3 : 0.1;
        s.q[i] = size * r(rng);
        s.qd[i] = 3.0 * size * r(rng);
    }
    return s;
}

/// p with a table where key has a profile (and p none), at p's stations or else at x/L = 0, 0.3, 0.55, 1 (irregular,
/// none at a piece boundary of FEM's or BSIM's Ny = 4 bases): the section of p's rho, S, I, E at the root, falling to
/// half at the tip and with a bump between, so that no value is the uniform beam's. A blade's (out of the plane) also
/// has a flapwise stiffness that falls otherwise, a torsional stiffness, a chord angle that turns one way and back (0.6
/// rad at the root, -0.3 at the tip) and unequal mass moments; with offsets, those too.
inline Parameters with_profile(const VariantKey& key, Parameters p)
{
    if (!key.extras.profile() || !p.profile.empty()) return p;
    if (p.stations.empty()) p.stations = {0.0, 0.3, 0.55, 1.0};
    for (double x : p.stations) {
        const double s = 1.0 - 0.5 * x + 0.3 * x * (1.0 - x);
        p.profile.insert(p.profile.end(), {p.rho * p.S * s, p.E * p.I * s * s, p.E * p.S * s});
        if (key.out_of_plane())
            p.profile.insert(p.profile.end(),
                             {p.E * p.I_flap * s * (1.0 + 0.4 * x), 0.4 * p.E * p.I * s * (1.0 + 0.2 * x),
                              0.6 - 1.7 * x + 0.8 * x * x, p.rho * p.I_flap * s, p.rho * p.I * s * (1.2 - 0.3 * x),
                              0.9 - 1.2 * x});  // the inertia axes off the chord, by -0.3 to 0.4 rad
    }
    // A blade's section offsets: the centre of mass 0.06 m behind the axis at the root and 0.04 m before it at the tip,
    // the tension centre from 0.03 m before it to 0.05 m behind (each changes sign on the span).
    if (key.extras.offsets)
        for (double x : p.stations) p.offsets.insert(p.offsets.end(), {0.06 - 0.1 * x, -0.03 + 0.08 * x * x});
    return p;
}

/// The paper's beam on a hub of radius 0.35 m with every extra term switched on at a size where it shows (a taper's
/// tip ratio 0.6): so that each term's code, and each parameter's derivative, is exercised.
inline Parameters with_every_term()
{
    Parameters p;
    p.a = 0.35;
    p.m_tip = 0.8;
    p.J_tip = 0.05;
    p.g = 9.81;
    p.alpha = 0.3;
    p.beta = 2e-3;
    p.tip_ratio = 0.6;
    // The out-of-plane section's (read by out-of-plane variants only): a flapwise second moment unlike I, torsion,
    // pitch, pre-twist, precone and weight along the spin axis, none of them a special value.
    p.I_flap = 2.3 * p.I;
    p.G = 2.6e10;
    p.J_t = 1.7e-8;
    p.pitch = 0.3;
    p.twist = -0.25;
    p.precone = 0.05;
    p.g_axis = 4.0;
    // A moving hub's (read by variants with a [support] only).
    p.m_hub = 12.0;
    p.k_x = 3.1e3;
    p.k_y = 4.7e3;
    p.c_x = 15.0;
    p.c_y = 22.0;
    // The tip body's in the blade's axes (read by variants that carry it only).
    p.J_tip_flap = 0.02;
    p.J_tip_twist = 0.045;  // its axes' second moments all nonzero: P_n = (J_tip_twist + J_tip_flap - J_tip) / 2
    p.tip_offset = 0.04;
    return p;
}

/// random_state with a prescribed angle as well, in (-3, 3) rad (a prescribed variant with gravity reads it).
inline State random_state_with_angle(const VariantKey& key, std::mt19937& rng)
{
    State s = random_state(key, rng);
    s.u.theta = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
    return s;
}

/// max |a - b| / max |b|: the relative error of a whole vector or matrix.
inline double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
    return (a - b).lpNorm<Eigen::Infinity>() / std::max(b.lpNorm<Eigen::Infinity>(), 1e-300);
}

/// A variant of Ny = 4 by its method, counts, drive, order, terms and spline: the generated-against-assembled tests'
/// variants, spelled alike so that they share one cache of compiled variants.
inline VariantKey key_of(Method method, int nx, int nz, int nt, Drive drive, Order order, Extras extras,
                         SplineBasis spline = SplineBasis::paper)
{
    return {.method = method,
            .nx = nx,
            .ny = 4,
            .nz = nz,
            .nt = nt,
            .order = order,
            .drive = drive,
            .spline = spline,
            .extras = extras};
}

}  // namespace hubbeam::test
