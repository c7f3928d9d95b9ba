// Scene problems as messages: SceneError's wording, the helpers that throw it, and a problem against the
// command-line option that set its key.
#include <hubbeam/printable.hpp>
#include <hubbeam/scene.hpp>
#include <hubbeam/shortest.hpp>

#include "io/scene_io.hpp"

namespace hubbeam {

namespace {

std::string file_label(const std::string& path) { return path.empty() ? std::string("<scene>") : path; }

}  // namespace

[[noreturn]] void scene_io::fail(const std::string& file, const std::string& key, const std::string& expected,
                                 const std::string& got)
{
    throw SceneError(file, key, expected, got);
}

std::string scene_io::angle_bound()
{
    return shortest(max_hub_angle) + " rad (beyond it double precision no longer resolves an angle's small changes)";
}

SceneError::SceneError(std::string file_, std::string key_, std::string expected_, std::string got_,
                       std::string detail_)
    : SceneError(Clean{}, printable(file_, 400), printable(key_, 80), std::move(expected_), printable(got_, 120),
                 printable(detail_, 400))
{
}

SceneError::SceneError(Clean, std::string file_, std::string key_, std::string expected_, std::string got_,
                       std::string detail_)
    : std::runtime_error(file_label(file_) + ": " + (key_.empty() ? "" : key_ + ": ") +
                         (detail_.empty() ? "expected " + expected_ + ", got " + got_ : detail_)),
      file(std::move(file_)), key(std::move(key_)), expected(std::move(expected_)), got(std::move(got_)),
      detail(std::move(detail_))
{
}

SceneError::SceneError(std::string file_, std::string key_, std::string expected_, std::string got_)
    : SceneError(std::move(file_), std::move(key_), std::move(expected_), std::move(got_), "")
{
}

SceneError SceneError::with_detail(std::string file, std::string key, std::string detail)
{
    return SceneError(std::move(file), std::move(key), "", "", std::move(detail));
}

std::string SceneError::problem() const { return detail.empty() ? "expected " + expected + ", got " + got : detail; }

std::string message_for(const SceneError& e, const Overrides& overrides)
{
    for (const auto& [name, value] : overrides)
        if (name == e.key) return option_name(scene_key(name)) + ": " + e.problem();
    return e.what();
}

}  // namespace hubbeam
