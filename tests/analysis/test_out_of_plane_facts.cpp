// The facts of docs/model.md section 12 that any correct out-of-plane model reproduces, each from physics: the
// rotating uniform blade's flap frequencies (Wright et al. 1982 as tabulated by Bir 2009), flap and lead-lag
// related by omega_flap^2 = omega_lag^2 + Omega^2, torsion at rest and stiffened by the propeller moment, a pitch of
// 90 degrees exchanging the flapwise and edgewise stiffness, the flap sag under gravity along the spin axis, and the
// planar model as the special case nz = nt = 0. Generated models, compiled on demand where not built in.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <string>
#include <vector>

#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

/// A uniform blade in the units sqrt(EI/(m L^4)) = 1 (L = 1, m = 1, EI_edge = EI_flap = 1), clamped at the axis,
/// with a torsion stiffness GJ = 1/2 and section mass moments j_n = rho I, j_c = rho I_flap.
Parameters unit_blade()
{
    Parameters p;
    p.L = 1.0, p.rho = 1.0, p.S = 1.0, p.I = 1.0, p.E = 1.0, p.a = 0.0, p.J_oh = 1.0;
    p.I_flap = 1.0, p.G = 1.0, p.J_t = 0.5;
    return p;
}

VariantKey blade_key(Method method, int n, int nt = 0, Extras extras = {})
{
    VariantKey key{.method = method, .nx = 0, .ny = n, .order = Order::first, .drive = Drive::prescribed};
    key.nz = n;
    key.nt = nt;
    key.extras = extras;
    return key;
}

/// The frequencies (rad/s) of the modes of one kind at spin omega, lowest first.
std::vector<double> frequencies(const Model& model, double omega, const std::string& kind)
{
    std::vector<double> f;
    for (const NaturalMode& m : natural_modes(model, steady_spin(model, omega)))
        if (m.kind == kind) f.push_back(m.rad_s);
    return f;
}

}  // namespace

TEST_CASE("flap frequencies of a rotating uniform blade converge to the Wright/Bir table with every method",
          "[out_of_plane]")
{
    // Bir 2009 (BModes verification), from Wright, Smith, Thresher & Wang 1982: modes 1-3 at Omega = 0, 6, 12.
    const double omegas[] = {0.0, 6.0, 12.0};
    const double table[3][3] = {{3.516, 22.035, 61.697}, {7.360, 26.809, 66.684}, {13.170, 37.603, 79.615}};
    struct Case {
        Method method;
        int coarse, fine;
    };
    // Each method at two sizes: the finer one within the table's rounding (5e-4 of the value) on mode 1 and closer
    // than the coarser on every mode.
    for (const Case c :
         {Case{Method::amm, 6, 10}, Case{Method::fem, 8, 16}, Case{Method::bim, 8, 12}, Case{Method::bsim, 8, 14}}) {
        const Parameters p = unit_blade();
        const auto coarse = make_model(blade_key(c.method, c.coarse), p, ModelSource::generated);
        const auto fine = make_model(blade_key(c.method, c.fine), p, ModelSource::generated);
        for (int w = 0; w < 3; ++w) {
            const std::vector<double> f_coarse = frequencies(*coarse, omegas[w], "flap");
            const std::vector<double> f_fine = frequencies(*fine, omegas[w], "flap");
            REQUIRE(f_fine.size() >= 3);
            for (int i = 0; i < 3; ++i) {
                INFO(to_string(c.method) << " Omega " << omegas[w] << " mode " << i + 1 << ": " << f_coarse[i] << ", "
                                         << f_fine[i] << " against " << table[w][i]);
                const double e_coarse = std::abs(f_coarse[i] - table[w][i]), e_fine = std::abs(f_fine[i] - table[w][i]);
                CHECK((e_fine <= e_coarse || e_fine <= 5e-4 * table[w][i]));
                CHECK(e_fine <= (i == 0 ? 5e-4 : 2e-3) * table[w][i]);
            }
        }
    }
}

TEST_CASE("flap and lead-lag of a uniform blade: omega_flap^2 = omega_lag^2 + Omega^2 mode by mode", "[out_of_plane]")
{
    // Nx = 0, order first, a = 0, no pitch or precone, EI_flap = EI_edge: the centrifugal stiffening is the same,
    // lead-lag alone softened by -Omega^2 m (section 12). Holds for any discretization with nz = ny.
    for (Method method : {Method::amm, Method::fem, Method::bim, Method::bsim}) {
        const auto model = make_model(blade_key(method, 8), unit_blade(), ModelSource::generated);
        for (double omega : {2.0, 6.0, 12.0}) {
            const std::vector<double> flap = frequencies(*model, omega, "flap"),
                                      edge = frequencies(*model, omega, "edge");
            REQUIRE(flap.size() == edge.size());
            for (std::size_t i = 0; i < 4; ++i) {
                INFO(to_string(method) << " Omega " << omega << " mode " << i + 1);
                // 1e-8: the eigen solver resolves the first-order (gyroscopic) form's frequencies to about 1e-9 of
                // their square (BSIM's fourth pair 9.8e-10 at worst, docs/validation.md).
                CHECK(flap[i] * flap[i] == Approx(edge[i] * edge[i] + omega * omega).epsilon(1e-8));
            }
        }
    }
}

TEST_CASE("torsion: (2i-1) pi/(2L) sqrt(GJ/j_p) at rest, and the propeller moment's Omega^2 (j_n - j_c)/j_p",
          "[out_of_plane]")
{
    Parameters p = unit_blade();
    p.I = 1.0, p.I_flap = 0.25;  // j_n = 1, j_c = 0.25, j_p = 1.25: the section resists turning from the plane
    const double jp = p.rho * (p.I + p.I_flap), shift = (p.rho * p.I - p.rho * p.I_flap) / jp;
    const double at_rest = M_PI / (2.0 * p.L) * std::sqrt(p.G * p.J_t / jp);
    for (Method method : {Method::fem, Method::bsim, Method::amm, Method::bim}) {
        const int nt = method == Method::bim ? 8 : 16;
        const auto model = make_model(blade_key(method, 4, nt), p, ModelSource::generated);
        const std::vector<double> rest = frequencies(*model, 0.0, "twist");
        REQUIRE(rest.size() >= 2);
        INFO(to_string(method) << ": " << rest[0] << ", " << rest[1]);
        CHECK(rest[0] == Approx(at_rest).epsilon(method == Method::fem ? 2e-3 : 1e-6));
        CHECK(rest[1] == Approx(3.0 * at_rest).epsilon(method == Method::fem ? 1e-2 : 1e-5));
        for (double omega : {3.0, 10.0}) {
            // The same discretization's twist frequencies, shifted exactly: the propeller moment is a stiffness
            // proportional to the twist field's own mass.
            const std::vector<double> spun = frequencies(*model, omega, "twist");
            for (std::size_t i = 0; i < 2; ++i)
                CHECK(spun[i] * spun[i] == Approx(rest[i] * rest[i] + omega * omega * shift).epsilon(1e-9));
        }
    }
}

TEST_CASE("a blade file's flap and edge mass moments are the section's about the chord and its normal, by the "
          "propeller moment",
          "[out_of_plane][blade_files]")
{
    // BModes' flp_iner and ElastoDyn's FlpIner are the mass moment about the chord (flap: the section turning about
    // it), edg_iner and EdgIner about its normal. A uniform blade with the flap one 1/4 and the edge one 1 resists
    // turning from the plane of rotation: its twist frequencies rise by Omega^2 (1 - 1/4)/(1 + 1/4) exactly (the
    // facts' test above), and would fall by as much were the two read the wrong way round. BModes gives them about
    // the principal inertia axes at tw_iner: the same section written with those axes turned a right angle from the
    // chord (tw_iner 90 deg, the two moments exchanged) is the same blade.
    const TempFolder folder("inertia-columns");
    const std::string bmodes =
        "uniform blade\n2 n_secs\n\nsec_loc str_tw tw_iner mass_den flp_iner edge_iner flp_stff edge_stff tor_stff "
        "axial_stff cg_offst sc_offst tc_offst\n(-) (deg) (deg) (kg/m) (kg-m) (kg-m) (Nm^2) (Nm^2) (Nm^2) (N) (m) (m) "
        "(m)\n0 0 0 1 0.25 1 1 4 0.5 1e4 0 0 0\n1 0 0 1 0.25 1 1 4 0.5 1e4 0 0 0\n";
    std::string turned = bmodes;
    for (const char* row : {"0 0 0 1 0.25 1 ", "1 0 0 1 0.25 1 "}) {
        const std::size_t at = turned.find(row);
        turned.replace(at, 15, std::string(1, row[0]) + " 0 90 1 1 0.25 ");
    }
    const std::string elastodyn =
        "---\n--- FAST INDIVIDUAL BLADE FILE ---\nuniform blade\n--- BLADE PARAMETERS ---\n2 NBlInpSt - stations\n"
        "F CalcBMode - x\n1 BldFlDmp(1) - x\n1 BldFlDmp(2) - x\n1 BldEdDmp(1) - x\n--- BLADE ADJUSTMENT FACTORS ---\n"
        "1 FlStTunr(1) - x\n1 FlStTunr(2) - x\n1 AdjBlMs - x\n1 AdjFlSt - x\n1 AdjEdSt - x\n"
        "--- DISTRIBUTED BLADE PROPERTIES ---\n"
        "BlFract AeroCent StrcTwst BMassDen FlpStff EdgStff GJStff EAStff Alpha FlpIner EdgIner PrecrvRef PreswpRef "
        "FlpcgOf EdgcgOf FlpEAOf EdgEAOf\n(-) (-) (deg) (kg/m) (Nm^2) (Nm^2) (Nm^2) (N) (-) (kg m) (kg m) (m) (m) (m) (m) "
        "(m) (m)\n0 0.25 0 1 1 4 0.5 1e4 0 0.25 1 0 0 0 0 0 0\n1 0.25 0 1 1 4 0.5 1e4 0 0.25 1 0 0 0 0 0 0\n"
        "--- BLADE MODE SHAPES ---\n";
    for (const auto& [name, text] :
         {std::pair{"bmodes.dat", bmodes}, {"bmodes_axes.dat", turned}, {"elastodyn.dat", elastodyn}}) {
        folder.write(name, text);
        const std::string scene = folder.write(
            "blade.toml", "[beam]\nlength = 1.0\nblade_file = \"" + std::string(name) +
                              "\"\n[motion]\nkind = \"spin-up\"\nomega0 = 1.0\nduration = 1.0\n[discretization]\n"
                              "method = \"fem\"\nnx = 0\nny = 4\nnz = 4\nnt = 8\n[output]\nt_end = 1.0\n");
        const Scene s = load_scene(scene);
        const auto model = make_model(s.key(), s.parameters, ModelSource::assembled);
        const std::vector<double> rest = frequencies(*model, 0.0, "twist"), spun = frequencies(*model, 5.0, "twist");
        REQUIRE(rest.size() >= 2);
        REQUIRE(spun.size() >= 2);
        for (std::size_t i = 0; i < 2; ++i) {
            INFO(name << " twist mode " << i + 1 << ": " << rest[i] << " at rest, " << spun[i] << " at 5 rad/s");
            CHECK(spun[i] * spun[i] == Approx(rest[i] * rest[i] + 25.0 * 0.75 / 1.25).epsilon(1e-9));
        }
    }
}

TEST_CASE("the library refuses a spin about which weight in the plane of rotation allows no steady state",
          "[out_of_plane][modes]")
{
    // The wind turbine's blade: its weight in a vertical plane of rotation turns with it, so a spin at a rate is
    // periodic (every caller of steady_spin meets the refusal, not the command line alone; the modes there are the
    // periodic motion's Floquet modes, test_floquet.cpp); held (Omega = 0) it has its static equilibrium.
    const Scene s = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/wind_turbine_blade.toml");
    const auto model = make_model(s.key(), s.parameters, ModelSource::assembled);
    CHECK_THROWS_WITH(steady_spin(*model, 3.0), Catch::Contains("not steady"));
    CHECK_FALSE(unsteady_spin(s.key(), s.parameters.packed(), 3.0).empty());
    CHECK(steady_spin(*model, 0.0).held);
    // Weight along the spin axis does not turn: a blade holds its sag at any spin.
    Parameters p = unit_blade();
    p.g_axis = 0.2;
    const VariantKey key = blade_key(Method::fem, 4, 0, {.gravity = true});
    const auto axial_weight = make_model(key, p, ModelSource::assembled);
    CHECK(unsteady_spin(key, p.packed(), 3.0).empty());
    const SteadySpin spun = steady_spin(*axial_weight, 3.0);
    CHECK_FALSE(spun.held);
    CHECK(spun.omega == 3.0);
}

TEST_CASE("a blade's in-plane modes are edge modes whatever takes it out of the plane: twist alone, a pitch alone",
          "[out_of_plane][modes]")
{
    // Lead-lag is "edge" on a blade (docs/cli.md's kinds), "bending" only on a planar beam; a twist field without a
    // flapwise one, or a pitch with neither, makes a blade as much as flap does.
    Parameters p = unit_blade();
    p.pitch = 0.3;
    for (const auto& [nz, nt, extras] : {std::tuple{0, 4, Extras{}}, {0, 0, Extras{.pitch = true}}, {4, 0, Extras{}}}) {
        VariantKey key = blade_key(Method::fem, 4, nt, extras);
        key.nz = nz;
        const auto model = make_model(key, p, ModelSource::assembled);
        INFO("nz " << nz << ", nt " << nt << ", pitch " << extras.pitch);
        const std::vector<double> edge = frequencies(*model, 0.0, "edge"), bending = frequencies(*model, 0.0, "bending");
        CHECK(edge.size() >= 2);
        CHECK(bending.empty());
    }
    // The planar beam keeps "bending".
    VariantKey planar_key = blade_key(Method::fem, 4);
    planar_key.nz = 0;
    const auto planar = make_model(planar_key, unit_blade(), ModelSource::assembled);
    CHECK(frequencies(*planar, 0.0, "edge").empty());
    CHECK(frequencies(*planar, 0.0, "bending").size() >= 2);
}

TEST_CASE("a pitch of 90 degrees exchanges the flapwise and the edgewise stiffness", "[out_of_plane]")
{
    Parameters flat = unit_blade();
    flat.I_flap = 0.2;  // a blade stiffer edgewise: I = 1, I_flap = 0.2
    Parameters pitched = flat;
    pitched.pitch = M_PI / 2;
    Parameters swapped = flat;  // the stiffnesses exchanged at pitch 0 (with the mass moments kept: no twist field)
    swapped.I = flat.I_flap, swapped.I_flap = flat.I;
    swapped.S = flat.S;
    for (Method method : {Method::fem, Method::amm}) {
        const auto with_pitch =
            make_model(blade_key(method, 6, 0, Extras{.pitch = true}), pitched, ModelSource::generated);
        const auto exchanged = make_model(blade_key(method, 6), swapped, ModelSource::generated);
        for (double omega : {0.0, 5.0}) {
            std::vector<NaturalMode> a = natural_modes(*with_pitch, steady_spin(*with_pitch, omega));
            std::vector<NaturalMode> b = natural_modes(*exchanged, steady_spin(*exchanged, omega));
            REQUIRE(a.size() == b.size());
            for (std::size_t i = 0; i < 8; ++i) {
                INFO(to_string(method) << " Omega " << omega << " mode " << i + 1);
                CHECK(a[i].rad_s == Approx(b[i].rad_s).epsilon(1e-10));
                CHECK(a[i].kind == b[i].kind);
            }
        }
        // And the edgewise modes of the flat blade are the flapwise ones of the pitched blade at rest.
        const auto flat_model = make_model(blade_key(method, 6), flat, ModelSource::generated);
        const std::vector<double> edge = frequencies(*flat_model, 0.0, "edge"),
                                  flap = frequencies(*with_pitch, 0.0, "flap");
        for (std::size_t i = 0; i < 3; ++i) CHECK(flap[i] == Approx(edge[i]).epsilon(1e-10));
    }
}

TEST_CASE("a held blade sags -m g L^4/(8 EI_flap) under gravity along the spin axis", "[out_of_plane]")
{
    Parameters p = unit_blade();
    p.I_flap = 0.3;
    p.g_axis = 0.01;  // small: the linear sag of the first-order model
    const double sag = -p.rho * p.S * p.g_axis * std::pow(p.L, 4) / (8.0 * p.E * p.I_flap);
    // FEM's cubic Hermite elements hold the quartic deflection's nodal values exactly; AMM converges.
    for (const auto& [method, n, tolerance] :
         {std::tuple{Method::fem, 4, 1e-9}, {Method::bsim, 6, 1e-9}, {Method::bim, 6, 1e-9}, {Method::amm, 10, 1e-4}}) {
        const auto model = make_model(blade_key(method, n, 0, Extras{.gravity = true}), p, ModelSource::generated);
        const SteadySpin held = held_equilibrium(*model, 0.0);
        const Tip tip = model->tip(held.q.data());
        INFO(to_string(method) << ": " << tip.uz << " against " << sag);
        CHECK(tip.uz == Approx(sag).epsilon(tolerance));
        CHECK(std::abs(tip.uy) < 1e-12 * std::abs(sag));  // no weight in the plane
    }
}

TEST_CASE("a pitched blade's steady twist under the propeller moment is the closed form of GJ phi'' - k^2 GJ phi = q",
          "[out_of_plane]")
{
    // cases/pitched_propeller.toml's blade: q = 1/2 Omega^2 (j_n - j_c) sin 2 beta per length turns the section towards
    // the plane, k^2 GJ = Omega^2 (j_n - j_c) cos 2 beta stiffens it; phi(0) = 0, phi'(L) = 0.
    Parameters p;
    p.L = 2.0, p.rho = 2700.0, p.S = 0.002, p.I = 4e-7, p.I_flap = 4e-8, p.E = 7e10, p.G = 2.6e10, p.J_t = 1.6e-8;
    p.a = 0.1, p.pitch = 0.3;
    const double omega = 100.0, GJ = p.G * p.J_t, dj = p.rho * (p.I - p.I_flap);
    const double q = 0.5 * omega * omega * dj * std::sin(2 * p.pitch);
    const double k = std::sqrt(omega * omega * dj * std::cos(2 * p.pitch) / GJ);
    const double tip = -q / (k * k * GJ) * (1.0 - 1.0 / std::cosh(k * p.L));
    for (const auto& [method, nt, tolerance] :
         {std::tuple{Method::bim, 6, 1e-8}, {Method::amm, 12, 1e-4}, {Method::bsim, 8, 1e-5}, {Method::fem, 8, 1e-3}}) {
        const auto model = make_model(blade_key(method, 4, nt, Extras{.pitch = true}), p, ModelSource::generated);
        const SteadySpin s = steady_spin(*model, omega);
        INFO(to_string(method) << ": " << model->tip(s.q.data()).phi << " against " << tip);
        CHECK(model->tip(s.q.data()).phi == Approx(tip).epsilon(tolerance));
    }
}

TEST_CASE("with gravity along the spin axis a steady spin holds the sag, as a damped run settles to it",
          "[out_of_plane]")
{
    // cases/helicopter_blade.toml: Newton on the elastic rows at 30 rad/s (steady_spin) against the damped run's
    // last rows at 30 rad/s, two routes that share no code beyond the model.
    Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/helicopter_blade.toml");
    scene.output.t_end = 60.0;  // the spin steady from 20 s: 40 s of settling at damping ratios of 1 % and more
    double settled = 0.0;
    simulate(scene, [&](const Row& r) { settled = r.extras.tip_uz; });
    const auto model = make_model(scene.key(), scene.parameters, ModelSource::generated);
    const SteadySpin s = steady_spin(*model, 30.0);
    const double held = model->tip(steady_spin(*model, 0.0).q.data()).uz;
    INFO("steady " << model->tip(s.q.data()).uz << ", settled " << settled << ", at rest " << held);
    CHECK(model->tip(s.q.data()).uz == Approx(settled).epsilon(1e-6));
    CHECK(std::abs(settled) < 0.2 * std::abs(held));  // the spin's tension lifts the blade
}

TEST_CASE("a free hub with a pitched, coned, twisting blade keeps its energy and momentum once the torque ends",
          "[out_of_plane]")
{
    // cases/torque_tau10.toml's beam given flap and twist fields and every angle: after the pulse (t > 10 s) nothing
    // acts on the system, so T + U and the angular momentum h = int tau dt (zero: a full sine period) are constant.
    // Order full too: its extra terms are conservative.
    for (Order order : {Order::first, Order::full}) {
        Scene scene = load_scene(std::string(HUBBEAM_SOURCE_DIR) + "/cases/torque_tau10.toml");
        scene.variant.method = Method::fem, scene.variant.nx = 0, scene.variant.ny = 4;
        scene.variant.nz = 4, scene.variant.nt = 2, scene.variant.order = order;
        Parameters& p = scene.parameters;
        p.I_flap = 0.5 * p.I, p.G = 2.6e10, p.J_t = 2.0 * p.I, p.pitch = 0.3, p.twist = -0.2, p.precone = 0.05;
        scene.output.t_end = 20.0;
        double energy = 0.0, largest = 0.0, drift = 0.0, momentum = 0.0;
        bool first = true;
        simulate(scene, [&](const Row& r) {
            largest = std::max(largest, std::abs(r.kinetic) + std::abs(r.potential));
            if (r.t < 10.0) return;
            if (first) energy = r.kinetic + r.potential, first = false;
            drift = std::max(drift, std::abs(r.kinetic + r.potential - energy));
            momentum = std::max(momentum, std::abs(r.momentum));
        });
        INFO(to_string(order) << ": energy drift " << drift << " of " << largest << ", momentum " << momentum);
        CHECK(drift < 1e-7 * largest);
        CHECK(momentum < 1e-8);
    }
}

TEST_CASE("order full and order first share a blade's frequencies about its straight steady spin",
          "[out_of_plane][full]")
{
    // Order full's terms beyond order first are of third order and above in the bending (u_x2 squared, u_x2 times u_y
    // or u_z): about a steady spin that bends nothing (no precone, no gravity, nx = 0; a steady twist bends nothing)
    // the linearizations are one.
    Parameters p = unit_blade();
    p.I_flap = 0.4, p.pitch = 0.3, p.twist = -0.2, p.a = 0.1;
    for (VariantKey key : {blade_key(Method::fem, 4, 2, Extras{.pitch = true, .twist = true}),
                           blade_key(Method::bim, 4, 0, Extras{.pitch = true})}) {
        VariantKey full = key;
        full.order = Order::full;
        const auto a = make_model(key, p, ModelSource::generated), b = make_model(full, p, ModelSource::generated);
        for (double omega : {0.0, 6.0}) {
            const std::vector<NaturalMode> ma = natural_modes(*a, steady_spin(*a, omega)),
                                           mb = natural_modes(*b, steady_spin(*b, omega));
            INFO(full.name() << " at " << omega);
            REQUIRE(ma.size() == mb.size());
            for (std::size_t i = 0; i < ma.size(); ++i) CHECK(mb[i].rad_s == Approx(ma[i].rad_s).epsilon(1e-9));
        }
    }
}
