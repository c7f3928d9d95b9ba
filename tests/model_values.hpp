// A model's values at a test state as Eigen objects: M, Q, dQ/dtheta and the energies, for tests that compare models.
#pragma once

#include <Eigen/Dense>

#include <hubbeam/model.hpp>
#include "random_state.hpp"

namespace hubbeam::test {

/// M(q), read row-major.
inline Eigen::MatrixXd mass_of(const Model& model, const State& s)
{
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(model.nq(), model.nq());
    model.mass(s.u, s.q.data(), M.data());
    return M;
}

/// Q(u, q, qd).
inline Eigen::VectorXd forces_of(const Model& model, const State& s)
{
    Eigen::VectorXd Q(model.nq());
    model.forces(s.u, s.q.data(), s.qd.data(), Q.data());
    return Q;
}

/// dQ/dtheta of a prescribed angle (Model::forces_theta).
inline Eigen::VectorXd forces_theta_of(const Model& model, const State& s)
{
    Eigen::VectorXd d(model.nq());
    model.forces_theta(s.u, s.q.data(), s.qd.data(), d.data());
    return d;
}

/// (T2, T1, T0, U).
inline Eigen::Vector4d energy_of(const Model& model, const State& s)
{
    const Energy e = model.energy(s.u, s.q.data(), s.qd.data());
    return {e.T2, e.T1, e.T0, e.U};
}

}  // namespace hubbeam::test
