// The generated kernels of a variant compiled into this build, behind the Model interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model.hpp"

namespace hubbeam {

/// The generated variant for key, or nullptr if it was not generated into this build.
std::unique_ptr<Model> make_generated_model(const VariantKey& key, const Parameters& p);

/// The names of the variants generated into this build, in registry order.
std::vector<std::string> generated_variant_names();

}  // namespace hubbeam
