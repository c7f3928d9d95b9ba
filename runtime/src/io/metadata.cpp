// The metadata beside an output (metadata.hpp): a hand-written JSON writer (the library links no JSON library, and
// the object is flat but for the scene), the effective scene, the tables' hashes and the summary's fields.
#include <hubbeam/metadata.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <hubbeam/on_demand.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/scene_print.hpp>
#include <hubbeam/shortest.hpp>

#include "io/scene_io.hpp"
#include "on_demand/sha256.hpp"

namespace hubbeam {

namespace {

std::string json_number(double v)
{
    if (!std::isfinite(v)) return quoted_string(toml_number(v), Quoting::json);
    return shortest(v);
}

/// Appends text to out indented by two spaces after each newline: a nested object inside its parent. A line at a
/// time, for the scene's objects nest the effective scene's twice.
void append_indented(std::string& out, std::string_view text)
{
    for (std::size_t start = 0;;) {
        const std::size_t newline = text.find('\n', start);
        if (newline == std::string_view::npos) {
            out.append(text.substr(start));
            return;
        }
        out.append(text.substr(start, newline + 1 - start)).append("  ");
        start = newline + 1;
    }
}

/// The SHA-256 of a table's file, or "" where it cannot be read (it was read moments ago to load the scene).
std::string file_sha256(const std::string& path)
{
    const std::string bytes = scene_io::read_file(path, max_table_bytes);
    Sha256 h;
    h.add(bytes);
    return h.hex();
}

}  // namespace

std::string metadata_path(const std::string& output)
{
    return output + metadata_suffix;
}

JsonObject& JsonObject::number(std::string_view key, double v)
{
    entries_.emplace_back(key, json_number(v));
    return *this;
}

JsonObject& JsonObject::integer(std::string_view key, long long v)
{
    entries_.emplace_back(key, std::to_string(v));
    return *this;
}

JsonObject& JsonObject::boolean(std::string_view key, bool v)
{
    entries_.emplace_back(key, v ? "true" : "false");
    return *this;
}

JsonObject& JsonObject::text(std::string_view key, std::string_view v)
{
    entries_.emplace_back(key, quoted_string(v, Quoting::json));
    return *this;
}

JsonObject& JsonObject::texts(std::string_view key, const std::vector<std::string>& v)
{
    std::string list = "[";
    for (std::size_t i = 0; i < v.size(); ++i) list += (i ? ", " : "") + quoted_string(v[i], Quoting::json);
    entries_.emplace_back(key, list + "]");
    return *this;
}

JsonObject& JsonObject::numbers(std::string_view key, const std::vector<double>& v)
{
    std::string list = "[";
    for (std::size_t i = 0; i < v.size(); ++i) list += (i ? ", " : "") + json_number(v[i]);
    entries_.emplace_back(key, list + "]");
    return *this;
}

JsonObject& JsonObject::raw(std::string_view key, const std::string& json)
{
    entries_.emplace_back(key, json);
    return *this;
}

std::string JsonObject::str() const
{
    std::size_t size = 3;
    for (const auto& [key, value] : entries_) size += key.size() + 2 * value.size() + 8;
    std::string out;
    out.reserve(size);
    out += '{';
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        out.append(i ? ",\n  " : "\n  ").append(quoted_string(entries_[i].first, Quoting::json)).append(": ");
        append_indented(out, entries_[i].second);
    }
    out.append("\n}");
    return out;
}

JsonObject scene_metadata(const std::string& command, const Scene& scene)
{
    // The effective scene, table by table in the key table's order.
    std::vector<std::pair<std::string, JsonObject>> tables;
    for (const SceneValue& v : effective_scene(scene)) {
        const std::string table = v.key.substr(0, v.key.find('.')), leaf = v.key.substr(v.key.find('.') + 1);
        if (tables.empty() || tables.back().first != table) tables.emplace_back(table, JsonObject{});
        JsonObject& t = tables.back().second;
        switch (v.kind) {
            case SceneValue::Kind::number:
                t.number(leaf, v.number);
                break;
            case SceneValue::Kind::integer:
                t.integer(leaf, v.integer);
                break;
            case SceneValue::Kind::text:
                t.text(leaf, v.text);
                break;
            case SceneValue::Kind::numbers:
                t.numbers(leaf, v.numbers);
                break;
        }
    }
    JsonObject effective;
    for (const auto& [name, t] : tables) effective.raw(name, t.str());
    // A table by its content: the same name may hold other rows tomorrow.
    JsonObject files;
    for (const auto& [key, file] : scene.tables)
        files.raw(key, JsonObject{}
                           .text("path", std::filesystem::absolute(file).lexically_normal().string())
                           .text("sha256", file_sha256(file))
                           .str());
    JsonObject out;
    out.text("format", metadata_format)
        .text("command", command)
        .text("hubbeam_version", HUBBEAM_VERSION)
        .text("generator_version", generator_version())
        .text("scene_file", scene.path)
        .text("variant", scene.key().name())
        .raw("scene", effective.str())
        .raw("tables", files.str());
    if (scene.control && scene.control->law) out.text("torque_law", "a Python callable (torque=): not in the scene");
    return out;
}

std::string summary_json(const RunSummary& s, const Scene& scene)
{
    return JsonObject{}
        .text("variant", s.variant)
        .text("source", s.source)
        .text("algebra", s.algebra)
        .text("stepper", s.stepper)
        .text("stepper_why", s.stepper_why)
        .text("newton", s.newton)
        .boolean("completed", s.completed)
        .text("failure", s.failure)
        .number("t_reached", s.t_reached)
        .number("max_abs_tip_uy", s.max_abs_tip_uy)
        .number("t_steady", s.t_steady)
        .number("jacobi_drift", s.jacobi_drift)
        .number("vibration_energy", s.vibration_energy)
        .boolean("energy_balance", s.energy_balance)
        .text("monitor_off", s.monitor_off)
        .number("estimated_error", s.estimated_error)
        .text("error_column", s.error_column)
        .text("error_from", s.error_from)
        .integer("steps", s.steps)
        .integer("rejected_steps", s.rejected_steps)
        .integer("rhs_evals", s.rhs_evals)
        .integer("jacobian_evals", s.jacobian_evals)
        .number("wall_seconds", s.wall_seconds)
        .number("check_wall_seconds", s.check_wall_seconds)
        .text("summary_text", format_summary(s, scene))
        .str();
}

std::string run_metadata(const Scene& scene, const RunSummary& summary, const std::string& output,
                         const std::string& columns, long rows, const std::string& fields)
{
    JsonObject out = scene_metadata("run", scene);
    std::vector<std::string> names;
    for (std::size_t start = 0; start <= columns.size();) {
        const std::size_t comma = std::min(columns.find(',', start), columns.size());
        names.push_back(columns.substr(start, comma - start));
        start = comma + 1;
    }
    out.text("output", std::filesystem::path(output).filename().string()).texts("columns", names).integer("rows", rows);
    if (!fields.empty()) out.text("fields", std::filesystem::path(fields).filename().string());
    out.raw("solver", JsonObject{}
                          .text("stepper", summary.stepper)
                          .text("asked", scene.solver.stepper)
                          .text("why", summary.stepper_why)
                          .number("rtol", scene.solver.rtol)
                          .number("atol", scene.solver.atol)
                          .number("h0", scene.solver.h0)
                          .text("error_check", to_string(scene.solver.error_check))
                          .text("sensitivity_error_control", to_string(scene.solver.sensitivity_error_control))
                          .number("check_rtol", summary.check_rtol)
                          .number("check_atol", summary.check_atol)
                          .str())
        .number("wall_seconds", summary.wall_seconds + summary.check_wall_seconds)
        .raw("summary", summary_json(summary, scene));
    return out.str() + "\n";
}

MetadataFile::MetadataFile(const std::string& output)
    : path_(metadata_path(output)), file_(std::make_unique<OutputFile>(path_))
{
}

MetadataFile::~MetadataFile() = default;

std::string MetadataFile::write(const std::string& json)
{
    if (!file_) throw std::logic_error("MetadataFile::write called twice");
    std::string why;
    if (const int error = file_->write(json); error != 0) why = path_ + ": cannot write: " + std::strerror(error);
    else if (const std::string failed = file_->commit(); !failed.empty()) why = path_ + ": " + failed;
    file_.reset();  // removes the temporary file if the write or the commit failed
    return why;
}

}  // namespace hubbeam
