// A run's columns by name (simulate.hpp): the optional columns a scene has, the sensitivities' derivative columns,
// and the CSV header made of them.
#include <hubbeam/simulate.hpp>

#include <iterator>
#include <string>
#include <vector>

#include <hubbeam/config.hpp>
#include "dynamics/integrate.hpp"
#include "terms.hpp"

namespace hubbeam {

ColumnSet optional_columns_of(const Scene& scene)
{
    const Control* control = scene.controller();
    const VariantKey key = scene.key();
    const Auxiliary aux = Auxiliary::of(key, scene.damped(), control, &scene.parameters, scene.wants({"ki"}));
    const bool torque = key.drive == Drive::torque && (control != nullptr || scene.damped());
    const bool hub = key.extras.hub;
    const bool has[] = {key.nz > 0,   key.nt > 0,     torque,   control != nullptr && !control->law,
                        aux.integral, aux.dissipated, aux.work, hub,
                        hub,          hub,            hub};
    static_assert(std::size(has) == optional_width);
    ColumnSet set;
    for (std::size_t i = 0; i < optional_width; ++i)
        if (has[i]) set.bits |= 1u << i;
    set.derived = sensitivity_columns(scene.output.sensitivities, key);
    set.blades = scene.rotor.blades;
    set.loads = scene.output.loads == OutputLoads::root;
    return set;
}

std::vector<std::string> sensitivity_outputs_of(const VariantKey& key)
{
    std::vector<std::string> outputs(std::begin(sensitivity_outputs), std::end(sensitivity_outputs));
    if (key.nz > 0) outputs.emplace_back(blade_sensitivity_outputs[0]);
    if (key.nt > 0) outputs.emplace_back(blade_sensitivity_outputs[1]);
    return outputs;
}

std::vector<std::string> sensitivity_columns(const std::vector<std::string>& parameters, const VariantKey& key)
{
    std::vector<std::string> names;
    const std::vector<std::string> outputs = sensitivity_outputs_of(key);
    for (const std::string& p : parameters)
        for (const std::string& o : outputs) names.push_back("d_" + o + "/d_" + p);
    return names;
}

std::vector<std::string> row_column_names(const ColumnSet& set)
{
    std::vector<std::string> names;
    // A rotor's tip columns are each blade's: blade 1's in their places, suffixed "_1", the others' after.
    const auto blade = [&](const char* name, int b) {
        const std::string n = name;
        return set.blades > 1 && n.rfind("tip_", 0) == 0 ? n + "_" + std::to_string(b) : n;
    };
    for (const RowColumn& c : row_columns) names.push_back(blade(c.name, 1));
    for (std::size_t i = 0; i < optional_width; ++i)
        if (set.has(i)) names.push_back(blade(optional_columns[i].name, 1));
    for (int b = 2; b <= set.blades; ++b)
        for (const char* tip : {"tip_uy", "tip_ux1", "tip_ux", "tip_uz", "tip_phi"})
            if ((std::string(tip) != "tip_uz" || set.has(0)) && (std::string(tip) != "tip_phi" || set.has(1)))
                names.push_back(blade(tip, b));
    for (int b = 1; set.loads && b <= set.blades; ++b)
        for (const LoadColumn& c : root_load_columns)
            names.push_back(set.blades > 1 ? std::string(c.name) + "_" + std::to_string(b) : std::string(c.name));
    names.insert(names.end(), set.derived.begin(), set.derived.end());
    return names;
}

std::string row_header(const ColumnSet& set)
{
    std::string h;
    for (const std::string& name : row_column_names(set)) h += (h.empty() ? "" : ",") + name;
    return h;
}

const char* row_header()
{
    static const std::string header = [] {
        std::string h;
        for (const RowColumn& c : row_columns) {
            if (!h.empty()) h += ',';
            h += c.name;
        }
        return h;
    }();
    return header.c_str();
}

}  // namespace hubbeam
