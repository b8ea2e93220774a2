#pragma once
/// A picture of one output step without a display (docs/guide/paraview.md):
/// the grains of a particles .pvtu as spheres of their radius coloured by speed, the block
/// outlines of the matching blocks .pvtu coloured by owner rank, rendered off screen with
/// VTK into a PNG. VTK's OpenGL window needs an X display: on a machine without one run the
/// tool under `xvfb-run` (Debian package xvfb).
#include "io/vtk/VtkSeries.hpp"

#include <string>

namespace regolith::io {

struct SnapshotOptions {
    std::string particles; ///< .pvtu (or .vtu) of particles written by VtkOutput
    std::string blocks;    ///< .pvtu of the block outlines, or "" for none
    std::string png;       ///< output file
    int width = 1200;      ///< [pixels]
    int height = 900;      ///< [pixels]
};

/// Renders the snapshot described by `options` into options.png. Throws core::InputError
/// naming the file for an unreadable input or an unwritable PNG, and (before touching VTK's
/// window) if there is no X display. Not collective: one process renders.
void renderSnapshot(SnapshotOptions const& options);

} // namespace regolith::io
