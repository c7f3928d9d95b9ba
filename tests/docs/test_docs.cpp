// The documentation's facts about scenes, against the program: docs/scene.md's key table lists exactly the keys
// of scene_keys() with what each accepts, its documented defaults are the defaults load_scene() applies, the
// keys it calls required are refused when missing, the scenes the pages show parse, docs/cli.md's `run`
// table sets the key each option sets; and across the pages: no changelog tone, the variant-name grammar the
// parser reads, one spelling of the Dask commands, tip_ux as each order writes it.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <hubbeam/fields.hpp>
#include <hubbeam/scene.hpp>
#include "command.hpp"

using namespace hubbeam;

namespace {

/// The cells of a Markdown table row "| a | b | c |", trimmed.
std::vector<std::string> cells(const std::string& line)
{
    std::vector<std::string> out;
    std::size_t start = line.find('|');
    while (start != std::string::npos) {
        const std::size_t end = line.find('|', start + 1);
        if (end == std::string::npos) break;
        std::string cell = line.substr(start + 1, end - start - 1);
        cell.erase(0, cell.find_first_not_of(' '));
        cell.erase(cell.find_last_not_of(' ') + 1);
        out.push_back(cell);
        start = end;
    }
    return out;
}

/// The rows of the tables in a page of the docs (in its section "## SECTION" if one is named) whose first cell
/// starts with a backquoted name, by that name's first word ("--ny" of "`--ny N`").
std::map<std::string, std::vector<std::string>> table_rows(const std::string& page, const std::string& section = "")
{
    std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/docs/" + page);
    REQUIRE(in);
    std::map<std::string, std::vector<std::string>> rows;
    bool inside = section.empty();
    for (std::string line; std::getline(in, line);) {
        if (!section.empty() && line.rfind("## ", 0) == 0) inside = line == "## " + section;
        if (!inside || line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> c = cells(line);
        const std::string name = c[0].substr(1, c[0].find_first_of("` ", 1) - 1);
        rows[name] = c;
    }
    return rows;
}

/// A scene with every required key of its motion: one line per key, as "table.key = value".
using SceneLines = std::vector<std::pair<std::string, std::string>>;

const SceneLines spin_up = {
    {"beam.length", "8.0"},         {"beam.density", "2.7667e3"},    {"beam.area", "7.2968e-5"},
    {"beam.second_moment", "8.2189e-9"}, {"beam.youngs_modulus", "6.8952e10"}, {"motion.kind", "\"spin-up\""},
    {"motion.omega0", "4.0"},       {"motion.duration", "15.0"},     {"discretization.method", "\"amm\""},
    {"discretization.ny", "4"},     {"discretization.nx", "4"},      {"output.t_end", "30.0"},
};

SceneLines torque_scene()
{
    SceneLines s;
    for (const auto& [key, value] : spin_up) {
        if (key == "motion.kind") s.emplace_back(key, "\"torque\"");
        else if (key == "motion.omega0") s.emplace_back("motion.tau0", "10.0");
        else s.emplace_back(key, value);
    }
    s.emplace_back("hub.inertia", "30.0");
    return s;
}

/// The spin-up scene with its [motion] of another kind: `motion` replaces the spin-up's motion keys.
SceneLines other_motion(const SceneLines& motion)
{
    SceneLines s;
    for (const auto& [key, value] : spin_up) {
        if (key == "motion.kind") s.insert(s.end(), motion.begin(), motion.end());
        else if (key.rfind("motion.", 0) != 0) s.emplace_back(key, value);
    }
    return s;
}

/// A controlled hub following a step: the scene whose [control] keys the tables' rows are checked in.
SceneLines controlled_step()
{
    SceneLines s = other_motion({{"motion.kind", "\"step\""}, {"motion.angle", "0.5"}});
    s.emplace_back("hub.inertia", "30.0");
    s.emplace_back("control.kp", "64.0");
    s.emplace_back("control.kd", "90.0");
    return s;
}

/// The TOML text of the scene without the key `left_out`.
std::string scene_text(const SceneLines& lines, const std::string& left_out = "")
{
    std::map<std::string, std::string> tables;
    for (const auto& [key, value] : lines) {
        const std::size_t dot = key.find('.');
        std::string& body = tables[key.substr(0, dot)];  // the table stays, even if left_out was its only key
        if (key != left_out) body += key.substr(dot + 1) + " = " + value + "\n";
    }
    std::string text;
    for (const auto& [table, body] : tables) text += "[" + table + "]\n" + body;
    return text;
}

/// Every value a scene key sets, compared field by field.
void check_same(const Scene& a, const Scene& b)
{
    CHECK(a.parameters.L == b.parameters.L);
    CHECK(a.parameters.rho == b.parameters.rho);
    CHECK(a.parameters.S == b.parameters.S);
    CHECK(a.parameters.I == b.parameters.I);
    CHECK(a.parameters.E == b.parameters.E);
    CHECK(a.parameters.a == b.parameters.a);
    CHECK(a.parameters.J_oh == b.parameters.J_oh);
    CHECK(a.parameters.packed() == b.parameters.packed());  // every parameter, the terms' and the section's too
    CHECK(a.motion.kind == b.motion.kind);
    CHECK(a.motion.omega0 == b.motion.omega0);
    CHECK(a.motion.spin_time == b.motion.spin_time);
    CHECK(a.motion.tau0 == b.motion.tau0);
    CHECK(a.motion.torque_time == b.motion.torque_time);
    CHECK(a.motion.theta0 == b.motion.theta0);
    CHECK(a.motion.angle == b.motion.angle);
    CHECK(a.motion.table_file == b.motion.table_file);
    CHECK(a.variant == b.variant);
    CHECK(a.source == b.source);
    CHECK(a.axial == b.axial);
    CHECK(a.solver.stepper == b.solver.stepper);
    CHECK(a.solver.rtol == b.solver.rtol);
    CHECK(a.solver.atol == b.solver.atol);
    CHECK(a.solver.h0 == b.solver.h0);
    CHECK(a.solver.stepping == b.solver.stepping);
    CHECK(a.solver.max_steps == b.solver.max_steps);
    CHECK(a.output.t_end == b.output.t_end);
    CHECK(a.output.dt_out == b.output.dt_out);
    CHECK(a.output.file == b.output.file);
    CHECK(a.motion.angle == b.motion.angle);
    REQUIRE(a.control.has_value() == b.control.has_value());
    if (a.control) {
        CHECK(a.control->kp == b.control->kp);
        CHECK(a.control->kd == b.control->kd);
        CHECK(a.control->ki == b.control->ki);
        CHECK(a.control->tau_max == b.control->tau_max);
        CHECK(a.control->k_tip == b.control->k_tip);
    }
}

}  // namespace

TEST_CASE("docs/scene.md lists exactly the program's scene keys, with what each accepts", "[docs]")
{
    // The key table in scene.cpp is the one definition; the page's column "accepts" is its `expected`, word for word.
    std::map<std::string, std::vector<std::string>> rows = table_rows("scene.md");
    std::set<std::string> documented;
    for (const auto& [name, row] : rows)
        if (name.find('.') != std::string::npos) documented.insert(name);
    std::set<std::string> keys;
    for (const SceneKey& k : scene_keys()) {
        keys.insert(k.name);
        INFO(k.name);
        REQUIRE(rows.count(k.name) == 1);
        REQUIRE(rows[k.name].size() >= 4);
        CHECK(rows[k.name][1] == k.expected);
    }
    CHECK(documented == keys);
}

TEST_CASE("docs/scene.md's defaults are the ones a scene gets, and its required keys are required", "[docs]")
{
    // A default `V` is right when a scene without the key is valid and setting the key to V changes nothing; a
    // required key is refused when missing.
    int defaults = 0, required = 0, derived = 0;
    for (const auto& [name, row] : table_rows("scene.md")) {
        if (name.find('.') == std::string::npos) continue;
        INFO(name);
        REQUIRE(row.size() >= 4);
        const std::string& cell = row[3];
        if (cell.rfind("`", 0) == 0) {
            std::string value = cell.substr(1, cell.find('`', 1) - 1);
            if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
            INFO("documented default " << value);
            // A [control] key's default is the one a controlled scene gets (in another, the key would add [control]);
            // a [support] key's and hub.mass's the one a torque-driven scene with a [support] gets.
            SceneLines base = name.rfind("control.", 0) == 0 ? controlled_step() : spin_up;
            if (name.rfind("support.", 0) == 0 || name == "hub.mass") {
                base = torque_scene();
                base.emplace_back(name == "support.stiffness_x" ? "support.stiffness_y" : "support.stiffness_x", "0");
            }
            const std::string without = scene_text(base, name);
            Scene plain;
            REQUIRE_NOTHROW(plain = parse_scene(without, "spin-up.toml"));
            check_same(parse_scene(without, "spin-up.toml", {{name, value}}), plain);
            ++defaults;
        } else if (cell.rfind("as `", 0) == 0) {
            // A default that is another key's value: setting the key to that value changes nothing.
            const std::string other = cell.substr(4, cell.find('`', 4) - 4);
            const std::string without = scene_text(spin_up, name);
            std::string value;
            for (const auto& line : spin_up)
                if (line.first == other) value = line.second;
            INFO("documented default: the value of " << other);
            REQUIRE(!value.empty());
            check_same(parse_scene(without, "spin-up.toml", {{name, value}}), parse_scene(without, "spin-up.toml"));
            ++derived;
        } else if (cell.rfind("required", 0) == 0) {
            bool held = false;
            const SceneLines held_hub = other_motion({{"motion.kind", "\"held\""}, {"motion.angle", "0.5"}});
            const SceneLines from_table = other_motion(
                {{"motion.kind", "\"table\""},
                 {"motion.file", "\"" + std::string(HUBBEAM_SOURCE_DIR) + "/cases/table_spinup.csv\""}});
            for (const SceneLines& scene : {spin_up, torque_scene(), held_hub, from_table, controlled_step()}) {
                bool holds = false;
                for (const auto& line : scene) holds = holds || line.first == name;
                if (!holds) continue;
                held = true;
                try {
                    parse_scene(scene_text(scene, name), "scene.toml");
                    FAIL("a scene without " << name << " was accepted");
                } catch (const SceneError& e) {
                    CHECK(e.key == name);
                }
            }
            CHECK(held);
            ++required;
        }
    }
    // Every key is one or the other, or defaults to another key's value, but output.file, whose default is derived
    // from the scene's name.
    CHECK(defaults + required + derived + 1 == static_cast<int>(scene_keys().size()));
}

TEST_CASE("docs/cli.md's run options set the keys the program's options set", "[docs]")
{
    std::map<std::string, std::vector<std::string>> rows = table_rows("cli.md", "hubbeam run");
    for (const SceneKey& k : scene_keys()) {
        if (!k.option) continue;
        const std::string option = option_name(k);
        INFO(option);
        REQUIRE(rows.count(option) == 1);
        REQUIRE(rows[option].size() >= 2);
        CHECK(rows[option][1] == std::string("`") + k.name + "`");
    }
}

TEST_CASE("the scenes shown in README.md and docs/scene.md are valid scenes", "[docs]")
{
    int shown = 0;
    for (const std::string page : {"README.md", "docs/scene.md"}) {
        std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/" + page);
        REQUIRE(in);
        std::string block;
        bool inside = false;
        for (std::string line; std::getline(in, line);) {
            if (!inside && line == "```toml") {
                inside = true;
                block.clear();
            } else if (inside && line.rfind("```", 0) == 0) {
                inside = false;
                INFO(page << ":\n" << block);
                CHECK_NOTHROW(parse_scene(block, page));
                ++shown;
            } else if (inside) {
                block += line + "\n";
            }
        }
    }
    CHECK(shown >= 2);
}

namespace {

/// The pages of the documentation: README.md and docs/*.md, by path relative to the source tree, with their text.
std::vector<std::pair<std::string, std::string>> doc_pages()
{
    std::vector<std::pair<std::string, std::string>> pages;
    std::vector<std::string> names = {"README.md"};
    for (const auto& e : std::filesystem::directory_iterator(std::string(HUBBEAM_SOURCE_DIR) + "/docs"))
        if (e.path().extension() == ".md") names.push_back("docs/" + e.path().filename().string());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
        std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/" + name);
        REQUIRE(in);
        std::stringstream text;
        text << in.rdbuf();
        pages.emplace_back(name, text.str());
    }
    return pages;
}

/// A page's prose: its text without code blocks and backquoted spans (a program's own output, quoted, may say
/// anything), each line kept.
std::string prose(const std::string& text)
{
    std::string out;
    bool block = false;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("```", 0) == 0) {
            block = !block;
            out += "\n";
            continue;
        }
        if (block) {
            out += "\n";
            continue;
        }
        bool quoted = false;
        for (const char c : line) {
            if (c == '`') quoted = !quoted;
            else if (!quoted) out += c;
        }
        out += "\n";
    }
    return out;
}

/// The backquoted spans of a text.
std::vector<std::string> quoted_spans(const std::string& text)
{
    std::vector<std::string> spans;
    for (std::size_t at = text.find('`'); at != std::string::npos;) {
        const std::size_t end = text.find('`', at + 1);
        if (end == std::string::npos) break;
        spans.push_back(text.substr(at + 1, end - at - 1));
        at = text.find('`', end + 1);
    }
    return spans;
}

}  // namespace

TEST_CASE("the docs describe the program as it is: no changelog tone, no undefined jobs", "[docs]")
{
    // Words that tell a history ("now", "no longer", "once chose") or name a run the page never defines.
    const std::regex history(R"(\b(now|no longer|once (chose|took|was|did|had)|used to|previously|formerly|main job)\b)",
                             std::regex::icase);
    int pages = 0;
    for (const auto& [name, text] : doc_pages()) {
        std::istringstream in(prose(text));
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            std::smatch m;
            INFO(name << ":" << number << ": " << line);
            CHECK_FALSE(std::regex_search(line, m, history));
        }
        ++pages;
    }
    CHECK(pages >= 10);
}

TEST_CASE("the docs give the variant-name grammar VariantKey::parse reads, every suffix", "[docs]")
{
    // the grammar as parse's message gives it: "... (expected GRAMMAR, e.g. ...)"
    std::string grammar;
    try {
        VariantKey::parse("x");
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        const std::size_t from = what.find("(expected ") + 10;
        grammar = what.substr(from, what.find(", e.g.", from) - from);
    }
    REQUIRE(grammar.rfind("METHOD_nx", 0) == 0);
    int shown = 0;
    for (const auto& [name, text] : doc_pages())
        for (const std::string& span : quoted_spans(text))
            if (span.rfind("METHOD_nx", 0) == 0) {
                INFO(name);
                CHECK(span == grammar);
                ++shown;
            }
    CHECK(shown >= 2);  // docs/cli.md (hubbeam-gen) and docs/development.md
    // and each suffix of the grammar is one parse takes, in that order
    for (const char* name : {"bsim_nx0_ny4_prescribed_first_open", "amm_nx0_ny4_torque_first_tip_gravity_damped_width",
                             "fem_nx0_ny4_torque_full_depth", "amm_nx0_ny4_torque_zero_profile"}) {
        INFO(name);
        CHECK(VariantKey::parse(name).name() == name);
    }
}

TEST_CASE("the docs spell the Dask scheduler command one way, its alias once", "[docs]")
{
    int alias = 0;
    for (const auto& [name, text] : doc_pages()) {
        INFO(name);
        for (const char* command : {"dask-scheduler", "dask-worker"}) {
            const std::string backquoted = std::string("`") + command + "`";
            for (std::size_t at = text.find(command); at != std::string::npos; at = text.find(command, at + 1)) {
                const bool named = at > 0 && text.compare(at - 1, backquoted.size(), backquoted) == 0;
                CHECK(named);  // only as the alias, in a sentence, never as a command to run
                alias += named;
            }
        }
    }
    CHECK(alias == 2);  // "also installs these as `dask-scheduler` and `dask-worker`", once
}

TEST_CASE("docs/cli.md's tip_ux is what each order writes: u_x1(L) under order zero", "[docs]")
{
    const std::map<std::string, std::vector<std::string>> rows = table_rows("cli.md", "hubbeam run");
    REQUIRE(rows.count("tip_ux") == 1);
    const std::string meaning = rows.at("tip_ux")[1];
    INFO(meaning);
    CHECK(meaning.find("order `zero`") != std::string::npos);
    CHECK(meaning.find("writes `u_x1(L)`") != std::string::npos);
    // the program: a bent beam's tip under order zero, its stretch alone; under order first, foreshortened
    const Parameters p;
    const std::vector<double> A = {1e-4, -2e-5, 3e-6, 0.0}, B = {0.3, -0.05, 0.01, 0.002};
    for (const Order order : {Order::zero, Order::first}) {
        const VariantKey key{.method = Method::amm, .nx = 4, .ny = 4, .order = order, .drive = Drive::torque, .extras = {}};
        const Tip tip = BeamFields(key, p).tip(A.data(), B.data());
        if (order == Order::zero) CHECK(tip.ux == tip.ux1);
        else CHECK(tip.ux < tip.ux1 - 1e-4);
    }
}

namespace {

/// The exit codes a text lists: every number of two or three digits or one digit standing alone, in "0 done, 1
/// ..., 129/130/131/143 ..." or a table's "| 129, 130, 131, 143 |".
std::set<int> codes_in(const std::string& text)
{
    std::set<int> codes;
    const std::regex number(R"((^|[ |/,(])([0-9]{1,3})(?=[ |/,]))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
        codes.insert(std::stoi((*it)[2]));
    return codes;
}

/// The text of a page from the line starting with `from` to the first blank line after it.
std::string paragraph(const std::string& page, const std::string& from)
{
    const std::string text = [&] {
        std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/" + page);
        std::stringstream t;
        t << in.rdbuf();
        return t.str();
    }();
    const std::size_t start = text.find(from);
    REQUIRE(start != std::string::npos);
    const std::size_t end = text.find("\n\n", start);
    return text.substr(start, end - start);
}

}  // namespace

TEST_CASE("the exit codes are one list: --help's sentence, docs/cli.md's table and README.md's line", "[docs]")
{
    const std::set<int> program = codes_in(std::string(" ") + cli::exit_codes_help);
    CHECK(program == std::set<int>{0, 1, 2, 129, 130, 131, 143});
    std::string table;
    {
        std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/docs/cli.md");
        bool inside = false;
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("Exit codes, for every command", 0) == 0) inside = true;
            else if (inside && line.rfind("## ", 0) == 0) break;
            else if (inside && line.rfind("| ", 0) == 0) table += " " + cells(line)[0] + " |";
        }
    }
    CHECK(codes_in(table) == program);
    CHECK(codes_in(" " + paragraph("README.md", "Exit codes:")) == program);
}

TEST_CASE("a scene in cases/ cites sections of docs/model.md that exist, a table's section by its name", "[docs]")
{
    std::map<std::string, std::string> titles;  // "11.3" -> its title, lower case
    {
        std::ifstream in(std::string(HUBBEAM_SOURCE_DIR) + "/docs/model.md");
        const std::regex heading(R"(^#{2,3} ([0-9]+(\.[0-9]+)?)\.? (.*)$)");
        for (std::string line; std::getline(in, line);)
            if (std::smatch m; std::regex_match(line, m, heading)) {
                std::string title = m[3];
                std::transform(title.begin(), title.end(), title.begin(), ::tolower);
                titles[m[1]] = title;
            }
    }
    REQUIRE(titles.size() > 20);
    const std::regex cite(R"(docs/model\.md section ([0-9]+(\.[0-9]+)?))");
    const std::regex table_cite(R"(\[([a-z]+)\][^;()]*; docs/model\.md section ([0-9]+(\.[0-9]+)?))");
    int cites = 0;
    for (const auto& e : std::filesystem::directory_iterator(std::string(HUBBEAM_SOURCE_DIR) + "/cases")) {
        if (e.path().extension() != ".toml") continue;
        std::ifstream in(e.path());
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            INFO(e.path().filename().string() << ":" << number << ": " << line);
            for (auto it = std::sregex_iterator(line.begin(), line.end(), cite); it != std::sregex_iterator(); ++it) {
                CHECK(titles.count((*it)[1]) == 1);
                ++cites;
            }
            // "([gravity] g; docs/model.md section 11.3)": the section that the scene's table is about.
            if (std::smatch m; std::regex_search(line, m, table_cite) && titles.count(m[2]))
                CHECK(titles[m[2]].find(m[1]) != std::string::npos);
        }
    }
    CHECK(cites >= 15);
}
