// The built-in table of generated variants and the check of a table row against the variant it should hold.
#include "on_demand/variant_rows.hpp"

#include <stdexcept>

#include "generated_abi.h"

namespace hubbeam {

std::string row_problem(const generated::Variant& v, const VariantKey& key)
{
    // A row from before versions were recorded starts with the name's pointer: its low half is no small number.
    if (v.abi_version < 1 || v.abi_version > 10000)
        return "was built by an older generator (one that recorded no interface version; this hubbeam reads " +
               std::to_string(generated::abi_version) + ")";
    if (v.abi_version != generated::abi_version)
        return "was built by an older generator (interface version " + std::to_string(v.abi_version) +
               ", this hubbeam reads " + std::to_string(generated::abi_version) + ")";
    if (v.name == nullptr || key.name() != v.name || v.nq != key.nq()) return "does not hold variant " + key.name();
    return {};
}

const generated::Variant* built_in_variant(const VariantKey& key)
{
    const std::string name = key.name();
    for (int i = 0; i < generated::variant_count; ++i) {
        const generated::Variant* v = generated::variants[i];
        if (v == nullptr || v->name == nullptr || name != v->name) continue;
        // Rows compiled into this program come from its own generator: a refusal means a stale build.
        if (const std::string why = row_problem(*v, key); !why.empty())
            throw std::logic_error("the built-in variant " + name + " " + why + ": rebuild hubbeam");
        return v;
    }
    return nullptr;
}

std::vector<std::string> generated_variant_names()
{
    std::vector<std::string> names;
    for (int i = 0; i < generated::variant_count; ++i)
        if (generated::variants[i] != nullptr) names.emplace_back(generated::variants[i]->name);
    return names;
}

}  // namespace hubbeam
