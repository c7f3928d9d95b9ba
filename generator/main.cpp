// hubbeam-gen: derives the named variants symbolically and writes one C++ source per variant plus the
// registry into the output folder. Usage: hubbeam-gen --out DIR VARIANT...
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "variant_source.hpp"

namespace {

void write(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream f(path);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv)
{
    std::filesystem::path out = ".";
    std::vector<std::string> names;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc) out = argv[++i];
        else if (a == "--help" || a == "-h") {
            std::cout << "usage: hubbeam-gen --out DIR VARIANT...\n"
                         "  VARIANT: method_nxN_nyN_drive_order[_open], e.g. bim_nx4_ny4_torque_first\n";
            return 0;
        } else names.push_back(a);
    }
    try {
        std::filesystem::create_directories(out);
        for (const std::string& name : names) {
            const auto start = std::chrono::steady_clock::now();
            const hubbeam::VariantKey key = hubbeam::VariantKey::parse(name);
            if (key.name() != name) throw std::invalid_argument("variant '" + name + "' is spelled " + key.name());
            write(out / (name + ".cpp"), hubbeam::gen::variant_source(key));
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cout << "hubbeam-gen: " << name << " (" << s << " s)\n";
        }
        write(out / "registry.cpp", hubbeam::gen::registry_source(names));
    } catch (const std::exception& e) {
        std::cerr << "hubbeam-gen: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
