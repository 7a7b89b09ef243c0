// knotwork bench [FILES...]: the paper's Tables 1 and 2 off-screen, speed and quality side by side
//. Measurement in bench/bench_runner, outputs in bench/bench_report.
#include "app/commands.h"
#include "app/render_args.h"
#include "bench/bench_report.h"
#include "bench/drag_step.h"
#include "bench/edit_loop.h"
#include "bench/scale_report.h"
#include "bench/zoom_loop.h"
#include "model/io/install_layout.h"
#include "model/io/savefile.h"
#include "render/analysis.h"

#include <QCommandLineParser>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <cmath>

namespace kw::cli {

namespace {

/// The samples folder of this build tree or installed prefix (share/knotwork/samples).
QString samplesDir() {
    const QString data = dataDir();
    return data.isEmpty() ? QStringLiteral("resources/samples") : data + QStringLiteral("/samples");
}

constexpr int kMaxSide = 4096;

bool parseList(const QString& text, int lo, int hi, std::vector<int>& out) {
    out.clear();
    for (const QString& s : text.split(QLatin1Char(','))) {
        int v = 0;
        if (!parseIntIn(s, lo, hi, v))
            return false;
        out.push_back(v);
    }
    return !out.empty();
}

/// --scale-size: N (square) or WxH, each side in 1..kMaxSide.
bool parseScaleSize(const QString& text, bench::ScaleConfig& config) {
    if (!text.contains(QLatin1Char('x'))) {
        config.height = 0;
        return parseIntIn(text, 1, kMaxSide, config.side);
    }
    QSize size;
    if (!parseImageSize(text, size) || size.width() > kMaxSide || size.height() > kMaxSide)
        return false;
    config.side = size.width();
    config.height = size.height();
    return true;
}

/// `text` is modeName(m) for a mode m (render_args keeps the names).
bool parseModeName(const QString& text, RenderMode& mode) {
    for (RenderMode m : {RenderMode::Exact, RenderMode::Tessellated})
        if (text == modeName(m)) {
            mode = m;
            return true;
        }
    return false;
}

/// `text` is shadingName(s) for a shading way s.
bool parseShadingName(const QString& text, RenderOptions::Shading& shading) {
    for (auto s : {RenderOptions::Shading::DepthPrepass, RenderOptions::Shading::ExactDepth})
        if (text == shadingName(s)) {
            shading = s;
            return true;
        }
    return false;
}

bool writeFile(const QString& path, const QByteArray& bytes) {
    // The old report stays on failure.
    if (const Status saved = saveBytesAtomically(path, bytes); !saved) {
        printError(saved.message());
        return false;
    }
    return true;
}

/// The bench JSON, with the scale table under "scale" when it ran.
QJsonObject benchJson(const bench::BenchReport& report, bool scale,
                      const bench::ScaleReport& scaleReport, const QString& command) {
    QJsonObject o = bench::reportJson(report, command);
    if (scale)
        o.insert(QStringLiteral("scale"), bench::scaleJson(scaleReport));
    return o;
}

} // namespace

int runBench(const QStringList& args, const std::function<bool()>& startGui) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "The paper's Tables 1 and 2, off-screen, speed and quality in one run, for every FILE "
        "(.knot, IGES, STEP, BREP or OBJ, read as render reads them) or, with none, the bundled "
        "samples (Table 2: teapot.knot).\n"
        "Table 1: exact mode at each --sizes (square), --table1-partitions, --lights. "
        "Table 2: at --table2-size and each --partitions, exact mode against "
        "the tessellated baseline at the same partitions, a prebuilt fine mesh and libGLU's "
        "NURBS tessellator re-run every frame, both searched to equal max normal error. FPS = "
        "median of --frames frames after 3 warm-up frames, "
        "each ended by glFinish. Quality: normal-angle error against the CPU kernel, silhouette "
        "error against exact mode at 256 partitions (docs/PERFORMANCE.md defines both). Progress "
        "on stderr, markdown on stdout. Needs OpenGL 4.5 core (see knotwork render --help)."));
    const QCommandLineOption sizes(
        QStringLiteral("sizes"),
        QStringLiteral("Table 1 sizes, each 1..4096 (default 256,512,768,1024)."),
        QStringLiteral("LIST"), QStringLiteral("256,512,768,1024"));
    const QCommandLineOption partitions(
        QStringLiteral("partitions"),
        QStringLiteral("Table 2 partition counts (default 5,10,20,30,40,60)."),
        QStringLiteral("LIST"), QStringLiteral("5,10,20,30,40,60"));
    const QCommandLineOption t1Partitions(QStringLiteral("table1-partitions"),
                                          QStringLiteral("Table 1 partitions (default 30)."),
                                          QStringLiteral("N"), QStringLiteral("30"));
    const QCommandLineOption frames(
        QStringLiteral("frames"),
        QStringLiteral("Timed frames per measurement, >= 20 (default 20)."), QStringLiteral("N"),
        QStringLiteral("20"));
    const QCommandLineOption lights(QStringLiteral("lights"),
                                    QStringLiteral("Number of lights, 1..8 (default 2)."),
                                    QStringLiteral("N"), QStringLiteral("2"));
    const QCommandLineOption tables(
        QStringLiteral("tables"),
        QStringLiteral("Which tables: 1, 2, scale, or a list (default 1,2). scale: --scale-model "
                       "tiled in a grid up to each --scale-faces (docs/PERFORMANCE.md ## Scale)."),
        QStringLiteral("LIST"), QStringLiteral("1,2"));
    const QCommandLineOption scaleModel(
        QStringLiteral("scale-model"),
        QStringLiteral("Scale table: the part to tile, .knot or IGES/STEP/BREP (default: the "
                       "hammer.iges of the samples)."),
        QStringLiteral("FILE"), samplesDir() + QStringLiteral("/hammer.iges"));
    const QCommandLineOption scaleFaces(
        QStringLiteral("scale-faces"),
        QStringLiteral("Scale table: face counts to reach, each 1..1000000 (default "
                       "1,100,300,1000,3000,10000; 1 = one copy)."),
        QStringLiteral("LIST"), QStringLiteral("1,100,300,1000,3000,10000"));
    const QCommandLineOption scaleSize(
        QStringLiteral("scale-size"),
        QStringLiteral("Scale table: image size, N (square) or WxH, each side 1..4096 "
                       "(default 1024)."),
        QStringLiteral("SIZE"), QStringLiteral("1024"));
    const QCommandLineOption scalePartitionMode(
        QStringLiteral("scale-partition-mode"),
        QStringLiteral("Scale table: uniform (default, the paper's grid) or adaptive (the "
                       "editor's: the fewest partitions at or above each surface's own that keep "
                       "0.5 px)."),
        QStringLiteral("MODE"), QStringLiteral("uniform"));
    const QCommandLineOption scalePartitions(
        QStringLiteral("scale-partitions"),
        QStringLiteral("Scale table: partitions N for every surface, 1..%1 (default: each "
                       "surface's own; in adaptive mode the minimum).")
            .arg(kMaxPartitions),
        QStringLiteral("N"));
    const QCommandLineOption scaleShading(
        QStringLiteral("scale-shading"),
        QStringLiteral("Scale table: phong (default) or an analysis mode (gaussian, mean, "
                       "zebra, ...), as render --shading."),
        QStringLiteral("MODE"), QStringLiteral("phong"));
    const QCommandLineOption smoke(
        QStringLiteral("smoke"),
        QStringLiteral("2 timed frames after 1 warm-up per measurement instead of --frames: "
                       "checks the pipeline and the report, measures nothing."));
    const QCommandLineOption t2Size(QStringLiteral("table2-size"),
                                    QStringLiteral("Table 2 image size (default 780x400)."),
                                    QStringLiteral("WxH"), QStringLiteral("780x400"));
    const QCommandLineOption samples(QStringLiteral("samples"),
                                     QStringLiteral("Folder of the samples (default: "
                                                    "share/knotwork/samples)."),
                                     QStringLiteral("DIR"), samplesDir());
    const QCommandLineOption mode(QStringLiteral("mode"),
                                  QStringLiteral("Table 1 mode: exact (default) or tessellated."),
                                  QStringLiteral("MODE"), QStringLiteral("exact"));
    const QCommandLineOption shading(
        QStringLiteral("depth"),
        QStringLiteral("Exact mode: prepass (default: depth pre-pass + GL_EQUAL) or exact-depth "
                       "(one pass writing gl_FragDepth)."),
        QStringLiteral("WAY"), QStringLiteral("prepass"));
    const QCommandLineOption floor(
        QStringLiteral("normal-floor"),
        QStringLiteral("Table 2 equal quality: max normal error <= max(exact mode's, DEG) "
                       "(default 0.2247 = 1/255 rad, one 8-bit diffuse level; 0 = strict)."),
        QStringLiteral("DEG"), QStringLiteral("0.2247"));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Write JSON to OUT."),
                                  QStringLiteral("OUT"));
    const QCommandLineOption markdown(QStringLiteral("markdown"),
                                      QStringLiteral("Write the markdown tables to OUT."),
                                      QStringLiteral("OUT"));
    const QCommandLineOption plots(
        QStringLiteral("plots"),
        QStringLiteral("Write PNG plots into DIR (default: the --markdown file's folder)."),
        QStringLiteral("DIR"));
    const QCommandLineOption noTrims(
        QStringLiteral("no-trims"),
        QStringLiteral("Draw trimmed surfaces over their whole domains (trims ignored) in every "
                       "exact and baseline frame."));
    const QCommandLineOption trimDrag(
        QStringLiteral("trim-drag"),
        QStringLiteral("Table 1: after each row's frames, also time frames that each move one "
                       "trim control point of the file's first trimmed surface (its mask is "
                       "redrawn every frame) and report their median, the CPU ms per mask "
                       "redraw and the mask side ('-' for files without trims)."));
    parser.addOptions(
        {sizes,           partitions,  t1Partitions, frames, lights,  tables,   scaleModel,
         scaleFaces,      scaleSize,   smoke,        t2Size, samples, mode,     shading,
         floor,           json,        markdown,     plots,  noTrims, trimDrag, scalePartitionMode,
         scalePartitions, scaleShading});
    const QCommandLineOption trimMode(
        QStringLiteral("trim-mode"),
        QStringLiteral("exact (default: exact trim edges) or mask (the paper's trim mask alone, "
                       "for comparison)."),
        QStringLiteral("MODE"), QStringLiteral("exact"));
    parser.addOption(trimMode);
    const QCommandLineOption aaSamples(
        QStringLiteral("aa-samples"),
        QStringLiteral("Anti-aliasing samples per pixel of the renderer's timed frames, 1..%1 "
                       "(default 1; as render --samples).")
            .arg(kMaxSamples),
        QStringLiteral("N"), QStringLiteral("1"));
    parser.addOption(aaSamples);
    const QCommandLineOption aaMethod(
        QStringLiteral("aa-method"),
        QStringLiteral("How --aa-samples are drawn: accumulate (default) or coverage (as render "
                       "--aa-method)."),
        QStringLiteral("METHOD"), QStringLiteral("accumulate"));
    parser.addOption(aaMethod);
    const QCommandLineOption noAnalytic(
        QStringLiteral("no-analytic"),
        QStringLiteral("Knotwork's frames shade analytic faces by the Newton step onto their "
                       "NURBS, not in closed form (as render --no-analytic), for A/B."));
    parser.addOption(noAnalytic);
    const QCommandLineOption editLoop(
        QStringLiteral("edit-loop"),
        QStringLiteral(
            "Instead of Tables 1 and 2 (unless --tables is given): drag one control "
            "point of each FILE's largest free-form face (else its largest face, "
            "which the drag turns free-form) through --edit-steps steps and time, "
            "alternated step by step, Knotwork's edit to the editor's aliased frame "
            "(partial: the face's rectangle redrawn), to the same frame drawn whole and "
            "to the editor's still frame (4 samples), against OpenCASCADE's mesh peer: the "
            "face rebuilt as an OCCT face, re-meshed by BRepMesh at equal quality "
            "(searched as tools/peer_search.py does, or --peer-deflections), re-sent "
            "and drawn; and the peer at OCCT viewers' default deflections. JSON "
            "rows under \"editLoop\" (docs/PERFORMANCE.md ## Editing)."));
    const QCommandLineOption peerDeflections(
        QStringLiteral("peer-deflections"),
        QStringLiteral("--edit-loop: the peer's linear (model units) and angular (degrees) "
                       "deflections instead of the equal-quality search."),
        QStringLiteral("LIN,ANG"));
    const QCommandLineOption editSteps(QStringLiteral("edit-steps"),
                                       QStringLiteral("--edit-loop: drag steps, 1..10000 "
                                                      "(default 50)."),
                                       QStringLiteral("N"), QStringLiteral("50"));
    const QCommandLineOption editSize(
        QStringLiteral("edit-size"),
        QStringLiteral("--edit-loop, --zoom-loop: square frame side, 1..4096 "
                       "(default 1024)."),
        QStringLiteral("N"), QStringLiteral("1024"));
    const QCommandLineOption zoomLoop(
        QStringLiteral("zoom-loop"),
        QStringLiteral("Instead of Tables 1 and 2 (unless --tables is given): the close-up. For "
                       "each FILE, from the fitted view to --zoom-levels times closer on a "
                       "contour: the time to the first correct frame, Knotwork's against "
                       "OpenCASCADE's mesh peer, which re-meshes the faces in view at the "
                       "deflections that give equal quality at that zoom (searched), re-sends "
                       "and draws them; and the memory each holds for the view. JSON rows under "
                       "\"zoomLoop\" (docs/PERFORMANCE.md ## Close-up)."));
    const QCommandLineOption zoomLevels(QStringLiteral("zoom-levels"),
                                        QStringLiteral("--zoom-loop: zoom factors, each in "
                                                       "2..4096 (default 8,64)."),
                                        QStringLiteral("LIST"), QStringLiteral("8,64"));
    const QCommandLineOption zoomRepeats(QStringLiteral("zoom-repeats"),
                                         QStringLiteral("--zoom-loop: timed transitions per "
                                                        "method and zoom, 1..1000 (default 5)."),
                                         QStringLiteral("N"), QStringLiteral("5"));
    const QCommandLineOption fullFrames(
        QStringLiteral("full-frames"),
        QStringLiteral("--edit-loop: draw the editor's aliased frames whole after each step, "
                       "not only the rectangle the dragged face covered before and covers now "
                       "(docs/RENDERING.md, \"The partial frame\")."));
    const QCommandLineOption editPassTimes(
        QStringLiteral("pass-times"),
        QStringLiteral("--edit-loop: profile the editor's aliased frames pass by pass, each pass "
                       "ended by glFinish (their times then include the waits); medians per pass "
                       "in the JSON rows' \"partialPasses\"."));
    parser.addOptions({editLoop, peerDeflections, editSteps, editSize, fullFrames, editPassTimes,
                       zoomLoop, zoomLevels, zoomRepeats});
    const QCommandLineOption dragStep(
        QStringLiteral("drag-step"),
        QStringLiteral("Instead of Tables 1 and 2 (unless --tables is given): time one "
                       "control-point drag step with the Edge Continuity overlay on against off, "
                       "alternated step by step, on each FILE (default: --scale-model) as read "
                       "and tiled to each --drag-faces: edit, the dragged face's shared edges "
                       "re-measured (on: their bands re-made and uploaded; off: for the status "
                       "bar's 'opens N seams'), frame to glFinish. Medians of wall and CPU ms; "
                       "JSON rows under \"dragStep\" (docs/PERFORMANCE.md ## Editing)."));
    const QCommandLineOption continuityOverlay(
        QStringLiteral("continuity-overlay"),
        QStringLiteral("--drag-step: on, off or both (default)."), QStringLiteral("STATE"),
        QStringLiteral("both"));
    const QCommandLineOption dragFaces(
        QStringLiteral("drag-faces"),
        QStringLiteral("--drag-step: models per FILE, 0 = the file as read, N = tiled as the "
                       "scale table tiles it (its shared-edge record copied) to >= N faces, "
                       "each 0..1000000 (default 0,10000)."),
        QStringLiteral("LIST"), QStringLiteral("0,10000"));
    const QCommandLineOption dragSteps(
        QStringLiteral("drag-steps"),
        QStringLiteral("--drag-step: timed steps per overlay state, 1..10000 (default 30)."),
        QStringLiteral("N"), QStringLiteral("30"));
    const QCommandLineOption dragSize(
        QStringLiteral("drag-size"),
        QStringLiteral("--drag-step: square frame side, 1..4096 (default 1024)."),
        QStringLiteral("N"), QStringLiteral("1024"));
    parser.addOptions({dragStep, continuityOverlay, dragFaces, dragSteps, dragSize});
    parser.addPositionalArgument(QStringLiteral("FILES"),
                                 QStringLiteral(".knot projects or IGES/STEP/BREP/OBJ files "
                                                "(read as render reads them)."),
                                 QStringLiteral("[FILE...]"));
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QString cmd = args.value(0);

    bench::BenchConfig config;
    bench::ScaleConfig scaleConfig;
    std::vector<int> tableList;
    // --tables: 1, 2 and "scale" (kept as 3 here).
    QStringList tableNames = parser.value(tables).split(QLatin1Char(','));
    const bool scale = tableNames.removeAll(QStringLiteral("scale")) > 0;
    if (scale && tableNames.isEmpty())
        tableNames << QStringLiteral("0"); // no Table 1 or 2 (0 is accepted below only so)
    // Sizes stop at 4096: each quality frame reads back 10 float channels per pixel.
    if (!parseList(parser.value(sizes), 1, kMaxSide, config.sizes) ||
        !parseList(parser.value(partitions), kMinPartitions, kMaxPartitions, config.partitions) ||
        !parseIntIn(parser.value(t1Partitions), kMinPartitions, kMaxPartitions,
                    config.table1Partitions) ||
        !parseIntIn(parser.value(frames), 20, 100000, config.frames) ||
        !parseImageSize(parser.value(t2Size), config.table2Size) ||
        config.table2Size.width() > kMaxSide || config.table2Size.height() > kMaxSide ||
        !parseIntIn(parser.value(lights), 1, kMaxLights, config.lights) ||
        !parseList(tableNames.join(QLatin1Char(',')), scale ? 0 : 1, 2, tableList) ||
        !parseList(parser.value(scaleFaces), 1, 1000000, scaleConfig.faces) ||
        !parseScaleSize(parser.value(scaleSize), scaleConfig) ||
        !parseModeName(parser.value(mode), config.table1Mode) ||
        !parseShadingName(parser.value(shading), config.shading)) {
        printError(
            QStringLiteral(
                "%1: bad --sizes (1..4096), --partitions or "
                "--table1-partitions (%2..%3), --frames (>= 20), --table2-size (WxH, each in "
                "1..4096), --lights "
                "(1..%4), --tables (1, 2, scale), --scale-faces, --scale-size, --mode (exact, "
                "tessellated) or "
                "--depth (prepass, exact-depth) (see --help)")
                .arg(cmd)
                .arg(kMinPartitions)
                .arg(kMaxPartitions)
                .arg(kMaxLights));
        return kExitUsage;
    }
    bool floorOk = false;
    config.normalFloorDegrees = parser.value(floor).toDouble(&floorOk);
    if (!floorOk || !(config.normalFloorDegrees >= 0.0) || config.normalFloorDegrees > 180.0) {
        printError(QStringLiteral("%1: --normal-floor '%2' is not a number of degrees in 0..180")
                       .arg(cmd, parser.value(floor)));
        return kExitUsage;
    }
    const bool table1 = std::count(tableList.begin(), tableList.end(), 1) > 0;
    const bool table2 = std::count(tableList.begin(), tableList.end(), 2) > 0;
    config.trims = !parser.isSet(noTrims);
    config.trimDrag = parser.isSet(trimDrag);
    if (const auto mode = trimModeNamed(parser.value(trimMode))) {
        config.trimMode = *mode;
    } else {
        printError(QStringLiteral("%1: --trim-mode '%2' is not exact or mask")
                       .arg(cmd, parser.value(trimMode)));
        return kExitUsage;
    }
    if (!parseIntIn(parser.value(aaSamples), 1, kMaxSamples, config.aaSamples)) {
        printError(QStringLiteral("%1: --aa-samples '%2' is not in 1..%3")
                       .arg(cmd, parser.value(aaSamples))
                       .arg(kMaxSamples));
        return kExitUsage;
    }
    if (const auto method = antialiasingNamed(parser.value(aaMethod))) {
        config.aaMethod = *method;
    } else {
        printError(QStringLiteral("%1: --aa-method '%2' is not accumulate or coverage")
                       .arg(cmd, parser.value(aaMethod)));
        return kExitUsage;
    }
    if (config.trimDrag && (!config.trims || !table1)) {
        printError(QStringLiteral("%1: --trim-drag needs Table 1 (--tables 1) and trims (not "
                                  "--no-trims)")
                       .arg(cmd));
        return kExitUsage;
    }
    // FILES, or else the samples (Table 2: the multi-patch teapot, the paper's Table 2 case).
    QStringList files1, files2;
    for (const QString& f : parser.positionalArguments()) {
        if (!QFileInfo(f).isFile()) {
            printError(QStringLiteral("%1: no such file: %2").arg(cmd, f));
            return kExitBadInput;
        }
        files1 << f;
        files2 << f;
    }
    if (files1.isEmpty()) {
        const QDir dir(parser.value(samples));
        const QStringList knots =
            dir.entryList({QStringLiteral("*.knot")}, QDir::Files, QDir::Name);
        if (knots.isEmpty()) {
            printError(QStringLiteral("%1: no FILES given and no .knot samples in %2 (use "
                                      "--samples DIR)")
                           .arg(cmd, dir.path()));
            return kExitBadInput;
        }
        for (const QString& k : knots)
            files1 << dir.filePath(k);
        files2 << dir.filePath(knots.contains(QStringLiteral("teapot.knot"))
                                   ? QStringLiteral("teapot.knot")
                                   : knots.front());
    }
    if (table1)
        config.table1Files = files1;
    if (table2)
        config.table2Files = files2;
    scaleConfig.model = parser.value(scaleModel);
    const QString scaleMode = parser.value(scalePartitionMode);
    if (scaleMode != QLatin1String("uniform") && scaleMode != QLatin1String("adaptive")) {
        printError(QStringLiteral("%1: --scale-partition-mode '%2' is not uniform or adaptive")
                       .arg(cmd, scaleMode));
        return kExitUsage;
    }
    scaleConfig.partitioning = partitioningNamed(scaleMode);
    if (parser.isSet(scalePartitions) && !parseIntIn(parser.value(scalePartitions), kMinPartitions,
                                                     kMaxPartitions, scaleConfig.partitions)) {
        printError(QStringLiteral("%1: --scale-partitions '%2' is not in %3..%4")
                       .arg(cmd, parser.value(scalePartitions))
                       .arg(kMinPartitions)
                       .arg(kMaxPartitions));
        return kExitUsage;
    }
    if (!readDevelopmentSwitches(cmd, config.base))
        return kExitUsage;
    config.base.analyticFaces = !parser.isSet(noAnalytic);
    scaleConfig.base = config.base;
    if (const std::optional<AnalysisMode> m = parseAnalysisMode(parser.value(scaleShading))) {
        scaleConfig.base.analysis.mode = *m;
    } else {
        printError(QStringLiteral("%1: --scale-shading '%2' is not phong or an analysis mode (%3)")
                       .arg(cmd, parser.value(scaleShading),
                            analysisModeNames().mid(1).join(QStringLiteral(", "))));
        return kExitUsage;
    }
    scaleConfig.frames = config.frames;
    scaleConfig.trims = config.trims;
    bench::EditLoopConfig editConfig;
    const bool edit = parser.isSet(editLoop);
    if (!parseIntIn(parser.value(editSteps), 1, 10000, editConfig.steps) ||
        !parseIntIn(parser.value(editSize), 1, kMaxSide, editConfig.side)) {
        printError(
            QStringLiteral("%1: bad --edit-steps (1..10000) or --edit-size (1..4096)").arg(cmd));
        return kExitUsage;
    }
    if (parser.isSet(peerDeflections)) {
        const QStringList pair = parser.value(peerDeflections).split(QLatin1Char(','));
        bool okLin = false, okAng = false;
        const double lin = pair.value(0).toDouble(&okLin);
        const double ang = pair.value(1).toDouble(&okAng);
        if (pair.size() != 2 || !okLin || !okAng || !std::isfinite(lin) || !(lin > 0.0) ||
            !(ang > 0.0) || ang > 180.0) {
            printError(QStringLiteral("%1: --peer-deflections '%2' is not LIN,ANG (a positive "
                                      "distance, an angle in (0, 180] degrees)")
                           .arg(cmd, parser.value(peerDeflections)));
            return kExitUsage;
        }
        editConfig.peerDeflections = std::pair{lin, ang};
    }
    editConfig.fullFrames = parser.isSet(fullFrames);
    editConfig.passTimes = parser.isSet(editPassTimes);
    editConfig.files = files1;
    editConfig.lights = config.lights;
    editConfig.base = config.base;
    bench::ZoomLoopConfig zoomConfig;
    const bool zoom = parser.isSet(zoomLoop);
    std::vector<int> levels;
    if (!parseList(parser.value(zoomLevels), 2, 4096, levels) ||
        !parseIntIn(parser.value(zoomRepeats), 1, 1000, zoomConfig.repeats)) {
        printError(QStringLiteral("%1: bad --zoom-levels (each 2..4096) or --zoom-repeats "
                                  "(1..1000)")
                       .arg(cmd));
        return kExitUsage;
    }
    zoomConfig.zooms.assign(levels.begin(), levels.end());
    zoomConfig.files = files1;
    zoomConfig.side = editConfig.side;
    zoomConfig.lights = config.lights;
    zoomConfig.base = config.base;
    bench::DragStepConfig dragConfig;
    const bool drag = parser.isSet(dragStep);
    const QString overlayState = parser.value(continuityOverlay);
    if (!parseList(parser.value(dragFaces), 0, 1000000, dragConfig.faces) ||
        !parseIntIn(parser.value(dragSteps), 1, 10000, dragConfig.steps) ||
        !parseIntIn(parser.value(dragSize), 1, kMaxSide, dragConfig.side) ||
        (overlayState != QLatin1String("on") && overlayState != QLatin1String("off") &&
         overlayState != QLatin1String("both"))) {
        printError(QStringLiteral("%1: bad --drag-faces (0..1000000), --drag-steps (1..10000), "
                                  "--drag-size (1..4096) or --continuity-overlay (on, off, both)")
                       .arg(cmd));
        return kExitUsage;
    }
    dragConfig.overlayOn = overlayState != QLatin1String("off");
    dragConfig.overlayOff = overlayState != QLatin1String("on");
    dragConfig.files = parser.positionalArguments();
    if (dragConfig.files.isEmpty())
        dragConfig.files << parser.value(scaleModel);
    dragConfig.lights = config.lights;
    dragConfig.base = config.base;
    if ((edit || zoom || drag) && !parser.isSet(tables)) { // the loops alone
        config.table1Files.clear();
        config.table2Files.clear();
    }
    if (parser.isSet(smoke)) {
        editConfig.steps = std::min(editConfig.steps, 2);
        zoomConfig.repeats = 1;
        dragConfig.steps = std::min(dragConfig.steps, 2);
        config.frames = 2;
        config.warmup = 1;
        scaleConfig.frames = 2;
        scaleConfig.warmup = 1;
        scaleConfig.dragSteps = 2;
        printError(
            QStringLiteral("%1: --smoke: 2 frames per measurement, not a measurement").arg(cmd));
    }
    if (!startGui())
        return kExitBadInput;

    bench::BenchReport report;
    const auto progress = [](const QString& line) {
        printError(line);
    };
    // Each run ends at its first failure, named with the table it stopped.
    const auto failed = [&cmd](const Status& run, const QString& table) {
        if (run)
            return false;
        printError(table.isEmpty() ? QStringLiteral("%1: %2").arg(cmd, run.message())
                                   : QStringLiteral("%1: %2: %3").arg(cmd, table, run.message()));
        return true;
    };
    if (failed(bench::runBench(config, report, progress), {}))
        return kExitBadInput;
    bench::ScaleReport scaleReport;
    if (scale &&
        failed(bench::runScale(scaleConfig, scaleReport, progress), QStringLiteral("scale table")))
        return kExitBadInput;
    bench::EditLoopReport editReport;
    if (edit &&
        failed(bench::runEditLoop(editConfig, editReport, progress), QStringLiteral("edit loop")))
        return kExitBadInput;
    bench::ZoomLoopReport zoomReport;
    if (zoom &&
        failed(bench::runZoomLoop(zoomConfig, zoomReport, progress), QStringLiteral("zoom loop")))
        return kExitBadInput;
    bench::DragStepReport dragReport;
    if (drag &&
        failed(bench::runDragStep(dragConfig, dragReport, progress), QStringLiteral("drag step")))
        return kExitBadInput;
    QStringList argv = args.mid(1);
    const QString command = QStringLiteral("knotwork bench %1").arg(argv.join(QLatin1Char(' ')));
    QString plotDir = parser.value(plots);
    if (plotDir.isEmpty() && parser.isSet(markdown))
        plotDir = QFileInfo(parser.value(markdown)).absolutePath();
    QStringList written, relative;
    if (!plotDir.isEmpty()) {
        Status plotted = bench::writePlots(report, plotDir, written);
        if (plotted && scale)
            plotted = bench::writeScalePlot(scaleReport, plotDir, written);
        if (failed(plotted, {}))
            return kExitBadInput;
    }
    const QDir mdDir =
        parser.isSet(markdown) ? QFileInfo(parser.value(markdown)).absoluteDir() : QDir::current();
    for (const QString& w : written)
        relative << mdDir.relativeFilePath(QFileInfo(w).absoluteFilePath());
    QString md = bench::reportMarkdown(report, command, relative);
    if (scale)
        md += bench::scaleMarkdown(scaleReport);
    if (edit)
        md += bench::editLoopMarkdown(editReport, command);
    if (zoom)
        md += bench::zoomLoopMarkdown(zoomReport, command);
    if (drag)
        md += bench::dragStepMarkdown(dragReport, command);
    printOut(md);
    if (parser.isSet(markdown) && !writeFile(parser.value(markdown), md.toUtf8()))
        return kExitBadInput;
    QJsonObject root = benchJson(report, scale, scaleReport, command);
    if (edit)
        root.insert(QStringLiteral("editLoop"), bench::editLoopJson(editReport));
    if (zoom)
        root.insert(QStringLiteral("zoomLoop"), bench::zoomLoopJson(zoomReport));
    if (drag)
        root.insert(QStringLiteral("dragStep"), bench::dragStepJson(dragReport));
    if (parser.isSet(json) && !writeFile(parser.value(json), QJsonDocument(root).toJson()))
        return kExitBadInput;
    return kExitOk;
}

} // namespace kw::cli
