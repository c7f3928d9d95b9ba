// The generated kernels' table rows a model can run on: those built into this program, and the check every loader
// (built in or on demand) makes of a row before calling any of its kernels.
#pragma once

#include <hubbeam/on_demand.hpp>
#include <string>
#include <vector>

#include "variant.hpp"

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

}  // namespace hubbeam
