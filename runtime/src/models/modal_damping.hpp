// Modal damping of a blade's own modes at rest (docs/model.md section 11.5; ElastoDyn's BldFlDmp, BldEdDmp): the
// constant matrix C = M_e Phi diag(2 zeta_k omega_k) Phi^T M_e and the model that adds -C qd to its forces.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>

namespace hubbeam {

/// C over blade's coordinates (nq x nq, zero outside the elastic fields): the modes of (K_e, M_e), the blade's
/// elastic stiffness and mass at rest (no spin, the state zero), mass-normalised; ratios.flap[k] given to the
/// (k+1)-th flapwise-dominated mode, ratios.edge[k] to the (k+1)-th edgewise-dominated one (a planar blade's in-plane
/// bending modes), by increasing frequency, and no other. Throws std::invalid_argument naming file and the key when
/// the blade has fewer modes of a kind than ratios for it.
Eigen::MatrixXd modal_damping_matrix(const Model& blade, const ModalDamping& ratios, const std::string& file);

/// blade with the scene's modal damping (blade itself where no ratio damps), its modes those of the blade at p
/// without gravity (a blade's own modes, as ElastoDyn's are): one blade of a scene's model (make_scene_model).
std::unique_ptr<Model> with_modal_damping(std::unique_ptr<Model> blade, const Scene& scene, const Parameters& p);

/// The modal damping matrix model adds to its forces as -C qd (nq x nq; a rotor's, each blade's scattered), or an
/// empty matrix for a model without.
Eigen::MatrixXd added_damping(const Model& model);

/// Whether model dissipates: its variant's damping or support (dissipates of its key) or modal damping.
bool dissipates(const Model& model);

}  // namespace hubbeam
