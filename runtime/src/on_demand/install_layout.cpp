// Locating companions from the code's own file: no absolute path of the build tree is compiled in, so that
// `cmake --install` followed by removing the build tree leaves every command working.
#include <hubbeam/install_layout.hpp>

#include <sstream>
#include <system_error>
#include <vector>

#include <dlfcn.h>
#include <link.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef HUBBEAM_GEN_SEARCH
#error "HUBBEAM_GEN_SEARCH must list hubbeam-gen's folders relative to the code's folder (set by CMakeLists.txt)"
#endif
#ifndef HUBBEAM_PYTHON_SEARCH
#define HUBBEAM_PYTHON_SEARCH ""
#endif

namespace hubbeam {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> colon_list(const std::string& s)
{
    std::vector<std::string> parts;
    std::stringstream in(s);
    for (std::string p; std::getline(in, p, ':');)
        if (!p.empty()) parts.push_back(p);
    return parts;
}

}  // namespace

fs::path code_folder()
{
    // The link map tells the main program (an empty name) from a shared object such as the Python module.
    Dl_info info{};
    link_map* map = nullptr;
    std::error_code ec;
    if (::dladdr1(reinterpret_cast<void*>(&code_folder), &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 &&
        map != nullptr && map->l_name != nullptr && map->l_name[0] == '/')
        return fs::weakly_canonical(map->l_name, ec).parent_path();
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : self.parent_path();
}

std::string untrusted_program(const fs::path& path)
{
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return path.string() + " cannot be read";
    // Not followed: the link's target is what would run, and whoever may change the link chooses it.
    if (S_ISLNK(st.st_mode)) return path.string() + " is a symbolic link, which hubbeam does not follow";
    if (!S_ISREG(st.st_mode)) return path.string() + " is not a regular file";
    if (st.st_uid != 0 && st.st_uid != ::geteuid())
        return path.string() + " belongs to another user (uid " + std::to_string(st.st_uid) + ")";
    if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0) return path.string() + " is writable by other users";
    return {};
}

std::string find_generator()
{
    const auto runnable = [](const fs::path& p) {
        std::error_code ec;
        return ::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p, ec) && untrusted_program(p).empty();
    };
    const fs::path here = code_folder();
    if (!here.empty())
        for (const std::string& relative : colon_list(HUBBEAM_GEN_SEARCH))
            if (const fs::path p = (here / relative / "hubbeam-gen").lexically_normal(); runnable(p)) return p.string();
    // A program of the user's own that links the installed library: the configured install folder.
    if (const fs::path p = fs::path(HUBBEAM_INSTALLED_GEN); runnable(p)) return p.string();
    return {};
}

fs::path python_package_parent()
{
    const fs::path here = code_folder();
    std::error_code ec;
    if (!here.empty())
        for (const std::string& relative : colon_list(HUBBEAM_PYTHON_SEARCH))
            if (const fs::path p = (here / relative).lexically_normal(); fs::exists(p / "hubbeam" / "__init__.py", ec))
                return p;
    return {};
}

}  // namespace hubbeam
