#pragma once
/// The scene files of the reference-scene apps, compiled in (regolith_embed_scene in
/// apps/CMakeLists.txt): each app runs its scene when no scene file is given.
#include <string_view>

namespace regolith::apps {

[[nodiscard]] std::string_view granularGasScene(); ///< scenes/granular-gas.toml
[[nodiscard]] std::string_view denseRampScene();   ///< scenes/dense-ramp.toml
[[nodiscard]] std::string_view bidisperseScene();  ///< scenes/bidisperse.toml

} // namespace regolith::apps
