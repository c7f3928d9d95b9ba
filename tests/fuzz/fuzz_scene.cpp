// libFuzzer target for the scene parser (docs/testing.md): any bytes as a scene file, with or
// without a command-line override. A SceneError is the parser's answer to bad input; anything else, another
// exception, a crash or a sanitizer report, is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <hubbeam/scene.hpp>

namespace {

/// The input's first byte picks an override key, or none (then the whole input is the scene); with a key, the
/// rest of the first line is the override's text and what follows the scene.
hubbeam::Overrides split(std::string_view& text)
{
    const auto& keys = hubbeam::scene_keys();
    if (text.empty()) return {};
    const std::size_t pick = static_cast<unsigned char>(text[0]) % (keys.size() + 1);
    if (pick == keys.size()) return {};
    const std::size_t eol = text.find('\n');
    const std::string_view value = text.substr(1, eol == std::string_view::npos ? std::string_view::npos : eol - 1);
    text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
    return {{keys[pick].name, std::string(value)}};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string_view whole = text;
    try {
        hubbeam::parse_scene(whole, "fuzz.toml");
    } catch (const hubbeam::SceneError&) {
    }
    try {
        const hubbeam::Overrides overrides = split(text);
        hubbeam::parse_scene(text, "fuzz.toml", overrides);
    } catch (const hubbeam::SceneError&) {
    }
    return 0;
}
