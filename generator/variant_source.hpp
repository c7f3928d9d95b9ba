// Stage "specialise + emit" for one variant: from a VariantKey to the complete C++ source of its kernels
// and its table row; and the registry of all generated variants.
#pragma once

#include <string>
#include <vector>

#include "emit.hpp"
#include "variant.hpp"

namespace hubbeam::gen {

/// The generated source file for one variant (banner, kernels, table row).
std::string variant_source(const VariantKey& key, const EmitOptions& options = {});

/// The entry point of a variant's source built as a shared object: extern "C" hubbeam_variant() returns its row.
std::string module_entry_source(const std::string& name);

/// The text of model/generated_abi.h this generator was built with: written beside an on-demand source, so that
/// compiling it needs no header from a source or install tree, and the row's layout is the one its version names.
std::string abi_header();

/// The registry source listing the named variants.
std::string registry_source(const std::vector<std::string>& names);

}  // namespace hubbeam::gen
