// Every table a scene reads (a motion table, a torque table, a beam profile), and the scene file itself, as editors
// save them: with a UTF-8 byte order mark, Windows line ends, comment and blank lines. Each reads as the plain file.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <hubbeam/scene.hpp>
#include "temp_folder.hpp"

using namespace hubbeam;

namespace {

std::string read_text(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A folder of its own, removed afterwards.
using Folder = TempFolder;

/// text as an editor may save it: with a byte order mark, with CRLF line ends, or with comment and blank lines
/// before the header, between the rows and at the end (a CSV's comments start with #, as a TOML file's do).
std::string encoded(const std::string& text, const std::string& how)
{
    std::string out = text;
    if (how == "comments" || how == "all") {
        std::string with;
        std::istringstream lines(text);
        with += "# written by hand, with commas, 1, 2, 3\n\n";
        for (std::string line; std::getline(lines, line);) with += line + "\n#\n\n   \n";
        out = with + "# the end\n";
    }
    if (how == "CRLF" || how == "all") {
        std::string crlf;
        for (const char c : out) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
        out = crlf;
    }
    if (how == "BOM" || how == "all") out = "\xef\xbb\xbf" + out;
    return out;
}

/// What a scene read: its parameters (a profile's values among them), a profile's stations, and its drive at times
/// across the table.
std::vector<double> what_was_read(const Scene& s)
{
    std::vector<double> v = s.parameters.packed();
    v.insert(v.end(), s.parameters.profile.begin(), s.parameters.profile.end());
    v.insert(v.end(), s.parameters.stations.begin(), s.parameters.stations.end());
    for (double t = 0.0; t <= 40.0; t += 0.37) {
        const HubInput u = s.motion.at(t);
        v.insert(v.end(), {u.tau, u.theta, u.theta_dot, u.theta_ddot});
    }
    return v;
}

}  // namespace

TEST_CASE("a table with a byte order mark, CRLF line ends or comment lines reads as the plain table", "[scene]")
{
    // cases/ holds one scene for each kind of table: its scene and table copied, then encoded.
    const struct {
        const char *scene, *table;
    } cases[] = {{"table_spinup.toml", "table_spinup.csv"},
                 {"torque_table.toml", "torque_table.csv"},
                 {"profile_blade.toml", "profile_blade.csv"}};
    const std::filesystem::path source = std::filesystem::path(HUBBEAM_SOURCE_DIR) / "cases";
    for (const auto& c : cases) {
        const std::string scene_text = read_text(source / c.scene), table_text = read_text(source / c.table);
        Folder plain("plain");
        plain.write(c.scene, scene_text);
        plain.write(c.table, table_text);
        const std::vector<double> expected = what_was_read(load_scene((plain.path / c.scene).string()));
        for (const char* how : {"BOM", "CRLF", "comments", "all"}) {
            INFO(c.table << " " << how);
            Folder folder("encoded");
            folder.write(c.scene, scene_text);
            folder.write(c.table, encoded(table_text, how));
            CHECK(what_was_read(load_scene((folder.path / c.scene).string())) == expected);
            // The scene file itself the same way (TOML's comments start with # too).
            folder.write(c.scene, encoded(scene_text, how));
            CHECK(what_was_read(load_scene((folder.path / c.scene).string())) == expected);
        }
    }
}
