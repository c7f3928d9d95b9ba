// hubbeam import: a BModes .bmi or an ElastoDyn main input file (and the blade file it names) into a scene file a
// user reads and edits (main_input.hpp); written as every output is (output_file.hpp).
#include <algorithm>
#include <filesystem>
#include <hubbeam/blade_files.hpp>
#include <hubbeam/main_input.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/printable.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "command.hpp"

namespace hubbeam::cli {

namespace {

/// hubbeam import: reads and checks everything, then writes the scene; returns the exit code.
int import_scene(const std::string& input, const std::string& output)
{
    std::string text;
    ImportedBlade blade;
    try {
        // Named by what it holds, as run's outputs are: a scene file ends in .toml.
        if (std::filesystem::path(output).extension() != ".toml")
            throw OutputRefused("-o: expected a scene file name ending in .toml, got \"" + printable(output, 400) +
                                "\"");
        // Against each file read, before it is read: no input is ever written over.
        check_outputs({{input, "the input file"}}, {{output, "-o"}});
        blade = read_main_input(input);
        check_outputs({{blade.blade_file, "its blade file"}}, {{output, "-o"}});
        text = imported_scene_toml(blade, output);
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const MainInputError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const BladeFileError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const SceneError& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    try {
        OutputFile file(output);
        if (file.write(text) != 0 || !file.commit().empty()) {
            std::cerr << printable(output, 400) << ": could not be written\n";
            return exit_stopped;
        }
    } catch (const OutputRefused& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    } catch (const std::runtime_error& e) {
        std::cerr << e.what() << "\n";
        return exit_bad_input;
    }
    std::cout << "scene       " << output << " (one blade of " << printable(input, 400) << ", " << blade.format
              << ")\n";
    return exit_ok;
}

}  // namespace

Command add_import_command(CLI::App& app)
{
    struct Options {
        std::string input, output;
    };
    auto o = std::make_shared<Options>();
    Subcommand cmd(app, "import",
                   "Turn a BModes .bmi or an ElastoDyn main input file (and its blade file) into a scene file");
    cmd.add_option("input", o->input, "BModes main input file (.bmi) or ElastoDyn main input file")
        .required()
        .type_name("FILE");
    cmd.add_option("-o,--output", o->output, "The scene to write (ending in .toml)").required().type_name("SCENE");
    cmd.footer(
        "Reads the settings that make one blade (docs/import.md) and refuses, in one line naming the file, "
        "line and setting, one that hubbeam does not model (exit 2, nothing written). The scene is written "
        "to DIR/.NAME.tmp-PID and renamed over SCENE; the input, its blade file, a link, a FIFO or a "
        "read-only file are refused as SCENE.");
    return {cmd.app(), [o] { return import_scene(o->input, o->output); }};
}

}  // namespace hubbeam::cli
