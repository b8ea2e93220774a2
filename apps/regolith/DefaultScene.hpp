#pragma once
/// The scene `regolith` runs without a scene file: the text of scenes/default.toml.
#include <string_view>

namespace regolith::apps {

/// Generated at configure time from scenes/default.toml (apps/regolith/CMakeLists.txt).
[[nodiscard]] std::string_view defaultScene();

} // namespace regolith::apps
