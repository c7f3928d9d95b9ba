// What a scene reads: the key table's file keys (SceneKey::Kind::file), the files scene_files lists and the inputs
// scene_inputs names for every writer's checks, enumerated over the table so that a new file key cannot be left out.
#include <catch2/catch.hpp>

#include <algorithm>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/scene.hpp>
#include <map>
#include <string>
#include <vector>

#include "io/scene_io.hpp"

using namespace hubbeam;

namespace {

std::string case_file(const std::string& name) { return std::string(HUBBEAM_SOURCE_DIR) + "/cases/" + name; }

/// For each file key, a scene of cases/ that sets it and the file it names there. A file key added to the key table
/// needs an entry here (the test below says so): that is what makes it an input of every writer, tested.
const std::map<std::string, std::pair<std::string, std::string>> scene_setting = {
    {"beam.profile", {"profile_blade.toml", "profile_blade.csv"}},
    {"beam.blade_file", {"blade_from_file.toml", "blade_sections.dat"}},
    {"motion.file", {"table_spinup.toml", "table_spinup.csv"}},
};

}  // namespace

TEST_CASE("every file key of the key table is an input of a scene that sets it", "[scene][output]")
{
    const std::vector<const SceneKey*> keys = file_keys();
    REQUIRE(keys.size() >= 3);
    for (const SceneKey* key : keys) {
        INFO(key->name);
        CHECK(key->max_bytes > 0);  // the reader's cap, which the Python module's sweeps read files with
        const auto setting = scene_setting.find(key->name);
        if (setting == scene_setting.end()) FAIL("a file key with no scene that sets it in this test: add one");
        const std::string scene_path = case_file(setting->second.first), file = case_file(setting->second.second);
        const Scene scene = load_scene(scene_path);
        const std::vector<NamedPath> inputs = scene_inputs(scene);
        const auto named = std::find_if(inputs.begin(), inputs.end(),
                                        [&](const NamedPath& p) { return p.name == "the scene's " + std::string(key->name); });
        REQUIRE(named != inputs.end());
        CHECK(same_file(named->path, file));
        CHECK(same_file(inputs.front().path, scene_path));
        CHECK(inputs.front().name == "the scene itself");
        // A writer asked to replace that file is refused, naming the key.
        CHECK_THROWS_WITH(check_outputs(inputs, {{file, "-o"}}),
                          Catch::StartsWith("-o: expected a file other than the scene's " + std::string(key->name)));
    }
}

TEST_CASE("the file keys and their caps are the readers'", "[scene]")
{
    // Each reader's own limit: what a sweep reads of a file to key its points is what the core reads of it.
    CHECK(scene_key("beam.profile").kind == SceneKey::Kind::file);
    CHECK(scene_key("beam.profile").max_bytes == scene_io::max_profile_bytes);
    CHECK(scene_key("beam.blade_file").kind == SceneKey::Kind::file);
    CHECK(scene_key("beam.blade_file").max_bytes == max_blade_file_bytes);
    CHECK(scene_key("motion.file").kind == SceneKey::Kind::file);
    CHECK(scene_key("motion.file").max_bytes == max_table_bytes);
    CHECK(scene_key("output.file").kind == SceneKey::Kind::text);  // an output, not an input
    for (const SceneKey& k : scene_keys())
        if (k.kind != SceneKey::Kind::file) CHECK(k.max_bytes == 0);
}

TEST_CASE("scene_files lists a scene's files by key without reading them or checking the rest", "[scene]")
{
    const std::string scene_path = case_file("blade_from_file.toml");
    const std::string text = scene_io::read_file(scene_path);
    const auto files = scene_files(text, scene_path);
    REQUIRE(files.size() == 1);
    CHECK(files[0].first == "beam.blade_file");
    CHECK(same_file(files[0].second, case_file("blade_sections.dat")));
    // A scene refused for another key (a negative Ny) still names its files: a sweep keys such a point by them too.
    CHECK_THROWS_AS(parse_scene(text, scene_path, {{"discretization.ny", "-1"}}), SceneError);
    CHECK(scene_files(text, scene_path, {{"discretization.ny", "-1"}}) == files);
    // An override names another file, which need not exist (the run says so); empty: none.
    const auto other = scene_files(text, scene_path, {{"beam.blade_file", "other.dat"}});
    REQUIRE(other.size() == 1);
    CHECK(other[0].second == case_file("other.dat"));
    CHECK(scene_files(text, scene_path, {{"beam.blade_file", ""}}).empty());
    // Text that is no TOML is the scene's error, as when it is read.
    CHECK_THROWS_AS(scene_files("[beam\n", scene_path), SceneError);
}
