// Model: the one interface the integrator sees (mass matrix, generalized forces, energy, momentum of a
// variant), with its two implementations: generated kernels and the hand-assembled MODEL.md section 5.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "variant.hpp"

namespace hubbeam {

/// Physical parameters (SI). p = (L, rho, S, I, E, a, J_oh) is the order generated code takes.
struct Parameters {
    double L = 8.0, rho = 2.7667e3, S = 7.2968e-5, I = 8.2189e-9, E = 6.8952e10, a = 0.0, J_oh = 30.0;
    std::array<double, 7> packed() const { return {L, rho, S, I, E, a, J_oh}; }
};

/// The drive at one instant, u = (tau, theta_dot, theta_ddot): torque variants read tau, prescribed ones
/// theta_dot and theta_ddot.
struct HubInput {
    double tau = 0.0, theta_dot = 0.0, theta_ddot = 0.0;
};

/// Kinetic energy split by degree in the rates qd (T = T2 + T1 + T0) and potential energy U.
struct Energy {
    double T2 = 0.0, T1 = 0.0, T0 = 0.0, U = 0.0;
    double kinetic() const { return T2 + T1 + T0; }
};

enum class ModelSource { automatic, generated, assembled };
/// Words "auto", "generated", "assembled" (scene key model.source, option --source).
std::string to_string(ModelSource);
bool parse(std::string_view, ModelSource&);
template <> std::vector<std::string> words<ModelSource>();

class Model {
public:
    virtual ~Model() = default;
    const VariantKey& key() const { return key_; }
    int nq() const { return key_.nq(); }
    /// "generated" or "assembled".
    virtual const char* source() const = 0;
    /// True when M does not depend on q (prescribed rotation, first and zero order): factor it once.
    virtual bool mass_is_constant() const = 0;
    /// M(q), nq x nq row-major.
    virtual void mass(const HubInput& u, const double* q, double* M) const = 0;
    /// Q(t, q, qd) such that M qdd = Q.
    virtual void forces(const HubInput& u, const double* q, const double* qd, double* Q) const = 0;
    virtual Energy energy(const HubInput& u, const double* q, const double* qd) const = 0;
    /// Angular momentum about the axis, dT/dtheta_dot.
    virtual double momentum(const HubInput& u, const double* q, const double* qd) const = 0;

protected:
    explicit Model(const VariantKey& key) : key_(key) {}

private:
    VariantKey key_;
};

/// The generated variant for key, or nullptr if it was not generated into this build.
std::unique_ptr<Model> make_generated_model(const VariantKey& key, const Parameters& p);
/// MODEL.md section 5 assembled numerically; orders zero and first only (throws std::invalid_argument).
std::unique_ptr<Model> make_assembled_model(const VariantKey& key, const Parameters& p);
/// automatic: generated if available, else assembled. Throws std::invalid_argument if none can serve.
std::unique_ptr<Model> make_model(const VariantKey& key, const Parameters& p,
                                  ModelSource source = ModelSource::automatic);

}  // namespace hubbeam
