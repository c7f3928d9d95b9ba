// A test's model that wraps another and forwards the equations to it: what a test changes of a model (its derivatives
// hidden, its mass pattern) it overrides alone.
#pragma once

#include <hubbeam/model.hpp>

#include <memory>
#include <utility>

namespace hubbeam::test {

/// Forwards Model's required members to the wrapped model; everything optional keeps Model's default.
class ForwardingModel : public Model {
public:
    explicit ForwardingModel(std::unique_ptr<Model> inner) : Model(inner->key()), inner_(std::move(inner)) {}
    const char* source() const override { return inner_->source(); }
    bool mass_is_constant() const override { return inner_->mass_is_constant(); }
    void mass(const HubInput& u, const double* q, double* M) const override { inner_->mass(u, q, M); }
    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        inner_->forces(u, q, qd, Q);
    }
    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        return inner_->energy(u, q, qd);
    }
    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        return inner_->momentum(u, q, qd);
    }
    Tip tip(const double* q) const override { return inner_->tip(q); }

protected:
    const Model& inner() const { return *inner_; }

private:
    std::unique_ptr<Model> inner_;
};

}  // namespace hubbeam::test
