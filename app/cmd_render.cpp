// knotwork render FILE -o OUT [...]: headless render of a .knot project or a CAD file (IGES,
// STEP, BREP, OBJ) to an image (and AOVs).
#include "app/commands.h"
#include "app/model_loader.h"
#include "app/render_args.h"
#include "app/render_reference.h"
#include "model/io/inputcheck.h"
#include "model/io/meshobj.h"
#include "render/image_writer.h"
#include "render/offscreen_renderer.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QRegularExpression>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <unordered_set>
#include <vector>

namespace kw::cli {

namespace {

/// Reads a tagged mesh (model/io/meshobj.h) for `scene` into the renderer's form. False with
/// *error naming the file when it cannot be read or tags a surface `scene` does not have (a
/// mesh of another file would compare nonsense).
bool loadPeerMesh(const QString& path, const QString& knotPath, const Scene& scene,
                  TriangleMesh& mesh, QString* error) {
    Expected<TaggedMeshSet> read = readTaggedMeshObjFile(path);
    if (!read) {
        *error = read.message();
        return false;
    }
    const TaggedMeshSet& set = *read;
    std::unordered_set<std::uint32_t> ids;
    for (const Surface& s : scene.surfaces)
        ids.insert(s.id.value);
    for (const TaggedMesh& f : set.faces) {
        if (!ids.count(f.id.value)) {
            *error = QStringLiteral("%1: group surface_%2 names no surface of %3 (mesh and "
                                    "model from different files?)")
                         .arg(path)
                         .arg(f.id.value)
                         .arg(knotPath);
            return false;
        }
        SurfaceMesh s;
        s.id = f.id;
        s.positions.assign(f.positions.begin(), f.positions.end());
        s.normals.assign(f.normals.begin(), f.normals.end());
        s.uvs.assign(f.uvs.begin(), f.uvs.end());
        s.indices = f.indices;
        mesh.surfaces.push_back(std::move(s));
    }
    return true;
}

} // namespace

int runRender(const QStringList& args, const std::function<bool()>& startGui) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Render a .knot project, or an IGES, STEP, BREP or OBJ file (imported as 'knotwork "
        "convert' does; skipped faces and warnings on stderr), off-screen with the exact "
        "per-pixel NURBS renderer (or the tessellated baseline) and write the image (PNG with "
        "Qt; JPG, TIF, EXR with OpenImageIO). Uses the project's camera, "
        "or fits one to the scene. Needs OpenGL 4.5 core: on a machine without a display run "
        "under xvfb-run -a -s \"-screen 0 1280x1024x24\" with QT_QPA_PLATFORM=xcb."));
    const QCommandLineOption out({QStringLiteral("o"), QStringLiteral("output")},
                                 QStringLiteral("Image to write: .png, .jpg, .tif or .exr."),
                                 QStringLiteral("OUT"));
    const QCommandLineOption size(QStringLiteral("size"),
                                  QStringLiteral("Image size WxH (default 1024x768)."),
                                  QStringLiteral("WxH"), QStringLiteral("1024x768"));
    const QCommandLineOption aov(QStringLiteral("aov"),
                                 QStringLiteral("Also write a float EXR with channels id, u, v, "
                                                "P.x, P.y, P.z, N.x, N.y, N.z, Z."),
                                 QStringLiteral("AOV.exr"));
    const QCommandLineOption aovCurvature(
        QStringLiteral("aov-curvature"),
        QStringLiteral(
            "Add channels K, H, k1, k2 (exact curvature, see README) to the --aov EXR."));
    const QCommandLineOption timeFrames(
        QStringLiteral("time-frames"),
        QStringLiteral("After the image, render N more frames (1..10000) and print the median "
                       "frame time in ms (glFinish per frame) and the OpenGL renderer it ran on, "
                       "for docs/PERFORMANCE.md."),
        QStringLiteral("N"));
    const QCommandLineOption passTimes(
        QStringLiteral("pass-times"),
        QStringLiteral("With --time-frames: also print each pass's median process CPU, each pass "
                       "ended by glFinish (the frame's total then includes the waits)."));
    const QCommandLineOption progressive(
        QStringLiteral("progressive"),
        QStringLiteral("With --samples N > 1 (accumulate): draw the image a sample per frame, as "
                       "the editor does on software OpenGL (the image is the same); "
                       "--time-frames then times each sample's frame and the whole image."));
    const QCommandLineOption wire(QStringLiteral("wireframe"),
                                  QStringLiteral("Overlay the base polygon cells."));
    const QCommandLineOption net(QStringLiteral("control-net"),
                                 QStringLiteral("Overlay the control points and net."));
    const QCommandLineOption reference(
        QStringLiteral("reference"),
        QStringLiteral("Write the CPU reference instead of a GPU frame: each pixel's exact "
                       "trimmed surface by ray casting through the kernel (slow; no GL)."));
    const QCommandLineOption edgeReport(
        QStringLiteral("edge-report"),
        QStringLiteral("Also compare the frame with the CPU reference and write the edge "
                       "metrics (silhouette, cracks, id/depth, normal error) as JSON ('-': "
                       "stdout)."),
        QStringLiteral("REPORT.json"));
    const QCommandLineOption peerMesh(
        QStringLiteral("peer-mesh"),
        QStringLiteral("Draw this triangle mesh (from 'knotwork mesh': groups surface_<id> with "
                       "the ids of FILE's surfaces) instead of FILE's surfaces, with the "
                       "tessellated baseline's shading, FILE's materials, lights and view; "
                       "--aov, --edge-report and --time-frames work as for the surfaces."),
        QStringLiteral("MESH.obj"));
    const QCommandLineOption zoom(
        QStringLiteral("zoom"),
        QStringLiteral("Magnify the view F times (1..1e6) about the point shown at image "
                       "fractions X,Y (0,0 top left; default 0.5,0.5, the centre), which becomes "
                       "the centre: the camera turns to it and narrows its field of view, the eye "
                       "stays (a close-up that never puts the camera inside the part)."),
        QStringLiteral("F[@X,Y]"));
    parser.addOptions({out, size, aov, aovCurvature, timeFrames, passTimes, progressive, wire, net,
                       reference, edgeReport, peerMesh, zoom});
    const RenderCliOptions shared = addRenderOptions(
        parser, QString(), partitioningName(RenderOptions::Partitioning::Adaptive));
    parser.addPositionalArgument(
        QStringLiteral("FILE"),
        QStringLiteral("A .knot project, or .igs/.iges, .stp/.step, .brep/.brp or .obj."));
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QString cmd = args.value(0);
    const QStringList files = parser.positionalArguments();
    if (files.size() != 1 || !parser.isSet(out)) {
        printError(QStringLiteral("%1: expected one FILE and -o OUT (see --help)").arg(cmd));
        return kExitUsage;
    }
    RenderOptions options;
    QSize imageSize;
    if (!parseImageSize(parser.value(size), imageSize)) {
        printError(QStringLiteral("%1: --size '%2' is not WxH with 1..16384")
                       .arg(cmd, parser.value(size)));
        return kExitUsage;
    }
    if (!readRenderOptions(parser, shared, cmd, options))
        return kExitUsage;
    options.wireframe = parser.isSet(wire);
    options.controlNet = parser.isSet(net);
    const QString outPath = parser.value(out);
    const QString aovPath = parser.value(aov);
    if (!isSupportedImagePath(outPath)) {
        printError(QStringLiteral("%1: unsupported image type (use .png, .jpg, .tif or .exr)")
                       .arg(outPath));
        return kExitUsage;
    }
    if (parser.isSet(aov) && !aovPath.endsWith(QLatin1String(".exr"), Qt::CaseInsensitive)) {
        printError(QStringLiteral("%1: the AOV image must be an .exr file").arg(aovPath));
        return kExitUsage;
    }

    if (parser.isSet(aovCurvature) && !parser.isSet(aov)) {
        printError(QStringLiteral("%1: --aov-curvature needs --aov AOV.exr").arg(cmd));
        return kExitUsage;
    }
    int timedFrames = 0;
    if (parser.isSet(timeFrames) && !parseIntIn(parser.value(timeFrames), 1, 10000, timedFrames)) {
        printError(QStringLiteral("%1: --time-frames '%2' is not in 1..10000")
                       .arg(cmd, parser.value(timeFrames)));
        return kExitUsage;
    }
    if (parser.isSet(passTimes) && timedFrames == 0) {
        printError(QStringLiteral("%1: --pass-times needs --time-frames N").arg(cmd));
        return kExitUsage;
    }
    double zoomFactor = 1.0;
    glm::dvec2 zoomAt(0.5);
    if (parser.isSet(zoom)) {
        static const QRegularExpression form(
            QStringLiteral("^([0-9.eE+-]+)(?:@([0-9.eE+-]+),([0-9.eE+-]+))?$"));
        const QRegularExpressionMatch m = form.match(parser.value(zoom));
        bool ok = m.hasMatch();
        if (ok) {
            zoomFactor = m.captured(1).toDouble(&ok);
            ok = ok && zoomFactor >= 1.0 && zoomFactor <= 1e6;
        }
        if (ok && m.hasCaptured(2)) {
            bool okX = false, okY = false;
            zoomAt = {m.captured(2).toDouble(&okX), m.captured(3).toDouble(&okY)};
            ok = okX && okY && zoomAt.x >= 0.0 && zoomAt.x <= 1.0 && zoomAt.y >= 0.0 &&
                 zoomAt.y <= 1.0;
        }
        if (!ok) {
            printError(QStringLiteral("%1: --zoom '%2' is not F[@X,Y] with F in 1..1e6 and "
                                      "X, Y in 0..1")
                           .arg(cmd, parser.value(zoom)));
            return kExitUsage;
        }
    }
    // Anti-aliasing reads the grids' texels about each trim-edge pixel (up to 4 x 4, else it
    // keeps the aliased answer), so coarser grids would change its edges: only --samples 1.
    if (options.samples == 1)
        options.trimGridCap = trimGridCapForImage(imageSize, zoomFactor);
    if (parser.isSet(peerMesh) && (parser.isSet(reference) || parser.isSet(aovCurvature))) {
        printError(
            QStringLiteral("%1: --peer-mesh excludes --reference and --aov-curvature").arg(cmd));
        return kExitUsage;
    }
    if (parser.isSet(progressive)) {
        if (options.samples == 1 ||
            options.antialiasing != RenderOptions::Antialiasing::Accumulate ||
            parser.isSet(peerMesh) || parser.isSet(reference)) {
            printError(QStringLiteral("%1: --progressive needs --samples N > 1 with --aa-method "
                                      "accumulate, and neither --peer-mesh nor --reference")
                           .arg(cmd));
            return kExitUsage;
        }
        options.progressive = true;
    }
    if (parser.isSet(reference) && parser.isSet(edgeReport)) {
        printError(QStringLiteral("%1: --reference and --edge-report exclude each other").arg(cmd));
        return kExitUsage;
    }
    // The input before the display: a missing file is the error to report, not the display.
    if (const QString why = checkRegularFile(files[0]).message(); !why.isEmpty()) {
        printError(QStringLiteral("%1: %2").arg(files[0], why));
        return kExitBadInput;
    }
    if (!startGui())
        return kExitBadInput;

    // The file is read (a CAD file by its child process) and the camera fitted on a second
    // thread while this one starts OpenGL: the first image costs the longer of the two, not
    // their sum (docs/PERFORMANCE.md ## Start-up).
    const double aspect = double(imageSize.width()) / double(imageSize.height());
    ModelLoader loader;
    loader.start(files[0], aspect);
    const bool withAov = parser.isSet(aov) || parser.isSet(edgeReport);
    OffscreenRenderer renderer;
    Status glReady; // the reference is drawn on the CPU
    if (!parser.isSet(reference)) {
        glReady = renderer.create();
        if (glReady)
            glReady = renderer.setSize(imageSize, withAov, parser.isSet(aovCurvature));
    }
    QString error;
    Expected<LoadedModel> model = loader.wait();
    if (!model) {
        printError(model.message());
        return kExitBadInput;
    }
    printImportRemarks(files[0], model->import.report);
    Document doc;
    if (const Status reset = doc.resetScene(std::move(model->import.scene)); !reset) {
        printError(QStringLiteral("%1: %2").arg(files[0], reset.message()));
        return kExitBadInput;
    }
    const Scene& scene = doc.scene();
    // The project's display settings, unless the command line says otherwise.
    if (!scene.display.partitionMode.isEmpty() && !parser.isSet(shared.partitionMode))
        options.partitioning = partitioningNamed(scene.display.partitionMode);
    if (!scene.display.partitionMode.isEmpty() && !parser.isSet(shared.pixelTolerance))
        options.pixelTolerance = scene.display.pixelTolerance;
    if (!scene.display.background.isEmpty() && !parser.isSet(shared.background))
        backgroundNamed(scene.display.background, options); // validated with the file
    // The project's sections (validated with the file) unless --section gives others.
    if (!parser.isSet(shared.section)) {
        options.sections = scene.display.sections;
        options.sectionCaps = scene.display.sectionCaps && !parser.isSet(shared.noCaps);
    }
    if (!parser.isSet(shared.pull))
        options.analysis.pullDirection = scene.display.pullDirection;
    if (!parser.isSet(shared.draftAngle))
        options.analysis.draftAngleDegrees = scene.display.draftAngleDegrees;
    Camera camera = model->camera;
    if (parser.isSet(zoom))
        camera = zoomedCamera(camera, zoomFactor, zoomAt, aspect);
    if (parser.isSet(reference)) {
        if (const Status written = writeReferenceRender(scene, camera, imageSize,
                                                        options.lightCount, outPath, aovPath);
            !written) {
            printError(written.message());
            return kExitBadInput;
        }
        return kExitOk;
    }
    TriangleMesh mesh;
    if (parser.isSet(peerMesh) &&
        !loadPeerMesh(parser.value(peerMesh), files[0], scene, mesh, &error)) {
        printError(error);
        return kExitBadInput;
    }
    if (!glReady) {
        printError(QStringLiteral("%1: %2").arg(cmd, glReady.message()));
        return kExitBadInput;
    }
    std::int64_t meshBytes = 0;
    if (parser.isSet(peerMesh) && (meshBytes = renderer.setMesh(0, mesh)) < 0) {
        printError(QStringLiteral("%1: cannot send the mesh to the GPU").arg(cmd));
        return kExitBadInput;
    }
    // One frame: the document's surfaces, or the peer mesh in their place.
    const auto frame = [&] {
        return parser.isSet(peerMesh) ? renderer.renderMesh(doc, 0, camera, options)
                                      : renderer.render(doc, camera, options);
    };
    // A progressive image is drawn until all its samples are in.
    for (int k = 0; k < std::max(options.samples, 1); ++k) {
        if (const Status drawn = frame(); !drawn) {
            printError(QStringLiteral("%1: rendering failed: %2").arg(files[0], drawn.message()));
            return kExitBadInput;
        }
        if (!renderer.lastReport().refining)
            break;
    }
    // Messy trims were drawn as repaired; say what was repaired.
    for (const QString& w : renderer.lastReport().warnings)
        printError(QStringLiteral("%1: warning: %2").arg(files[0], w));
    Status written = writeColorImage(renderer.colorImage(), outPath);
    if (written && parser.isSet(aov))
        written = writeAovImage(renderer.aov(), aovPath);
    if (written && parser.isSet(edgeReport))
        written = writeEdgeReport(scene, camera, renderer.aov(), parser.value(edgeReport));
    if (!written) {
        printError(written.message());
        return kExitBadInput;
    }
    if (timedFrames > 0) {
        // Steady-state frames: nothing changes between them, so no uploads; the median is
        // robust to a shared machine's hiccups.
        // Progressive: each frame draws a sample, the image restarted every --samples frames;
        // the whole image's time is the sum of its frames'.
        std::vector<double> ms, cpuMs, imageMs, firstMs, laterMs;
        // The process's CPU time too (llvmpipe's rasteriser threads included): on a shared,
        // loaded machine the wall time also counts the other processes' turns.
        const auto processCpuMs = [] {
            timespec t{};
            ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
            return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
        };
        double image = 0.0;
        // --pass-times: each pass's process CPU too, ended by glFinish
        // (Renderer::setPassProfiling; the frame's total then includes the waits).
        const bool profilePasses = parser.isSet(passTimes);
        renderer.renderer().setPassProfiling(profilePasses);
        std::vector<std::vector<double>> passCpu(PassTimes::kCount);
        for (int k = 0; k < timedFrames; ++k) {
            if (options.progressive && k % options.samples == 0)
                renderer.renderer().restartProgressive();
            QElapsedTimer t;
            t.start();
            const double cpu = processCpuMs();
            if (const Status drawn = frame(); !drawn) {
                printError(
                    QStringLiteral("%1: rendering failed: %2").arg(files[0], drawn.message()));
                return kExitBadInput;
            }
            renderer.finish();
            ms.push_back(double(t.nsecsElapsed()) * 1e-6);
            cpuMs.push_back(processCpuMs() - cpu);
            if (const PassTimes& p = renderer.lastReport().passes; p.measured)
                for (int pass = 0; pass < PassTimes::kCount; ++pass)
                    passCpu[std::size_t(pass)].push_back(p.cpuMs[pass]);
            if (options.progressive) {
                const FrameReport& r = renderer.lastReport();
                (r.samplesInImage == 1 ? firstMs : laterMs).push_back(ms.back());
                image += ms.back();
                if (!r.refining) {
                    imageMs.push_back(image);
                    image = 0.0;
                }
            }
        }
        const auto median = [](std::vector<double>& v) {
            std::sort(v.begin(), v.end());
            return v.empty() ? 0.0 : v[v.size() / 2];
        };
        if (options.progressive && !imageMs.empty())
            printOut(QStringLiteral("%1: progressive: median frame %2 ms for a first sample (a "
                                    "moving view's frame), %3 ms for a later one; median whole "
                                    "image of %4 samples %5 ms over %6 images\n")
                         .arg(files[0])
                         .arg(median(firstMs), 0, 'f', 2)
                         .arg(median(laterMs), 0, 'f', 2)
                         .arg(options.samples)
                         .arg(median(imageMs), 0, 'f', 2)
                         .arg(imageMs.size()));
        if (profilePasses) {
            QString line;
            for (int pass = 0; pass < PassTimes::kCount; ++pass)
                if (const double m = median(passCpu[std::size_t(pass)]); m >= 0.05)
                    line += QStringLiteral(" %1 %2")
                                .arg(QLatin1String(PassTimes::name(pass)))
                                .arg(m, 0, 'f', 1);
            printOut(QStringLiteral("%1: median pass CPU ms:%2\n").arg(files[0], line));
        }
        std::sort(ms.begin(), ms.end());
        // The GL renderer too: a timing is only comparable with one taken on the same device.
        printOut(
            QStringLiteral(
                "%1: median frame %2 ms (process CPU %6 ms) over %3 frames (--shading %4) on %5\n")
                .arg(files[0])
                .arg(ms[ms.size() / 2], 0, 'f', 2)
                .arg(timedFrames)
                .arg(analysisModeName(options.analysis.mode), renderer.renderer().glDescription())
                .arg(median(cpuMs), 0, 'f', 2));
    }
    const FrameReport::Partitions& parts = renderer.lastReport().partitions;
    if (parser.isSet(peerMesh))
        printOut(QStringLiteral("%1: peer mesh %2: %3 triangles, %4 vertices, %5 bytes on the GPU "
                                "(%6 faces drawn)\n")
                     .arg(files[0], parser.value(peerMesh))
                     .arg(mesh.triangleCount())
                     .arg(mesh.vertexCount())
                     .arg(meshBytes)
                     .arg(renderer.lastReport().surfaces));
    else if (options.mode == RenderMode::Exact)
        printOut(
            options.partitioning == RenderOptions::Partitioning::Adaptive
                ? QStringLiteral("%1: adaptive partitions: %2 cells, screen bound %3 px "
                                 "(tolerance %4 px), %5 edge skirt triangles, %6 affine "
                                 "surfaces drawn as their polygon, %7 surfaces shaded by "
                                 "the deferred pass, %8 analytic faces in closed form, %9 "
                                 "cells crossed by a section plane, %10 faces drawn by covers\n")
                      .arg(files[0])
                      .arg(parts.cells)
                      .arg(parts.worstBoundPixels, 0, 'f', 3)
                      .arg(options.pixelTolerance)
                      .arg(parts.skirtTriangles)
                      .arg(parts.affineSurfaces)
                      .arg(parts.deferredSurfaces)
                      .arg(parts.analyticSurfaces)
                      .arg(parts.sectionCrossedCells)
                      .arg(parts.coverSurfaces)
                : QStringLiteral("%1: uniform partitions: %2 cells\n")
                      .arg(files[0])
                      .arg(parts.cells));
    printOut(QStringLiteral("%1: %2 bytes resident on the GPU\n")
                 .arg(files[0])
                 .arg(renderer.lastReport().gpuBytes.total()));
    printOut(
        QStringLiteral("%1: %2x%3 %4 render of %5 surface(s) -> %6%7\n")
            .arg(files[0])
            .arg(imageSize.width())
            .arg(imageSize.height())
            .arg(parser.isSet(peerMesh) ? QStringLiteral("peer-mesh") : modeName(options.mode))
            .arg(scene.surfaces.size())
            .arg(outPath, parser.isSet(aov) ? QStringLiteral(", AOVs -> ") + aovPath : QString()));
    return kExitOk;
}

} // namespace kw::cli
