// The generated kernels of a variant (compiled into this build or loaded on demand) behind the Model interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <hubbeam/model.hpp>
#include "on_demand/variant_rows.hpp"

namespace hubbeam {

namespace generated {
struct Variant;
}

/// A Model over a variant's kernels (built in or loaded from the cache); origin says which, for the summary.
std::unique_ptr<Model> make_generated_model(const VariantKey& key, const generated::Variant& v, const Parameters& p,
                                            std::string origin);

}  // namespace hubbeam
