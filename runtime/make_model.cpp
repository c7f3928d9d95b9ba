// Model selection between the generated variants of this build and the hand-assembled fallback.
#include "make_model.hpp"

#include <stdexcept>

#include "assembled.hpp"
#include "generated_model.hpp"

namespace hubbeam {

namespace {

const WordTable<ModelSource, 3> sources = {
    {ModelSource::automatic, "auto"}, {ModelSource::generated, "generated"}, {ModelSource::assembled, "assembled"}};

}  // namespace

std::string to_string(ModelSource v) { return word_of(v, sources); }
bool parse(std::string_view w, ModelSource& v) { return parse_word(w, sources, v); }
template <> std::vector<std::string> words<ModelSource>() { return all_words(sources); }

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
