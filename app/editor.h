// The editor entry point of the knotwork executable: `knotwork [--screenshot OUT] [FILE]`.
#pragma once

namespace kw::app {

/// Runs the editor: sets the default OpenGL 4.5 core surface format, creates the QApplication,
/// checks that an OpenGL 4.5 core context can be made, shows the main window and opens FILE.
/// Returns the exit code: 0 on normal exit; 1 with a clear message when there is no display,
/// no OpenGL 4.5 core context, FILE cannot be read, or the screenshot cannot be written;
/// 2 for a usage error. Must be called before any Q*Application exists.
int runEditor(int argc, char** argv);

/// True when argv[1] names something the editor handles (a FILE or an editor option) rather
/// than a subcommand or a global option of the command-line tools.
bool isEditorInvocation(int argc, char** argv);

} // namespace kw::app
