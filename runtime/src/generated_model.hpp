// The generated kernels of a variant (compiled into this build or loaded on demand) behind the Model interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model.hpp"

namespace hubbeam {

namespace generated {
struct Variant;
}

/// The variant of key generated into this build, or nullptr.
const generated::Variant* built_in_variant(const VariantKey& key);

/// A Model over a variant's kernels (built in or loaded from the cache); origin says which, for the summary.
std::unique_ptr<Model> make_generated_model(const VariantKey& key, const generated::Variant& v, const Parameters& p,
                                            std::string origin);

/// The names of the variants generated into this build, in registry order.
std::vector<std::string> generated_variant_names();

}  // namespace hubbeam
