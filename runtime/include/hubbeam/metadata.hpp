// The metadata file beside every output of run, modes and linearize: a small JSON object saying where the output
// came from (hubbeam's version, the variant, the effective scene with its tables' content hashes, the stepper and
// tolerances, the summary, the wall time), so that a file found later can be trusted, re-made or read back
// (hubbeam.load in Python).
#pragma once

#include <hubbeam/config.hpp>
#include <hubbeam/simulate.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hubbeam {

/// The format's name and version, the value of the "format" key: a reader refuses another.
inline constexpr const char* metadata_format = "hubbeam-metadata 1";
/// The suffix appended to an output's whole name: run.csv -> run.csv.hubbeam.json. The output's own name (with its
/// extension) stays in it, so run.csv and run.npy, or an output and a file the user called run.json, never share one.
inline constexpr const char* metadata_suffix = ".hubbeam.json";

/// Where the metadata of output goes: output + metadata_suffix.
std::string metadata_path(const std::string& output);

/// A JSON object written key by key, in the order given: numbers in their shortest round-trip form (a non-finite
/// one as the string "inf", "-inf" or "nan", which JSON has no number for), strings escaped.
class JsonObject {
public:
    JsonObject& number(std::string_view key, double v);
    JsonObject& integer(std::string_view key, long long v);
    JsonObject& boolean(std::string_view key, bool v);
    JsonObject& text(std::string_view key, std::string_view v);
    JsonObject& texts(std::string_view key, const std::vector<std::string>& v);
    JsonObject& numbers(std::string_view key, const std::vector<double>& v);
    /// A nested object or any other JSON value, as text.
    JsonObject& raw(std::string_view key, const std::string& json);
    /// The object, on several lines (one per key, nested objects indented).
    std::string str() const;

private:
    std::vector<std::pair<std::string, std::string>> entries_;
};

/// The parts every command's metadata shares: format, command, hubbeam's version (HUBBEAM_VERSION) and the generator's,
/// the scene's file, the effective scene as {"table": {"key": value}} (effective_scene), and each table the scene reads
/// by path and SHA-256 of its content.
JsonObject scene_metadata(const std::string& command, const Scene& scene);

/// A run's metadata: scene_metadata, the output's name (as given, and its rows and columns), the fields CSV's name
/// where one was written, the variant, the stepper
/// and its tolerances, and the summary's fields under "summary" (those of the Python Result, with the summary's text).
std::string run_metadata(const Scene& scene, const RunSummary& summary, const std::string& output,
                         const std::string& columns, long rows, const std::string& fields = "");

/// JSON of summary's fields as the Python module's Result holds them, and the summary's text.
std::string summary_json(const RunSummary& summary, const Scene& scene);

class OutputFile;
/// The metadata file of an output, written atomically (OutputFile: beside it, renamed over it) and opened with the
/// output itself, before anything is computed: its lock is taken
/// and its temporary file made at once, so a sidecar that cannot be written (a planted link as its lock, another
/// hubbeam writing it) refuses the command up front, never after the run has put a new output beside an old sidecar.
class MetadataFile {
public:
    /// Opens metadata_path(output); throws OutputRefused or std::runtime_error as OutputFile's constructor does.
    explicit MetadataFile(const std::string& output);
    ~MetadataFile();
    MetadataFile(const MetadataFile&) = delete;
    MetadataFile& operator=(const MetadataFile&) = delete;

    const std::string& path() const { return path_; }
    /// Writes json and puts the file in place; returns "" or one line saying what failed. Once only.
    std::string write(const std::string& json);

private:
    std::string path_;
    std::unique_ptr<OutputFile> file_;
};

}  // namespace hubbeam
