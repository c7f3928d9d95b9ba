// Model selection between the generated variants of this build and the hand-assembled fallback.
#include <chrono>
#include <cstdio>
#include <hubbeam/make_model.hpp>
#include <hubbeam/on_demand.hpp>
#include <stdexcept>

#include "models/assembled/assembled.hpp"
#include "models/generated_model.hpp"

namespace hubbeam {

std::unique_ptr<Model> make_model(const VariantKey& key, const Parameters& p, ModelSource source, const ModelNote& note)
{
    if (const std::string why = key.dof_problem(); !why.empty()) throw std::invalid_argument(why);
    // A profile variant integrates the table against its basis; a table it would not read is a caller's mistake.
    if (key.extras.profile()) {
        if (const std::string why = stations_problem(p.stations); !why.empty())
            throw std::invalid_argument("the profile's stations: " + why);
        const std::size_t values = profile_value_count(key.out_of_plane()) * p.stations.size();
        if (p.profile.size() != values)
            throw std::invalid_argument("the parameters hold " + std::to_string(p.profile.size()) +
                                        " profile values at " + std::to_string(p.stations.size()) +
                                        " stations, the variant " + key.name() + " needs " + std::to_string(values));
        const std::size_t offsets = key.extras.offsets ? section_offset_count * p.stations.size() : 0;
        if (p.offsets.size() != offsets)
            throw std::invalid_argument("the parameters hold " + std::to_string(p.offsets.size()) +
                                        " section offsets at " + std::to_string(p.stations.size()) +
                                        " stations, the variant " + key.name() + " needs " + std::to_string(offsets));
    } else if (!p.stations.empty() || !p.profile.empty() || !p.offsets.empty()) {
        throw std::invalid_argument("the parameters hold a profile, the variant " + key.name() + " has none");
    }
    if (source == ModelSource::assembled) return make_assembled_model(key, p);
    if (const generated::Variant* v = built_in_variant(key)) return make_generated_model(key, *v, p, "built in");
    if (const generated::Variant* v = load_cached_variant(key)) return make_generated_model(key, *v, p, "cached");
    if (const std::string why = on_demand_problem(); !why.empty()) {
        if (source == ModelSource::generated)
            throw std::invalid_argument("variant " + key.name() +
                                        " is not built in and cannot be compiled on demand: " + why +
                                        "; or use the hand-assembled model (source = \"assembled\")");
        if (key.order == Order::full)
            throw std::invalid_argument("order full has no hand-assembled form, and variant " + key.name() +
                                        " cannot be compiled on demand: " + why);
        auto m = make_assembled_model(key, p);
        const std::string fallback = "hand-assembled, " + why;
        if (note) note("variant " + key.name() + " runs on the hand-assembled path: " + why);
        m->set_origin(fallback);
        return m;
    }
    const auto start = std::chrono::steady_clock::now();
    const generated::Variant* v = compile_variant(key, note);
    char took[64];
    std::snprintf(took, sizeof took, "compiled now in %.1f s",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return make_generated_model(key, *v, p, took);
}

}  // namespace hubbeam
