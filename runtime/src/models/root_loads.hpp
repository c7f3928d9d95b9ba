// A blade's root loads by force summation (docs/model.md section 13.3): the resultant and moment about the root of
// the inertial and gravity forces on the blade, from q, qd, qdd, the drive and the blade's parameters.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <vector>

#include <hubbeam/fields.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// The load the blade exerts on the hub at x = 0, in the blade's root frame (e1 along the undeformed blade, e2 in the
/// plane of rotation towards the direction of travel, e3 = e1 x e2, the spin axis turned by the precone): the force's
/// components along e1 (axial, positive in tension), e2 and e3 (shears), and the moment's about e3 (edgewise) and
/// about -e2 (flapwise), signed so that at rest they are EI_edge u_y''(0) and EI_flap u_z''(0) of a blade at pitch 0.
struct RootLoads {
    double edge_moment = 0.0, flap_moment = 0.0, shear_edge = 0.0, shear_flap = 0.0, axial_force = 0.0;
};

/// RootLoads' members in the order of root_load_columns (simulate.hpp, which names them; run_rows.cpp checks the count).
inline constexpr std::array<double RootLoads::*, 5> root_load_members = {
    &RootLoads::edge_moment, &RootLoads::flap_moment, &RootLoads::shear_edge, &RootLoads::shear_flap,
    &RootLoads::axial_force};

/// One blade's force summation: a Gauss rule on the pieces of every basis and the profile's stations, with enough
/// points to integrate the polynomial integrands exactly (AMM's to round-off), the shape functions' values at its nodes
/// computed once.
class BladeLoads {
public:
    /// Blade of variant key (a single blade's coordinate layout) with parameters p (Rotor::blade's).
    BladeLoads(const VariantKey& key, const Parameters& p);
    /// The loads at the blade's own q, qd, qdd (its model's layout; theta, when a coordinate, at the blade's azimuth)
    /// under the drive u (its angle at the blade's azimuth: RotorModel::blade_input).
    RootLoads operator()(const HubInput& u, const double* q, const double* qd, const double* qdd) const;

private:
    /// The kinematics of one node along the span: the shape functions' rows, the section's data there.
    struct Node {
        double x, weight;            // m; weight in m (0 for the tip's node)
        double m;                    // kg/m
        // The mass moments per length (kg m): their sum j_c + j_n and their deviator (j_n - j_c) / 2 turned by twice
        // the principal inertia axes' angle with the pitch, (j_n - j_c) / 2 e^(2 i beta), as the section integrals take
        // its components.
        double j_p;
        std::complex<double> j_dev;
        std::vector<double> axial, inplane, flap, twist;  // values
        std::vector<double> inplane_slope, flap_slope;    // d/dx
        // The foreshortening's integral from 0 to x: over the panels before this node's (their outer nodes) and over
        // [panel start, x] by its own rule (inner nodes' weights in m, slopes d/dx).
        std::size_t panel_first = 0;  // the first outer node of this node's panel
        std::vector<double> inner_weights;
        std::vector<std::vector<double>> inner_inplane, inner_flap;
    };
    /// The foreshortening's integrand and its first two time derivatives at a node's slope rows, state = (q, qd, qdd):
    /// g0 = u_y'^2 + u_z'^2, g1 = d/dt g0 / 2, g2 = d2/dt2 g0 / 2.
    std::array<double, 3> slope_products(const std::vector<double>& y_row, const std::vector<double>& z_row,
                                         const double* const state[3]) const;
    /// g0, g1, g2 summed with the rule's weights over the outer nodes before each node (entry n: nodes 0..n-1).
    std::vector<std::array<double, 3>> shortening_sums(const double* const state[3]) const;
    /// u_x2 at node n and its rates: -1/2 int g0, -int g1, -int g2 from the root to x (0 for order zero).
    std::array<double, 3> shortening(const Node& n, const std::vector<std::array<double, 3>>& before,
                                     const double* const state[3]) const;
    /// The node at xi with quadrature weight (m); section: a taper's ratios.
    Node node_at(const BeamFields& section, double xi, double weight) const;
    /// Adds -dh/dt dx, the section's rotary inertia over dx at node n, to M (i_b, j_b, k) at hub rate w and acceleration
    /// dw, twist phi[0..2] (value and rates) and precone cosine cb, sine sb.
    static void section_inertia(const Node& n, double dx, double w, double dw, const double* phi, double cb, double sb,
                                double* M);

    VariantKey key_;
    Parameters p_;
    std::vector<double> inertia_;  // a profile's j_p, j_cos, j_sin at each station (without the pitch); else empty
    int hub_x_ = -1, hub_y_ = -1, axial_ = -1, inplane_ = -1, flap_ = -1, twist_ = -1;
    bool torque_, foreshortened_;
    std::vector<Node> nodes_;  // the rule's, by increasing x
    Node tip_;                 // x = L
};

/// Each blade's root loads (blade 0 first) of a scene's model at its full q, qd, qdd (the rotor's layout for more than
/// one blade) under the drive u; blades[b] is blade b's BladeLoads.
std::vector<RootLoads> blade_root_loads(const Model& model, const std::vector<BladeLoads>& blades, const HubInput& u,
                                        const double* q, const double* qd, const double* qdd);

}  // namespace hubbeam
