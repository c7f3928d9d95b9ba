// Model selection: the generated kernels of a variant compiled into this build, or the hand-assembled
// fallback for variants that were not generated.
#include <stdexcept>
#include <string>
#include <vector>

#include "generated_abi.h"
#include "model.hpp"

namespace hubbeam {

namespace {

const WordTable<ModelSource, 3> sources = {
    {ModelSource::automatic, "auto"}, {ModelSource::generated, "generated"}, {ModelSource::assembled, "assembled"}};

class GeneratedModel final : public Model {
public:
    GeneratedModel(const VariantKey& key, const generated::Variant& v, const Parameters& p)
        : Model(key), v_(v), c_(static_cast<std::size_t>(v.ncoeff))
    {
        const auto packed = p.packed();
        v_.coefficients(packed.data(), c_.data());
    }

    const char* source() const override { return "generated"; }
    bool mass_is_constant() const override { return v_.mass_constant; }

    void mass(const HubInput& u, const double* q, double* M) const override { call(v_.mass, u, q, q, M); }
    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        call(v_.forces, u, q, qd, Q);
    }
    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        double e[4];
        call(v_.energy, u, q, qd, e);
        return {e[0], e[1], e[2], e[3]};
    }
    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        double h;
        call(v_.momentum, u, q, qd, &h);
        return h;
    }

private:
    void call(generated::Kernel k, const HubInput& u, const double* q, const double* qd, double* out) const
    {
        const double uu[3] = {u.tau, u.theta_dot, u.theta_ddot};
        k(c_.data(), uu, q, qd, out);
    }

    const generated::Variant& v_;
    std::vector<double> c_;
};

}  // namespace

std::string to_string(ModelSource v) { return word_of(v, sources); }
bool parse(std::string_view w, ModelSource& v) { return parse_word(w, sources, v); }
template <> std::vector<std::string> words<ModelSource>() { return all_words(sources); }

std::unique_ptr<Model> make_generated_model(const VariantKey& key, const Parameters& p)
{
    const std::string name = key.name();
    for (int i = 0; i < generated::variant_count; ++i) {
        const generated::Variant* v = generated::variants[i];
        if (v != nullptr && name == v->name) return std::make_unique<GeneratedModel>(key, *v, p);
    }
    return nullptr;
}

std::unique_ptr<Model> make_model(const VariantKey& key, const Parameters& p, ModelSource source)
{
    if (const std::string why = key.dof_problem(); !why.empty()) throw std::invalid_argument(why);
    if (source != ModelSource::assembled) {
        if (auto m = make_generated_model(key, p)) return m;
        if (source == ModelSource::generated)
            throw std::invalid_argument("variant " + key.name() +
                                        " is not generated in this build: add it to generator/variants.txt, "
                                        "or use the hand-assembled model (source = \"assembled\")");
    }
    return make_assembled_model(key, p);
}

}  // namespace hubbeam
