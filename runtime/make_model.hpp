// Model selection: which implementation serves a variant (generated kernels of this build, or the
// hand-assembled docs/model.md section 5), as a scene's model.source asks.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "model.hpp"

namespace hubbeam {

enum class ModelSource { automatic, generated, assembled };
/// Words "auto", "generated", "assembled" (scene key model.source, option --source).
std::string to_string(ModelSource);
bool parse(std::string_view, ModelSource&);
template <> std::vector<std::string> words<ModelSource>();

/// automatic: generated if available, else assembled. Throws std::invalid_argument if none can serve.
std::unique_ptr<Model> make_model(const VariantKey& key, const Parameters& p,
                                  ModelSource source = ModelSource::automatic);

}  // namespace hubbeam
