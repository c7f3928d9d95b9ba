// A scratch folder of a test's own under the system's temporary folder, removed with its contents at the end.
#pragma once

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

struct TempFolder {
    std::filesystem::path path;

    /// tag names the folder (hubbeam-test-TAG-PID-N), so a folder left by a crashed test says whose it is.
    explicit TempFolder(const std::string& tag = "scratch")
    {
        static std::atomic<int> count{0};
        path = std::filesystem::temp_directory_path() /
               ("hubbeam-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempFolder()
    {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    /// Writes text, byte for byte, to the file name in the folder; returns its path.
    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string file = (path / name).string();
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }
};
