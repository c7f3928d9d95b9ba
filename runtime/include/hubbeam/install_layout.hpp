// Where hubbeam's companions are (hubbeam-gen, the Python package), found relative to the program or module that
// holds this code, so that an installed or relocated tree works after its build tree is gone.
#pragma once

#include <filesystem>
#include <string>

namespace hubbeam {

/// The folder of the executable or shared object (the Python module) that holds this library's code.
std::filesystem::path code_folder();

/// Why hubbeam must not run the program at path, or empty: a program it runs must be as safe as itself (owned by
/// root or by this user, not writable by group or others, a regular file and not a symbolic link).
std::string untrusted_program(const std::filesystem::path& path);

/// hubbeam-gen of this build or installation: the first trusted one of code_folder()'s layouts (beside an installed
/// or built hubbeam, or where an installed or built Python module or test program finds it), else the configured
/// install folder's; empty if none.
std::string find_generator();

/// The folder to put on PYTHONPATH for the hubbeam package that belongs to this program (the build tree's
/// python/ or the installed package's folder); empty if neither is there.
std::filesystem::path python_package_parent();

}  // namespace hubbeam
