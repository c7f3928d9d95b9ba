// The generated kernels of a variant (compiled into this build or loaded on demand) behind the Model interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <hubbeam/model.hpp>

namespace hubbeam {

namespace generated {
struct Variant;
}

/// Why the table row v cannot serve key, or empty: a row of another interface version (generated_abi.h's
/// abi_version, which a row from an older generator does not carry) or of another variant. Checked by every
/// loader before any of the row's kernels is called.
std::string row_problem(const generated::Variant& v, const VariantKey& key);

/// The variant of key generated into this build, or nullptr; throws std::logic_error if its row is refused.
const generated::Variant* built_in_variant(const VariantKey& key);

/// A Model over a variant's kernels (built in or loaded from the cache); origin says which, for the summary.
std::unique_ptr<Model> make_generated_model(const VariantKey& key, const generated::Variant& v, const Parameters& p,
                                            std::string origin);

/// The names of the variants generated into this build, in registry order.
std::vector<std::string> generated_variant_names();

}  // namespace hubbeam
