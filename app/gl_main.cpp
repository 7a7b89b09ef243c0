// knotwork-gl: the editor and `knotwork render`, the part of Knotwork that needs Qt's GUI and
// OpenGL libraries and OpenImageIO. `knotwork` replaces itself with this program for them
// (app/launch.h); it takes the same arguments (argv[0] is still "knotwork").
#include "app/commands.h"
#include "app/editor.h"
#include "app/gl_command.h"
#include "model/cad/cadprestart.h"

#include <cstring>

int main(int argc, char** argv) {
    // A CAD read the launcher started for `render` (before any other thread exists here).
    kw::claimPrestartedCadRead();
    if (argc > 1 && std::strcmp(argv[1], "render") == 0)
        return kw::cli::runGlCommand(argc, argv, kw::cli::runRender);
    kw::cli::applyDevelopmentSwitches();
    return kw::app::runEditor(argc, argv);
}
