// A run's columns by name (simulate.hpp): the optional columns a scene has, the sensitivities' derivative columns,
// and the CSV header made of them.
#include <hubbeam/simulate.hpp>

#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <hubbeam/config.hpp>
#include <hubbeam/model.hpp>
#include "dynamics/integrate.hpp"
#include "terms.hpp"

namespace hubbeam {

namespace {

/// Whether set's rows carry the column name: a column of row_columns always, an optional one where set has it.
bool has_column(const ColumnSet& set, std::string_view name)
{
    for (std::size_t i = 0; i < optional_width; ++i)
        if (name == optional_columns[i].name) return set.has(i);
    return true;
}

constexpr bool same(const char* a, const char* b) { return std::string_view(a) == b; }
// The row's tip columns are tip_values in its order: blade 1's where the rows have them, the other blades' after.
static_assert(same(row_columns[3].name, tip_values[0].name) && same(row_columns[4].name, tip_values[1].name) &&
              same(row_columns[5].name, tip_values[2].name) && same(optional_columns[0].name, tip_values[3].name) &&
              same(optional_columns[1].name, tip_values[4].name));

}  // namespace

std::size_t ColumnSet::blade_columns() const
{
    std::size_t n = 0;
    for (const TipValue& v : tip_values) n += has_column(*this, v.name) ? 1 : 0;
    return n;
}

ColumnSet optional_columns_of(const Scene& scene)
{
    const Control* control = scene.controller();
    const VariantKey key = scene.key();
    const Auxiliary aux = Auxiliary::of(key, scene.damped(), control, &scene.parameters, scene.wants({"ki"}));
    const bool torque = key.drive == Drive::torque && (control != nullptr || scene.damped());
    const bool hub = coordinate_layout(key).find(FieldKind::hub_x) != nullptr;  // a moving hub's x_h, y_h
    const bool has[] = {has_tip_value(key, tip_values[3]),
                        has_tip_value(key, tip_values[4]),
                        torque,
                        control != nullptr && !control->law,
                        aux.integral,
                        aux.dissipated,
                        aux.work,
                        hub,
                        hub,
                        hub,
                        hub};
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
    for (const TipValue& v : tip_values)
        if (has_tip_value(key, v)) outputs.emplace_back(v.name);
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
        for (const TipValue& v : tip_values)
            if (has_column(set, v.name)) names.push_back(blade(v.name, b));
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
