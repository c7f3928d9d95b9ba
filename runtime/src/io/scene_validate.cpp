// validate(): the ranges of a Scene's values and the checks that join keys, each failure naming its key.
#include <algorithm>
#include <cmath>
#include <hubbeam/linearize.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>

#include "dynamics/stepper_names.hpp"
#include "io/scene_io.hpp"

namespace hubbeam {

using namespace scene_io;

namespace {

/// output.sensitivities: known symbols, each once, that this scene has (a gain needs [control], tip_ratio a taper,
/// rho, S, I and E a beam without a profile), and a run the sensitivity equations can follow (dynamic axial
/// coordinates, no torque law in code).
void check_sensitivities(const Scene& s)
{
    const char* key = "output.sensitivities";
    std::vector<std::string> seen;
    for (const std::string& name : s.output.sensitivities) {
        const bool gain = std::find(gain_names.begin(), gain_names.end(), name) != gain_names.end();
        if (!gain && std::find(param_names.begin(), param_names.end(), name) == param_names.end())
            fail(s.path, key, expected(key), "\"" + name + "\"");
        if (std::find(seen.begin(), seen.end(), name) != seen.end())
            fail(s.path, key, expected(key), "\"" + name + "\" twice");
        seen.push_back(name);
        if (gain && !s.control) fail(s.path, key, "a control gain only with a [control] table", "\"" + name + "\"");
        // A parameter of a term the scene's words choose (taper, moving hub) only where the scene carries it.
        for (const TermInfo& t : terms())
            if (!t.selected_by_values && !t.carried(s.variant.extras) &&
                std::any_of(t.params.begin(), t.params.end(), [&](Param q) { return param_names[index(q)] == name; }))
                fail(s.path, key, name + " only with " + t.chosen_by, "\"" + name + "\"");
        // A profile's table replaces E, rho, S, I and the blade's section (read_profile sets some from its root for
        // reports only): their derivatives would be columns of zeros.
        static const std::vector<std::string> tabulated = {"E", "rho", "S", "I", "I_flap", "G", "J_t", "twist"};
        if (!s.parameters.profile.empty() && std::find(tabulated.begin(), tabulated.end(), name) != tabulated.end())
            fail(s.path, key,
                 "a parameter that the scene uses, not " + name +
                     " with beam.profile (its table gives "
                     "the section along the span in place of rho, S, I, E, I_flap, G, J_t and twist)",
                 "\"" + name + "\"");
    }
    if (!s.output.sensitivities.empty() && s.axial == Axial::quasi_static)
        fail(s.path, key,
             "model.axial \"dynamic\" (the sensitivity equations follow the axial coordinates' own "
             "motion)",
             "model.axial \"quasi-static\"");
}

// Range checks of validate(), naming the key.
void check_positive(const Scene& s, double v, const char* key)
{
    if (!(v > 0.0) || !std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
}
void check_finite(const Scene& s, double v, const char* key)
{
    if (!std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
}
/// A hub angle: finite, and no larger than max_hub_angle, within which double precision resolves it.
void check_angle(const Scene& s, double v, const char* key)
{
    check_finite(s, v, key);
    if (std::abs(v) > max_hub_angle)
        fail(s.path, key, "|" + std::string(key).substr(std::string(key).find('.') + 1) + "| <= " + angle_bound(),
             shortest(v));
}

/// [control]'s ranges, and the motions it can follow: a step is a reference only, a torque drive is none.
void check_control(const Scene& s)
{
    if (!s.control) {
        if (s.motion.kind == Motion::Kind::step)
            fail(s.path, "motion.kind",
                 "a motion of its own without a [control] section (a step is the reference of a "
                 "controlled hub)",
                 "\"step\"");
        return;
    }
    if (s.motion.drive() == Drive::torque)
        fail(s.path, "motion.kind", "a reference for [control]: \"spin-up\", \"held\", \"table\" or \"step\"",
             "\"" + kind_word(s.motion.kind) + "\"");
    const Control& c = *s.control;
    for (const auto& [v, key] : {std::pair{c.kp, "control.kp"}, {c.kd, "control.kd"}, {c.ki, "control.ki"}})
        if (!(v >= 0.0) || !std::isfinite(v)) fail(s.path, key, expected(key), shortest(v));
    if (!(c.tau_max > 0.0)) fail(s.path, "control.tau_max", expected("control.tau_max"), shortest(c.tau_max));
    check_finite(s, c.k_tip, "control.k_tip");
}

/// The out-of-plane section's values and what it cannot be combined with (docs/model.md section 12).
void check_out_of_plane(const Scene& s)
{
    const Parameters& p = s.parameters;
    const VariantKey& key = s.variant;
    check_positive(s, p.I_flap, "beam.second_moment_flap");
    if (!(std::abs(p.pitch) <= max_section_angle))
        fail(s.path, "beam.pitch", expected("beam.pitch"), shortest(p.pitch));
    if (!(std::abs(p.twist) <= max_section_angle)) fail(s.path, "beam.twist", expected("beam.twist"), shortest(p.twist));
    if (!(std::abs(p.precone) < 1.5)) fail(s.path, "beam.precone", expected("beam.precone"), shortest(p.precone));
    if (key.nz < 0) fail(s.path, "discretization.nz", expected("discretization.nz"), std::to_string(key.nz));
    if (key.nt < 0) fail(s.path, "discretization.nt", expected("discretization.nt"), std::to_string(key.nt));
    for (const auto& [v, name] : {std::pair{p.G, "beam.shear_modulus"}, {p.J_t, "beam.torsion_constant"}}) {
        if (!(v >= 0.0) || !std::isfinite(v)) fail(s.path, name, expected(name), shortest(v));
        // A profile's GJ column (fit_profile) stands for both.
        if (key.nt > 0 && v == 0.0 && !key.extras.profile())
            fail(s.path, name, "a number > 0 with discretization.nt > 0 (the twist field's stiffness)", "0");
    }
}

/// Every term's own keys (model/terms.cpp), each against the range its registry row gives.
void check_term_keys(const Scene& s)
{
    for (const TermInfo& t : terms())
        for (const TermSceneKey& k : t.scene_keys)
            if (const double v = value(s.parameters, k.param); !in_range(k.range, v))
                fail(s.path, k.name(), k.expected(), shortest(v));
}

/// The tip body's flap and torsion inertias and its offset (docs/model.md section 11.1): a variant that can carry
/// them, the key named being the first one given.
void check_tip_body(const Scene& s)
{
    const std::string problem = s.key().tip_body_problem();
    if (problem.empty()) return;
    // Its keys are the registry's (model/terms.cpp): those of the term that a variant with the tip body alone carries.
    Extras tip_body;
    tip_body.tip_body = true;
    for (const TermInfo* t : carried_terms(tip_body))
        for (const TermSceneKey& k : t->scene_keys)
            if (value(s.parameters, k.param) != 0.0) throw SceneError::with_detail(s.path, k.name(), problem);
    // Carried at 0: a sensitivity to one of them.
    throw SceneError::with_detail(s.path, "output.sensitivities", problem);
}

/// [damping]'s modal ratios (docs/model.md section 11.5): each >= 0, and no sensitivities beside them (their
/// derivatives would need the modes' own); the count of the blade's modes is make_scene_model's, which has them.
void check_modal_damping(const Scene& s)
{
    const ModalDamping& d = s.modal_damping;
    for (const auto& [ratios, key] : {std::pair{&d.flap, "damping.flap_ratios"}, {&d.edge, "damping.edge_ratios"}})
        for (std::size_t k = 0; k < ratios->size(); ++k)
            if (!((*ratios)[k] >= 0.0) || !std::isfinite((*ratios)[k]))
                fail(s.path, key, expected(key), shortest((*ratios)[k]) + " for mode " + std::to_string(k + 1));
    if (d.given() && !s.output.sensitivities.empty())
        fail(s.path, "output.sensitivities", "none beside damping.flap_ratios or damping.edge_ratios",
             "\"" + s.output.sensitivities.front() + "\"");
}

/// The beam's, hub's and extra terms' parameters (docs/model.md sections 1 and 11).
void check_parameters(const Scene& s)
{
    const Parameters& p = s.parameters;
    check_positive(s, p.L, "beam.length");
    check_positive(s, p.rho, "beam.density");
    check_positive(s, p.S, "beam.area");
    check_positive(s, p.I, "beam.second_moment");
    check_positive(s, p.E, "beam.youngs_modulus");
    if (!(p.a >= 0.0) || !std::isfinite(p.a)) fail(s.path, "hub.radius", expected("hub.radius"), shortest(p.a));
    check_positive(s, p.J_oh, "hub.inertia");
    if (s.variant.extras.taper != Taper::uniform) check_positive(s, p.tip_ratio, "beam.tip_ratio");
    check_term_keys(s);
    check_out_of_plane(s);
    check_tip_body(s);
    check_modal_damping(s);
}

/// The motion's values for its kind, its start angle and the control that follows it.
void check_motion(const Scene& s)
{
    switch (s.motion.kind) {
        case Motion::Kind::spin_up:
            check_finite(s, s.motion.omega0, "motion.omega0");
            check_positive(s, s.motion.spin_time, "motion.duration");
            break;
        case Motion::Kind::torque:
            check_finite(s, s.motion.tau0, "motion.tau0");
            check_positive(s, s.motion.torque_time, "motion.duration");
            break;
        case Motion::Kind::held:
        case Motion::Kind::step:
            check_angle(s, s.motion.angle, "motion.angle");
            break;
        case Motion::Kind::table:
        case Motion::Kind::torque_table:
            if (!s.motion.table) fail(s.path, "motion.file", expected("motion.file"), missing);
            break;
    }
    if (s.motion.kind != Motion::Kind::held) check_angle(s, s.motion.theta0, "motion.theta0");
    check_control(s);
}

/// The DOF counts and the axial coordinates' treatment.
void check_discretization(const Scene& s)
{
    // DOF counts: the key named is the first whose removal (a count of 0, ny 2) cures the problem.
    const VariantKey& key = s.variant;
    if (key.ny < 1) fail(s.path, "discretization.ny", expected("discretization.ny"), std::to_string(key.ny));
    if (key.nx < 0) fail(s.path, "discretization.nx", expected("discretization.nx"), std::to_string(key.nx));
    if (const std::string problem = s.key().dof_problem(); !problem.empty()) {
        const char* name = "discretization.ny";
        for (const auto& [count, key_name] : {std::pair{&VariantKey::nx, "discretization.nx"},
                                              {&VariantKey::nz, "discretization.nz"},
                                              {&VariantKey::nt, "discretization.nt"}}) {
            VariantKey without = s.key();
            without.*count = 0;
            if (without.dof_problem().empty()) name = key_name;
        }
        if (problem.rfind("order full", 0) == 0) name = "model.order";
        throw SceneError::with_detail(s.path, name, problem);
    }

    if (s.axial == Axial::quasi_static && key.nx == 0)
        fail(s.path, "model.axial", "\"dynamic\" for a scene without axial coordinates (quasi-static needs nx > 0)",
             "\"quasi-static\"");
}

/// The stepper's name and the tolerances.
void check_solver(const Scene& s)
{
    if (s.solver.stepper != automatic_stepper_word && !is_stepper(s.solver.stepper))
        fail(s.path, "solver.stepper", expected("solver.stepper"), "\"" + s.solver.stepper + "\"");
    check_positive(s, s.solver.rtol, "solver.rtol");
    if (!(s.solver.rtol < 1.0))  // a relative error of 100 % or more controls nothing
        fail(s.path, "solver.rtol", "a number in (0, 1) (relative tolerance)", shortest(s.solver.rtol));
    check_positive(s, s.solver.atol, "solver.atol");
    check_positive(s, s.solver.h0, "solver.h0");
}

/// The output times and the motion table's span.
void check_output(const Scene& s)
{
    check_positive(s, s.output.t_end, "output.t_end");
    if (!(s.output.dt_out > 0.0) || !(s.output.dt_out <= s.output.t_end))
        fail(s.path, "output.dt_out", expected("output.dt_out"),
             shortest(s.output.dt_out) + " with t_end = " + shortest(s.output.t_end));
    // A bound on the rows, checked before anything runs: beyond it the CSV would be gigabytes and the row
    // clock's integer arithmetic would overflow.
    if (s.output.t_end / s.output.dt_out > static_cast<double>(max_output_rows))
        fail(s.path, "output.dt_out",
             "at most " + std::to_string(max_output_rows) + " rows (output.t_end / output.dt_out)",
             shortest(s.output.t_end / s.output.dt_out) + " rows (t_end = " + shortest(s.output.t_end) +
                 ", dt_out = " + shortest(s.output.dt_out) + ")");

    // A table is not extrapolated: a run past its rows would make up a drive no one wrote down.
    const bool tabled = s.motion.kind == Motion::Kind::table || s.motion.kind == Motion::Kind::torque_table;
    if (const DriveTable* t = s.motion.table.get();
        tabled && (t->first_time() > 0.0 || t->last_time() < s.output.t_end))
        table_fail(s.path, printable(s.motion.table_file, 400),
                   "its rows cover t = " + shortest(t->first_time()) + " to " + shortest(t->last_time()) +
                       " s, the run needs t = 0 to output.t_end = " + shortest(s.output.t_end) +
                       " s (a table is not extrapolated: extend it or shorten the run)");
}

/// [rotor]: a count of blades, and arrays of one value per blade. A rotor's run has no sensitivities (the derivatives
/// by one parameter of all blades at once are not a blade's): refused, not run wrong.
void check_rotor(const Scene& s)
{
    const Rotor& r = s.rotor;
    if (r.blades < 1 || r.blades > max_blades) fail(s.path, "rotor.blades", expected("rotor.blades"), std::to_string(r.blades));
    const auto per_blade = [&](const std::vector<double>& v, const char* key) {
        if (!v.empty() && v.size() != static_cast<std::size_t>(r.blades))
            fail(s.path, key, expected(key),
                 "an array of " + std::to_string(v.size()) + " with rotor.blades = " + std::to_string(r.blades));
    };
    per_blade(r.pitch_offsets, "rotor.pitch_offsets");
    per_blade(r.tip_masses, "rotor.tip_masses");
    for (std::size_t b = 0; b < r.pitch_offsets.size(); ++b) {
        const double pitch = s.parameters.pitch + r.pitch_offsets[b];
        if (!std::isfinite(r.pitch_offsets[b]) || std::abs(pitch) > max_section_angle)
            fail(s.path, "rotor.pitch_offsets", expected("rotor.pitch_offsets"),
                 shortest(r.pitch_offsets[b]) + " for blade " + std::to_string(b + 1) + " (its pitch " +
                     shortest(pitch) + " rad)");
    }
    for (std::size_t b = 0; b < r.tip_masses.size(); ++b)
        if (!(r.tip_masses[b] >= 0.0) || !std::isfinite(r.tip_masses[b]))
            fail(s.path, "rotor.tip_masses", expected("rotor.tip_masses"),
                 shortest(r.tip_masses[b]) + " for blade " + std::to_string(b + 1));
    if (const double m = s.parameters.m_hub; !(m >= 0.0) || !std::isfinite(m))
        fail(s.path, "hub.mass", expected("hub.mass"), shortest(m));
    if (!r.tip_masses.empty() && s.parameters.m_tip != 0.0)
        fail(s.path, "rotor.tip_masses", "no tip.mass beside it (each blade's tip mass replaces it): remove one",
             "both");
    if (r.blades > 1 && !s.output.sensitivities.empty())
        fail(s.path, "output.sensitivities", "none for a rotor of several blades (rotor.blades > 1)",
             "\"" + s.output.sensitivities.front() + "\"");
    // The force summation places each section's mass on its reference axis: an offset centre of mass would move it.
    if (s.output.loads == OutputLoads::root && s.variant.extras.offsets)
        fail(s.path, "output.loads", "\"none\" for a blade whose sections' centre of mass is offset (cg_offst)",
             "\"root\"");
    // It takes the tip body as a point mass with J_tip about k, not as the rigid body in the blade's axes.
    if (s.output.loads == OutputLoads::root && s.key().extras.tip_body)
        fail(s.path, "output.loads",
             "\"none\" for a tip body with tip.inertia_flap, tip.inertia_twist or tip.offset (the force summation "
             "has no such body)",
             "\"root\"");
}

/// initial.state: a steady spin only where the scene has one at its initial rate, and no start but rest under
/// sensitivities, whose equations start from zero (an equilibrium's own derivatives by the parameters are not zero).
void check_initial(const Scene& s)
{
    if (s.initial == InitialState::rest) return;
    const char* key = "initial.state";
    const std::string word = "\"" + to_string(s.initial) + "\"";
    if (!s.output.sensitivities.empty())
        throw SceneError::with_detail(s.path, key,
                                      word + " with output.sensitivities: the sensitivities start from rest; use "
                                             "\"rest\" or no sensitivities");
    const double rate = s.initial_theta_dot();
    if (s.initial == InitialState::steady && !unsteady_spin(s.key(), s.parameters.packed(), rate).empty())
        throw SceneError::with_detail(
            s.path, key,
            word + " at the initial spin " + shortest(rate) +
                " rad/s under gravity in the plane of rotation: no steady state (the weight turns with the beam, the "
                "motion is periodic); use \"static\" (the equilibrium at the initial angle and rate, which the "
                "periodic motion leaves) or \"rest\"");
}

}  // namespace

void validate(const Scene& s)
{
    check_rotor(s);
    check_parameters(s);
    check_motion(s);
    // Before the variant's own checks: a sensitivity keeps its term (Scene::key), which the variant may refuse.
    check_sensitivities(s);
    check_discretization(s);
    check_solver(s);
    check_output(s);
    check_initial(s);
}

}  // namespace hubbeam
