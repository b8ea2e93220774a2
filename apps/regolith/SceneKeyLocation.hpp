#pragma once
/// Where in the scene a key that an error message names was written, for the messages of code
/// that sees plain data instead of the TOML (the particle generators: "particles[2].spacing:
/// must be positive, got 0").
#include "core/config/ConfigTable.hpp"

#include <string>
#include <string_view>

namespace regolith::apps {

/// `message` prefixed with the location (ConfigTable::location: "scene.toml:14" or
/// "--set particles.0.radius=-1") of the scene key it starts with, so that it reads like the
/// scene reader's own errors: "scene.toml:14: particles[2].spacing: must be positive, got 0".
///
/// Recognised: a message starting with "particles[i]", "walls[i]" or "insert[i]", optionally
/// followed by a dotted key path whose segments may carry an index ("particles[1].position[3]",
/// "particles[0].velocity.random"), then ": ". The deepest key of the path that exists in the
/// scene gives the location; an absent key gives its table's. A message that does not start
/// so, or names an entry the scene does not have, is returned unchanged. Not collective.
[[nodiscard]] std::string locateSceneKey(core::ConfigTable const& root, std::string_view message);

/// The same for a message that starts with a key of a section, "<section>.<key> = value: ..."
/// or "<section>.<key>: ..." (the checks that compare several values, e.g. "time.dt = 0.5
/// exceeds t_c/10"), when the scene (or a --set) gave that key; otherwise `message`
/// unchanged. Not collective.
[[nodiscard]] std::string locateSectionKey(core::ConfigTable const& root, std::string_view message);

} // namespace regolith::apps
