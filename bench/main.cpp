// knotwork-bench: `knotwork bench`, the paper's Tables 1 and 2 (bench/cmd_bench.cpp). Its own
// executable so that libGLU, the comparison passes and the report code load only here;
// `knotwork bench ...` replaces itself with `knotwork-bench bench ...` (app/launch.h).
#include "app/commands.h"
#include "app/gl_command.h"

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    if (argc < 2 || std::strcmp(argv[1], "bench") != 0) {
        std::fputs("usage: knotwork bench [options] [FILES...] (see knotwork bench --help)\n",
                   stderr);
        return kw::cli::kExitUsage;
    }
    return kw::cli::runGlCommand(argc, argv, kw::cli::runBench);
}
