// The editor entry point of knotwork-gl (started by knotwork): `knotwork [--screenshot OUT]
// [FILE]`.
#pragma once

namespace kw::app {

/// Runs the editor: sets the default OpenGL 4.5 core surface format, creates the QApplication,
/// checks that an OpenGL 4.5 core context can be made, shows the main window and opens FILE.
/// Returns the exit code: 0 on normal exit; 1 with a clear message when there is no display,
/// no OpenGL 4.5 core context, FILE cannot be read, or the screenshot cannot be written;
/// 2 for a usage error. Must be called before any Q*Application exists.
int runEditor(int argc, char** argv);

} // namespace kw::app
