// CAD import dispatch by format; the OpenCASCADE formats live in occtimport.cpp.
#include "model/cad/cadimport.h"

#include "model/cad/cadprocess.h"
#include "model/document/validation.h"
#include "model/io/inputcheck.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "model/nurbs/trim.h"

#include <QElapsedTimer>
#include <QFileInfo>

namespace kw {

CadFormat cadFormatFromPath(const QString& path) {
    const QString ext = QFileInfo(path).suffix().toLower();
    if (ext == QLatin1String("igs") || ext == QLatin1String("iges"))
        return CadFormat::Iges;
    if (ext == QLatin1String("stp") || ext == QLatin1String("step"))
        return CadFormat::Step;
    if (ext == QLatin1String("brep") || ext == QLatin1String("brp"))
        return CadFormat::Brep;
    if (ext == QLatin1String("obj"))
        return CadFormat::Obj;
    if (ext == QLatin1String("knot"))
        return CadFormat::Knot;
    return CadFormat::Unknown;
}

QString cadFormatName(CadFormat format) {
    switch (format) {
    case CadFormat::Iges:
        return QStringLiteral("IGES");
    case CadFormat::Step:
        return QStringLiteral("STEP");
    case CadFormat::Brep:
        return QStringLiteral("BREP");
    case CadFormat::Obj:
        return QStringLiteral("OBJ");
    case CadFormat::Knot:
        return QStringLiteral(".knot");
    case CadFormat::Unknown:
        break;
    }
    return QStringLiteral("unknown");
}

QString occtUnavailableMessage() {
    return QStringLiteral("IGES/STEP/BREP import is unavailable: Knotwork was built without "
                          "OpenCASCADE");
}

// Loops bridged on import are saved closed (docs/FILE_FORMAT.md): every gap the file leaves
// between consecutive trim curves is closed here, as the renderer would bridge it, and reported.
Status finishImport(ImportResult& result, const QString& path) {
    result.report.warnings << closeSceneTrimLoops(result.scene);
    const QString why = checkScene(result.scene).message();
    if (!why.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(path, why), path);
    return ok();
}

bool occtAvailable() {
#ifdef KW_HAVE_OCCT
    return true;
#else
    return false;
#endif
}

Expected<ImportResult> importFile(const QString& path, const ImportProgress& progress) {
    const CadFormat format = cadFormatFromPath(path);
    // A device, FIFO or directory is named at once, never opened (each reader then sniffs
    // the first bytes of its format).
    if (const QString why = checkRegularFile(path).message(); !why.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(path, why), path);
    QElapsedTimer timer;
    timer.start();
    ImportResult result;
    switch (format) {
    case CadFormat::Iges:
    case CadFormat::Step:
    case CadFormat::Brep: {
        auto r = importInChildProcess(path, format, progress);
        if (!r)
            return std::move(r).error();
        result = std::move(*r);
        break;
    }
    case CadFormat::Obj:
        if (Status read = readObjFile(path, result.scene, result.report); !read)
            return std::move(read).error();
        if (result.scene.surfaces.empty())
            return Error(QStringLiteral("%1: no surface could be imported (%2)")
                             .arg(path, result.report.skipped.value(0)),
                         path);
        break;
    case CadFormat::Knot: {
        auto scene = readKnotFile(path);
        if (!scene)
            return std::move(scene).error();
        result.scene = std::move(*scene);
        result.report.facesImported = static_cast<int>(result.scene.surfaces.size());
        break;
    }
    case CadFormat::Unknown:
        return Error(QStringLiteral("%1: unknown file type (expected .igs, .iges, .stp, .step, "
                                    ".brep, .obj or .knot)")
                         .arg(path),
                     path);
    }
    if (format == CadFormat::Obj || format == CadFormat::Knot)
        for (int k = 0; k < static_cast<int>(result.scene.surfaces.size()); ++k)
            result.sourceFaces.push_back(k + 1);
    if (Status finished = finishImport(result, path); !finished)
        return std::move(finished).error();
    result.report.seconds = timer.elapsed() / 1000.0;
    return result;
}

Expected<ImportResult> openModelFile(const QString& path, const ImportProgress& progress) {
    // Any other name is read as .knot, as these tools always did (its error says what is wrong).
    if (const CadFormat f = cadFormatFromPath(path);
        f != CadFormat::Knot && f != CadFormat::Unknown)
        return importFile(path, progress);
    Expected<Scene> scene = readKnotFile(path);
    if (!scene)
        return std::move(scene).error();
    ImportResult result;
    result.scene = std::move(*scene);
    result.report.facesImported = static_cast<int>(result.scene.surfaces.size());
    for (int k = 0; k < result.report.facesImported; ++k)
        result.sourceFaces.push_back(k + 1);
    return result;
}

} // namespace kw
