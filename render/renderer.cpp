// Renderer: context check, per-frame state setup, cache sync, passes in order, overlays, the
// frame report, and the pick query.
#include "render/damage_tiles.h"
#include "render/depth_convention.h"
#include "render/gl_context.h"
#include "render/renderer_impl.h"
#include "render/thread_clock.h"

#include <QElapsedTimer>
#include <QOpenGLContext>
#include <QOpenGLShaderProgram>
#include <QOpenGLVersionFunctionsFactory>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace kw {

namespace {

double msSince(const QElapsedTimer& t) {
    return double(t.nsecsElapsed()) * 1e-6;
}

/// The first reason `target` and `options` cannot make a frame, or ok.
Status checkFrameRequest(const RenderTarget& target, const RenderOptions& options) {
    if (target.size.width() <= 0 || target.size.height() <= 0)
        return Error(QStringLiteral("render size %1x%2 is empty")
                         .arg(target.size.width())
                         .arg(target.size.height()));
    if (options.sections.size() > size_t(kMaxSectionPlanes))
        return Error(QStringLiteral("%1 section planes, at most %2")
                         .arg(options.sections.size())
                         .arg(kMaxSectionPlanes));
    for (const SectionPlane& p : options.sections)
        if (Status valid = checkSectionPlane(p); !valid)
            return valid;
    return ok();
}

} // namespace

Renderer::Renderer() : d(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

bool Renderer::isInitialized() const {
    return d->gl != nullptr;
}

QString Renderer::glDescription() const {
    return d->glDescription;
}

Status Renderer::initialize() {
    QOpenGLContext* ctx = QOpenGLContext::currentContext();
    if (!ctx)
        return Error(QStringLiteral("no current OpenGL context"));
    if (const QString got = openGlShortfall(ctx->format(), ctx->isOpenGLES()); !got.isEmpty())
        return Error(QStringLiteral("OpenGL 4.5 core is required, got %1").arg(got));
    auto* gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_5_Core>(ctx);
    if (!gl || !gl->initializeOpenGLFunctions())
        return Error(QStringLiteral("OpenGL 4.5 core functions are not available"));
    d->gl = gl;
    d->glDescription = currentContextReport();
    d->scene.initialize(gl, &d->shaders);
    d->exact.initialize(gl, &d->shaders);
    d->antialias.initialize(gl, &d->shaders);
    d->accumulate.initialize(gl, &d->shaders);
    d->floatDepth.initialize(gl);
    GLint maxSamples = 1;
    gl->glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    d->maxSamples = std::clamp(int(maxSamples), 1, kMaxSamples);
    d->tessellated.initialize(gl, &d->shaders);
    d->wireframe.initialize(gl, &d->shaders);
    d->controlNet.initialize(gl, &d->shaders);
    d->edgeBands.initialize(gl, &d->shaders);
    // No programs are built here: each pass asks the ShaderLibrary for the variant a frame
    // needs when it first draws it (a one-surface render builds 2 programs, not 6), and a
    // shader that does not build fails that frame with the compiler's message.
    return ok();
}

FrameReport Renderer::render(const Document& doc, const Camera& camera, const RenderTarget& target,
                             const RenderOptions& options) {
    return d->renderFrame(doc, camera, target, options, nullptr);
}

FrameReport Renderer::Impl::renderFrame(const Document& doc, const Camera& camera,
                                        const RenderTarget& target, RenderOptions options,
                                        const QRect* pickPixel) {
    QElapsedTimer total;
    total.start();
    const double cpuStart = threadCpuMs();
    const RenderOptions asked = options; // for a partial frame drawn again whole
    FrameReport report;
    const auto fail = [&](const QString& message) {
        report.ok = false;
        report.error = message;
        report.cpuMs.total = msSince(total);
        return report;
    };
    if (!gl)
        return fail(QStringLiteral("Renderer::render called before initialize()"));
    if (Status request = checkFrameRequest(target, options); !request)
        return fail(request.message());
    // A preview of a moving view: fewer pixels, each exact, magnified into the target.
    const bool preview = options.previewScale < 1.0 && !target.aov && !pickPixel;
    QSize size = target.size;
    if (preview) {
        const double s = std::clamp(options.previewScale, 1.0 / 8.0, 1.0);
        size = QSize(std::max(1, int(std::lround(size.width() * s))),
                     std::max(1, int(std::lround(size.height() * s))));
        options.samples = 1;
        options.progressive = false;
    }
    report.drawnSize = size;
    options.writeAov = target.aov;
    options.writeCurvatureAov = target.aov && target.curvatureAov;
    // The scene's bounds (the camera planes) are kept per surface by the GPU scene, which
    // follows the document's changes: no walk over every control point per frame.
    clock.start(gl, &report.passes);
    scene.prepare(doc);
    glm::dvec3 box[2];
    // The target's aspect: a preview's rounded size must not stretch the image.
    FrameCamera fc = frameCamera(camera, scene.bounds(box[0], box[1]) ? &box : nullptr,
                                 double(target.size.width()) / target.size.height());
    fc.viewport = glm::ivec2(size.width(), size.height());
    // A frame of a view being edited keeps the last one's camera planes while they hold the
    // scene: an edit that moves the scene's bounds a little then changes no depth elsewhere
    // (render/partial_frame.h).
    if (options.frameReuse != RenderOptions::FrameReuse::None && !pickPixel && !target.aov)
        if (const std::optional<FrameCamera> kept = partial.keptCamera(
                camera, size, target.size, scene.bounds(box[0], box[1]) ? &box : nullptr))
            fc = *kept;
    if (pickPixel) { // beginTarget's shifted viewport
        fc.viewportOrigin = glm::ivec2(-pickPixel->x(), -pickPixel->y());
        fc.pickPixel = glm::ivec2(pickPixel->x(), pickPixel->y());
    }
    const std::vector<Light> lights =
        lightsFor(doc.scene(), camera, options.lightCount, options.headlight);

    resetPassCounters();

    // The GPU scene first: trim masks draw into their own framebuffer.
    const Status synced = scene.sync(doc, fc, options, report);
    clock.mark(PassTimes::Sync);

    const int samples = frameSamples(options, target.aov, pickPixel != nullptr, report);
    if (!options.sections.empty() &&
        (!options.splitCellsBySections ||
         (samples > 1 && options.antialiasing == RenderOptions::Antialiasing::Coverage))) {
        // The pre-pass's depth is the base polygon's, which cannot tell on which side of a
        // plane a pixel's exact point lies: without the split of the cut surfaces' cells
        // (ExactPlanner, kw::splitCells; none in MSAA frames) every cell is drawn with exact
        // depth. The back faces of closed solids a plane crosses are where the caps are drawn:
        // the planner keeps them (ExactPlanner::backCulled).
        options.shading = RenderOptions::Shading::ExactDepth;
    }
    const FrameTargets targets =
        frameTargets(target, samples, options, preview, pickPixel != nullptr, size, report);
    AntialiasTarget* const aa = targets.aa;
    AccumulateTarget* const accumulated = targets.accumulated;
    const RenderTarget& drawn = targets.drawn;
    report.analysisRange = resolveAnalysisRange(doc, options.analysis);

    // The partial frame (render/partial_frame.h): an aliased exact frame kept in the own
    // framebuffer, of which the next frame of the same view redraws only what changed.
    const PartialPlan plan = planPartialFrame(doc, target, size, fc, lights, options, targets,
                                              pickPixel != nullptr, report);
    const bool unchanged = plan.unchanged;

    QElapsedTimer phase;
    phase.start();
    const SampleRange range = sampleRange(doc, camera, target, size, options, samples,
                                          accumulated != nullptr, pickPixel != nullptr);
    const size_t firstSample = range.first, endSample = range.end;
    RenderTarget sampleTarget = drawn;
    if (accumulated)
        sampleTarget.framebuffer = accumulated->sampleFramebuffer();
    // The frame's depth convention, for the overlays too when no sample is drawn (beginTarget
    // sets it again per sample).
    beginReversedDepth(gl);
    // The frame goes on while each step succeeds; the first failure is the frame's error.
    QString error;
    const auto step = [&error](const Status& done) {
        if (!done)
            error = done.message();
        return bool(done);
    };
    bool backCulledMoved = false;
    bool ok =
        unchanged || step(drawRegions(plan, range, sampleTarget, target.framebuffer, targets, fc,
                                      lights, options, pickPixel, report, backCulledMoved));
    clock.mark(PassTimes::Antialiasing);
    if (backCulledMoved) {
        // A solid's back faces skipped now and drawn in the kept frame, or the reverse: that
        // reaches every face of the solid, not only the rectangle's.
        partialScissor = QRect();
        gl->glDisable(GL_SCISSOR_TEST);
        endReversedDepth(gl);
        clock.stop();
        wholeFrameAgain = true;
        FrameReport again = renderFrame(doc, camera, target, asked, pickPixel);
        wholeFrameAgain = false;
        return again;
    }
    report.cpuMs.surfaces = msSince(phase);
    const double firstDraw =
        options.mode == RenderMode::Exact ? exact.firstDrawCpuMs : tessellated.firstDrawCpuMs;
    report.cpuMs.beforeDraws = (firstDraw >= 0.0 ? firstDraw : threadCpuMs()) - cpuStart;
    phase.restart();
    if (ok && !unchanged && (options.wireframe || options.controlNet || options.edgeBands))
        ok = step(drawOverlays(target, fc, options));
    clock.mark(PassTimes::Overlays);
    if (!partialScissor.isNull()) {
        partialScissor = QRect(); // the whole kept frame goes to the host
        gl->glDisable(GL_SCISSOR_TEST);
    }
    if (drawn.framebuffer != target.framebuffer)
        report.presentedPixels = present(plan, target, preview);
    else
        presented.reset(); // drawn over the host, whichever framebuffer it is
    report.keptInHost = presented.has_value();
    clock.mark(PassTimes::Present);
    clock.stop();
    report.cpuMs.overlays = msSince(phase);
    gl->glBindVertexArray(0);
    gl->glUseProgram(0);
    if (pickPixel)
        gl->glDisable(GL_SCISSOR_TEST);
    endReversedDepth(gl);

    if (!ok)
        progressKey.reset(); // a sum with a failed sample in it is not kept
    if (accumulated) {
        report.samplesInImage = accumulate.added();
        report.refining = ok && options.progressive && accumulate.added() < samples;
    } else if (aa) {
        report.samplesInImage = samples;
    }
    reportPassFigures(report);
    if (!ok)
        report.error = error;
    else if (!synced)
        report.error = synced.message();
    report.ok = ok && synced;
    if (!pickPixel) {
        const bool pickable =
            report.ok && !preview && !target.aov && options.mode == RenderMode::Exact;
        rememberFrame(LastFrame{&doc, doc.revision(), camera, size, sampleTarget.framebuffer}, fc,
                      options, plan, firstSample < endSample, pickable, report.ok);
    }
    report.cpuMs.total = msSince(total);
    return report;
}

std::int64_t Renderer::Impl::present(const PartialPlan& plan, const RenderTarget& target,
                                     bool preview) {
    const Presented now{target.framebuffer, target.size, floatDepth.serial()};
    // A partial frame changed its rectangles of the kept frame alone: where the host still
    // holds the last frame copied, those and what the host drew over are all that differ.
    const bool holdsLast =
        !preview && plan.damage && target.drawnOver && presented && *presented == now;
    // A preview's magnified copy is not the kept frame's pixels.
    presented = preview ? std::nullopt : std::optional<Presented>(now);
    if (!holdsLast) {
        floatDepth.copyColourTo(target.framebuffer, target.size);
        return std::int64_t(target.size.width()) * target.size.height();
    }
    std::vector<glm::ivec4> rects;
    if (!plan.unchanged)
        rects = plan.regions;
    if (const QRect& over = *target.drawnOver; !over.isEmpty())
        rects.emplace_back(over.x(), over.y(), over.x() + over.width(), over.y() + over.height());
    return floatDepth.copyColourRects(target.framebuffer, rects);
}

Renderer::Impl::PartialPlan
Renderer::Impl::planPartialFrame(const Document& doc, const RenderTarget& target, QSize size,
                                 FrameCamera& fc, const std::vector<Light>& lights,
                                 const RenderOptions& options, const FrameTargets& targets,
                                 bool pick, FrameReport& report) {
    PartialPlan plan;
    plan.keepable = options.frameReuse != RenderOptions::FrameReuse::None && !pick && !target.aov &&
                    !targets.aa && !targets.accumulated && options.mode == RenderMode::Exact &&
                    floatDepth.framebuffer() != 0 &&
                    targets.drawn.framebuffer == floatDepth.framebuffer();
    if (!plan.keepable)
        return plan;
    plan.view = partialView(doc, target, size, fc, lights, options, report.analysisRange);
    plan.footprints = surfaceFootprints(fc, options);
    std::vector<DamagedSurface> changed;
    bool bandsChanged = false;
    if (options.frameReuse == RenderOptions::FrameReuse::Partial && !wholeFrameAgain)
        plan.damage =
            partial.damage(plan.view, exact.prepassWrites(), plan.footprints, fc.viewProjection,
                           options.edgeBands.get(), &changed, &bandsChanged);
    if (!plan.damage)
        return plan;
    const glm::ivec4& damage = *plan.damage;
    report.partial = true;
    plan.unchanged = damage.z <= damage.x; // the kept frame is the image
    if (plan.unchanged)
        return plan;
    fc.reach = damage;
    partialScissor = QRect(damage.x, damage.y, damage.z - damage.x, damage.w - damage.y);
    // Tiles are taken in the frames after this one for the surfaces it redraws (damageRegions
    // marks them) and no longer for those of an earlier edit: else every face ever dragged
    // would have its cells projected again in every frame of each later view.
    for (SurfaceRecord* r : scene.records())
        r->tilesWanted = false;
    // The overlays are drawn over the whole rectangle (their lines and points are not the
    // surfaces' cells), and edge bands' ranges have no tiles: one rectangle then.
    if (options.wireframe || options.controlNet || options.edgeBands || bandsChanged)
        plan.regions = {damage};
    else
        plan.regions = damageRegions(changed, fc, PartialFrames::reachPixels(options),
                                     options.damageTiles, plan.footprints);
    // Both the tiles and the rectangle hold every pixel to redraw: so does what they share
    // (the tiles' edges fall on the grid, past the rectangle's).
    std::vector<glm::ivec4> regions;
    for (const glm::ivec4& r : plan.regions) {
        const glm::ivec4 shared(glm::max(glm::ivec2(r), glm::ivec2(damage)),
                                glm::min(glm::ivec2(r.z, r.w), glm::ivec2(damage.z, damage.w)));
        if (shared.z > shared.x && shared.w > shared.y)
            regions.push_back(shared);
    }
    if (regions.empty())
        regions.push_back(damage);
    plan.regions = std::move(regions);
    glm::ivec4 bounds(0);
    for (const glm::ivec4& r : plan.regions) {
        report.partialPixels += rectPixels(r);
        PartialFrames::unite(bounds, r);
    }
    report.partialRegions = int(plan.regions.size());
    report.partialRect =
        QRect(bounds.x, size.height() - bounds.w, bounds.z - bounds.x, bounds.w - bounds.y);
    if (plan.regions.size() == 1) {
        const glm::ivec4& r = plan.regions.front();
        fc.reach = r;
        partialScissor = QRect(r.x, r.y, r.z - r.x, r.w - r.y);
    }
    for (size_t k = 0; k < plan.footprints.size(); ++k) {
        const SurfaceFootprint& f = plan.footprints[k];
        const glm::ivec4& r = f.rect;
        if (f.drawn && (!f.bounded || (r.z > fc.reach.x && r.x < fc.reach.z && r.w > fc.reach.y &&
                                       r.y < fc.reach.w))) {
            ++report.partialSurfaces;
            report.partialSurfaceCells += scene.records()[k]->cells;
        }
    }
    return plan;
}

std::shared_ptr<const std::vector<std::int32_t>> Renderer::Impl::recordTiles(SurfaceRecord& r,
                                                                             const FrameCamera& fc,
                                                                             const TileGrid& grid,
                                                                             int pad) {
    r.tilesWanted = true;
    if (!r.drawnBounded || !r.exact)
        return nullptr;
    if (!r.drawnTiles || r.drawnTilesPad != pad || r.drawnTilesSide != grid.tile()) {
        std::optional<std::vector<std::int32_t>> cells =
            cellTiles(r.exact->polygon, fc.viewProjection, grid, pad);
        if (!cells)
            return nullptr;
        r.drawnTiles = std::make_shared<const std::vector<std::int32_t>>(std::move(*cells));
        r.drawnTilesPad = pad;
        r.drawnTilesSide = grid.tile();
    }
    return r.drawnTiles;
}

std::vector<glm::ivec4> Renderer::Impl::damageRegions(const std::vector<DamagedSurface>& changed,
                                                      const FrameCamera& fc, int pad,
                                                      const RenderOptions::DamageTiles& options,
                                                      std::vector<SurfaceFootprint>& footprints) {
    TileGrid grid(fc.viewport, options.tilePixels);
    for (const DamagedSurface& c : changed) {
        std::shared_ptr<const std::vector<std::int32_t>> tiles = c.footprint.tiles;
        if (!c.before && c.index >= 0 && size_t(c.index) < scene.records().size()) {
            // As this frame draws it, kept for the next frame's "before".
            tiles = recordTiles(*scene.records()[size_t(c.index)], fc, grid, pad);
            footprints[size_t(c.index)].tiles = tiles;
        }
        if (tiles)
            grid.addTiles(*tiles);
        else
            grid.addRect(PartialFrames::grown(c.footprint.rect, pad, fc.viewport));
    }
    return grid.rects(options.maxRects, options.mergePixels);
}

Status Renderer::Impl::drawRegions(const PartialPlan& plan, const SampleRange& range,
                                   const RenderTarget& sampleTarget, std::uint32_t framebuffer,
                                   const FrameTargets& targets, FrameCamera& fc,
                                   const std::vector<Light>& lights, const RenderOptions& options,
                                   const QRect* pickPixel, FrameReport& report,
                                   bool& backCulledMoved) {
    // The changed surfaces' tiles: each rectangle cleared and drawn whole, as the whole
    // frame draws it, with the cells that reach it (they may overlap: drawn twice alike). One
    // rectangle, or none (a whole frame), is drawn as planPartialFrame set it.
    const bool each = plan.regions.size() > 1;
    Status drawn;
    for (size_t k = 0; k < std::max<size_t>(plan.regions.size(), 1); ++k) {
        if (each) {
            const glm::ivec4& r = plan.regions[k];
            partialScissor = QRect(r.x, r.y, r.z - r.x, r.w - r.y);
            fc.reach = r;
        }
        drawn = drawSamples(range, sampleTarget, framebuffer, targets, fc, lights, options,
                            report.analysisRange, pickPixel);
        if (report.partial && options.mode == RenderMode::Exact)
            report.partialCells += exact.cellsSent();
        backCulledMoved =
            backCulledMoved || (report.partial && exact.backCulledSolids() != partial.backCulled());
        if (!drawn)
            break;
    }
    return drawn;
}

void Renderer::Impl::rememberFrame(const LastFrame& now, const FrameCamera& fc,
                                   const RenderOptions& options, const PartialPlan& plan,
                                   bool drewSample, bool pickable, bool ok) {
    // A partial frame's pre-pass data is its rectangle's and the kept frame's.
    if (plan.damage)
        lastFrame = pickable && partial.pickable() ? std::optional<LastFrame>(now) : std::nullopt;
    else
        rememberLastFrame(now, drewSample, pickable);
    // Any other frame may have drawn over the own framebuffer or the pre-pass data.
    if (plan.keepable && ok)
        partial.remember(now.camera, fc, plan.view, exact.prepassWrites(), plan.footprints,
                         options.edgeBands.get(), exact.backCulledSolids(), lastFrame.has_value());
    else
        partial.forget();
}

Renderer::FramePick Renderer::pickInLastFrame(const Document& doc, const Camera& camera,
                                              QSize viewport, QPointF pixel) {
    FramePick answer;
    const std::optional<Impl::LastFrame>& last = d->lastFrame;
    if (!d->gl || !last || last->document != &doc || last->revision != doc.revision() ||
        !(last->camera == camera) || last->size != viewport)
        return answer;
    const glm::ivec2 texture = d->exact.prepassSize();
    const double fx = std::floor(pixel.x()), fy = std::floor(pixel.y());
    if (!d->exact.prepassTexture() || texture != glm::ivec2(viewport.width(), viewport.height()) ||
        !(fx >= 0.0 && fy >= 0.0 && fx < viewport.width() && fy < viewport.height()))
        return answer;
    QOpenGLFunctions_4_5_Core* gl = d->gl;
    const int x = int(fx), y = viewport.height() - 1 - int(fy); // GL rows run bottom-up
    // Depth and stencil at the pixel (GL_FLOAT_32_UNSIGNED_INT_24_8_REV: the float depth, then
    // a word whose low 8 bits are the stencil).
    GLint readBefore = 0;
    gl->glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readBefore);
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, last->framebuffer);
    struct {
        GLfloat depth;
        GLuint stencil;
    } ds{kFarDepth, 0};
    gl->glReadPixels(x, y, 1, 1, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &ds);
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readBefore));
    const unsigned stencil = ds.stencil & 0xffu;
    if (stencil == 0) {
        // Nothing drawn there is background; a skirt, a fin or a cell a section plane
        // crosses left no (u, v) to read. The forward pass's surfaces left theirs
        // (ExactPlanner::kForwardStencil).
        answer.known = ds.depth == kFarDepth;
        return answer;
    }
    GLuint words[4] = {0, 0, 0, 0};
    gl->glGetTextureSubImage(d->exact.prepassTexture(), 0, x, y, 0, 1, 1, 1, GL_RGBA_INTEGER,
                             GL_UNSIGNED_INT, sizeof(words), words);
    const int row = int(words[2] & 0x7fffffffu);
    const SurfaceRecord* record = nullptr;
    for (const SurfaceRecord* r : d->scene.records())
        if (r->slot == row) {
            record = r;
            break;
        }
    const Surface* s = record ? doc.surface(record->id) : nullptr;
    if (!s)
        return answer; // not known: pick() draws it
    float uv[2];
    std::memcpy(uv, words, sizeof(uv));
    answer.known = true;
    PickHit hit;
    hit.surface = s->id;
    hit.uv = glm::dvec2(uv[0], uv[1]);
    hit.point = surfacePoint(s->geometry, hit.uv.x, hit.uv.y);
    hit.depth = glm::dot(hit.point - camera.eye, glm::normalize(camera.target - camera.eye));
    answer.hit = hit;
    return answer;
}

void Renderer::setPassProfiling(bool on) {
    d->clock.setEnabled(on);
    d->exact.clock = on ? &d->clock : nullptr;
}

bool Renderer::passProfiling() const {
    return d->clock.enabled();
}

void Renderer::restartProgressive() {
    d->progressKey.reset();
}

int Renderer::Impl::frameSamples(const RenderOptions& options, bool aov, bool pick,
                                 FrameReport& report) {
    if (options.samples <= 1 || aov || pick)
        return 1;
    if (options.antialiasing == RenderOptions::Antialiasing::Accumulate)
        return std::min(options.samples, kMaxSamples); // whole frames: no GPU limit
    const int limit = maxSamples;
    if (options.samples > limit)
        report.warnings << QStringLiteral("%1 samples asked, the GPU allows %2: using %2")
                               .arg(options.samples)
                               .arg(limit);
    return std::min(options.samples, limit);
}

void Renderer::Impl::beginTarget(const RenderTarget& target, const RenderOptions& options,
                                 const QRect* pickPixel) {
    const QSize size = target.size;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    beginReversedDepth(gl);
    if (pickPixel) {
        // The framebuffer holds one pixel of the frame: shift the viewport so that pixel lands
        // on (0, 0); the rasterisation is the full frame's, translated by whole pixels.
        gl->glViewport(-pickPixel->x(), -pickPixel->y(), size.width(), size.height());
        gl->glEnable(GL_SCISSOR_TEST);
        gl->glScissor(0, 0, 1, 1);
    } else {
        gl->glViewport(0, 0, size.width(), size.height());
        if (!partialScissor.isNull()) {
            // A partial frame: every clear and draw below within its rectangle, the rest of
            // the kept frame left as it is. Its stencil too, which says where the pre-pass data
            // is (Renderer::pickInLastFrame): the rectangle's old data is not.
            gl->glEnable(GL_SCISSOR_TEST);
            gl->glScissor(partialScissor.x(), partialScissor.y(), partialScissor.width(),
                          partialScissor.height());
            const GLint zero = 0;
            gl->glStencilMask(0xff);
            gl->glClearBufferiv(GL_STENCIL, 0, &zero);
        }
    }
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_CULL_FACE);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_TRUE);
    gl->glClearBufferfv(GL_COLOR, kColourOutput, &options.background.x);
    if (options.writeAov) {
        const GLfloat background[4] = {-1.0f, 0.0f, 0.0f, 0.0f}; // surface id -1
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        gl->glClearBufferfv(GL_COLOR, kAovIdUvDepthOutput, background);
        const int end = options.writeCurvatureAov ? kCurvatureAovDrawBuffers : kAovDrawBuffers;
        for (int k = kAovPositionOutput; k < end; ++k)
            gl->glClearBufferfv(GL_COLOR, k, zero);
    }
    gl->glClearBufferfv(GL_DEPTH, 0, &kFarDepth);
    if (options.backgroundTop)
        drawBackground(options);
}

void Renderer::Impl::drawBackground(const RenderOptions& options) {
    const Expected<QOpenGLShaderProgram*> built =
        shaders.program(QStringLiteral("aa_composite.vert"), QStringLiteral("background.frag"));
    if (!built) {
        qWarning("%s", qPrintable(built.message())); // the flat background stays
        return;
    }
    QOpenGLShaderProgram* prog = *built;
    if (!backgroundVao)
        gl->glCreateVertexArrays(1, &backgroundVao);
    GLint view[4] = {0, 0, 0, 0};
    gl->glGetIntegerv(GL_VIEWPORT, view);
    prog->bind();
    const UniformLocations& u = ShaderLibrary::uniforms(prog);
    gl->glUniform4f(u.viewport, float(view[0]), float(view[1]), float(view[2]), float(view[3]));
    gl->glUniform4fv(u.backgroundBottom, 1, &options.background.x);
    gl->glUniform4fv(u.backgroundTop, 1, &options.backgroundTop->x);
    // Colour only: the AOV targets keep "no surface", the depth its far clear.
    GLint drawBuffers = 1;
    gl->glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    for (GLint k = 1; k < drawBuffers; ++k)
        gl->glColorMaski(GLuint(k), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glBindVertexArray(backgroundVao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    gl->glDepthMask(GL_TRUE);
    gl->glEnable(GL_DEPTH_TEST);
    for (GLint k = 1; k < drawBuffers; ++k)
        gl->glColorMaski(GLuint(k), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    prog->release();
}

std::int64_t Renderer::setMesh(int slot, const TriangleMesh& mesh) {
    if (!d->gl || slot < 0 || slot >= kMeshSlots)
        return -1;
    std::unique_ptr<TriangleMeshPass>& pass = d->meshes[slot];
    if (!pass) {
        pass = std::make_unique<TriangleMeshPass>();
        pass->initialize(d->gl, &d->shaders);
    }
    return pass->upload(mesh);
}

FrameReport Renderer::renderMesh(const Document& doc, int slot, const Camera& camera,
                                 const RenderTarget& target, const RenderOptions& options) {
    return renderMeshes(doc, {slot}, camera, target, options);
}

FrameReport Renderer::renderMeshes(const Document& doc, const std::vector<int>& slots,
                                   const Camera& camera, const RenderTarget& target,
                                   const RenderOptions& options) {
    d->presented.reset(); // drawn straight into its target
    QElapsedTimer total;
    total.start();
    FrameReport report;
    std::vector<TriangleMeshPass*> passes;
    int missing = slots.empty() ? -1 : 0;
    for (int slot : slots) {
        TriangleMeshPass* pass =
            d->gl && slot >= 0 && slot < kMeshSlots ? d->meshes[slot].get() : nullptr;
        if (!pass) {
            missing = slot;
            break;
        }
        passes.push_back(pass);
    }
    const QSize size = target.size;
    if (passes.size() != slots.size() || slots.empty() || size.isEmpty()) {
        report.ok = false;
        report.error =
            passes.size() != slots.size() || slots.empty()
                ? QStringLiteral("Renderer::renderMesh: no mesh in slot %1").arg(missing)
                : QStringLiteral("render size %1x%2 is empty").arg(size.width()).arg(size.height());
        return report;
    }
    RenderOptions o = options;
    o.writeAov = target.aov;
    o.writeCurvatureAov = false;
    FrameCamera fc = frameCamera(camera, doc.scene(), double(size.width()) / size.height());
    fc.viewport = glm::ivec2(size.width(), size.height());
    const std::vector<Light> lights = lightsFor(doc.scene(), camera, o.lightCount, o.headlight);
    d->beginTarget(target, o, nullptr);
    Status drawn;
    for (TriangleMeshPass* pass : passes) {
        if (drawn)
            drawn = pass->draw(doc.scene(), fc, lights, o);
        report.drawCalls += pass->drawCalls;
        report.surfaces += pass->surfaces;
    }
    endReversedDepth(d->gl);
    report.ok = bool(drawn);
    if (!drawn)
        report.error = drawn.message();
    report.cpuMs.surfaces = msSince(total);
    d->scene.residentBytes(report.gpuBytes);
    report.gpuBytes.perSurface += d->exact.residentBytes();
    for (const std::unique_ptr<TriangleMeshPass>& m : d->meshes)
        if (m)
            report.gpuBytes.tessellatedMeshes += m->residentBytes();
    report.cpuMs.total = msSince(total);
    return report;
}

PartialFrameView Renderer::Impl::partialView(const Document& doc, const RenderTarget& target,
                                             QSize drawnSize, const FrameCamera& fc,
                                             const std::vector<Light>& lights,
                                             const RenderOptions& options,
                                             const ValueRange& range) const {
    PartialFrameView v;
    v.document = &doc;
    v.target = floatDepth.serial();
    v.drawnSize = drawnSize;
    v.targetSize = target.size;
    v.view = fc.view;
    v.projection = fc.projection;
    v.viewport = fc.viewport;
    v.lights = lights;
    v.options = options;
    v.options.frameReuse = RenderOptions::FrameReuse::Partial; // Full and Partial alike
    v.analysisRange = range;
    v.marks = scene.marksRevision();
    return v;
}

std::vector<SurfaceFootprint> Renderer::Impl::surfaceFootprints(const FrameCamera& fc,
                                                                const RenderOptions& options) {
    const bool controlNet = options.controlNet;
    const TileGrid grid(fc.viewport, options.damageTiles.tilePixels);
    const int pad = PartialFrames::reachPixels(options);
    std::vector<SurfaceFootprint> out;
    out.reserve(scene.records().size());
    for (SurfaceRecord* r : scene.records()) {
        // Where the polygon's vertices project, again only when the view, the polygon or its
        // points changed: a B-rep face's control net spans its whole untrimmed surface, and
        // the 8 corners of a slanted face's box project far wider than the face.
        const SurfaceGpu* g = r->exact.get();
        if (!g || g->polygon.vertices.empty()) {
            r->drawnBounded = false;
        } else if (const std::pair at{g->polygonSerial, g->revisions.points};
                   r->drawnOf != at || r->drawnView != fc.viewProjection ||
                   r->drawnViewport != fc.viewport) {
            glm::vec2 lo(std::numeric_limits<float>::max()), hi(-lo);
            bool front = true;
            for (const BaseVertex& v : g->polygon.vertices) {
                const glm::vec4 clip = fc.viewProjection * glm::vec4(v.position, 1.0f);
                if (!(clip.w > 0.0f)) {
                    front = false;
                    break;
                }
                const glm::vec2 ndc = glm::clamp(glm::vec2(clip) / clip.w, -2.0f, 2.0f);
                lo = glm::min(lo, ndc);
                hi = glm::max(hi, ndc);
            }
            const ExactPlanner::ScreenBox box{lo, hi, !front};
            r->drawnRect = front ? ExactPlanner::pixelRect(box, fc.viewport) : glm::ivec4(0);
            r->drawnBounded = front;
            r->drawnTiles.reset();
            r->drawnOf = at;
            r->drawnView = fc.viewProjection;
            r->drawnViewport = fc.viewport;
        }
        SurfaceFootprint f;
        f.id = r->id.value;
        f.slot = r->slot;
        f.revisions = r->revisions;
        f.polygon = g ? g->polygonSerial : 0;
        f.maskWidth = r->mask.width;
        f.maskHeight = r->mask.height;
        f.drawn = g != nullptr && r->slot >= 0;
        // The control points' rectangle: without the polygon's, and where the net is drawn.
        std::optional<glm::ivec4> control;
        if (r->bounded && (controlNet || !r->drawnBounded)) {
            const ExactPlanner::ScreenBox box =
                ExactPlanner::screenBox(r->boundsLo, r->boundsHi, fc.viewProjection);
            if (!box.behind)
                control = ExactPlanner::pixelRect(box, fc.viewport);
        }
        const bool needControl = !r->drawnBounded || (controlNet && r->bounded);
        f.bounded = needControl ? control.has_value() : true;
        if (r->drawnBounded)
            f.rect = r->drawnRect;
        if (control)
            PartialFrames::unite(f.rect, *control);
        else if (r->drawnBounded && r->tilesWanted)
            // A surface a partial frame redrew (being edited): its tiles as this frame draws
            // it, for the next partial frame, even when this one is drawn whole.
            f.tiles = recordTiles(*r, fc, grid, pad);
        out.push_back(f);
    }
    return out;
}

void Renderer::Impl::resetPassCounters() {
    exact.drawCalls = tessellated.drawCalls = wireframe.drawCalls = controlNet.drawCalls = 0;
    edgeBands.drawCalls = 0;
    exact.culled = exact.solidsBackCulled = 0;
    exact.trimTestedCells = exact.trimmedAwayCells = exact.skirtTriangles = 0;
    exact.affineSurfaces = 0;
    exact.analyticSurfaces = 0;
    exact.coverSurfaces = 0;
    exact.deferredSurfaces = 0;
    exact.sectionCrossedCells = 0;
    exact.firstDrawCpuMs = tessellated.firstDrawCpuMs = -1.0;
}

Renderer::Impl::FrameTargets Renderer::Impl::frameTargets(const RenderTarget& target, int samples,
                                                          const RenderOptions& options,
                                                          bool preview, bool pick, QSize& size,
                                                          FrameReport& report) {
    FrameTargets out;
    if (samples > 1 && options.antialiasing == RenderOptions::Antialiasing::Accumulate) {
        if (const Status ready = accumulate.ensure(size))
            out.accumulated = &accumulate;
        else
            report.warnings << QStringLiteral("anti-aliasing is off: %1").arg(ready.message());
        antialias.release();
    } else if (samples > 1) {
        if (const Status ready = antialias.ensure(size, samples))
            out.aa = &antialias;
        else
            report.warnings << QStringLiteral("anti-aliasing is off: %1").arg(ready.message());
    } else if (!target.aov && !pick && !preview) {
        antialias.release(); // anti-aliasing turned off: free its framebuffers
    }
    // A preview keeps them for the still frame after it.
    if (!out.accumulated && !target.aov && !pick && !preview)
        accumulate.release();
    // An aliased frame into a host whose depth is not float (Qt's widget framebuffers: 24-bit)
    // is drawn into the float-depth target and its colour copied over (float_depth_target.h).
    // AOV frames and picks go to Knotwork's own float-depth framebuffers already.
    out.drawn = target;
    out.drawn.size = size;
    // A frame kept for the next one (RenderOptions::FrameReuse) is drawn there too: the
    // host's framebuffer is swapped, drawn over and read by others between frames.
    if (!out.aa && !out.accumulated && !target.aov && !pick &&
        (preview || options.frameReuse != RenderOptions::FrameReuse::None ||
         floatDepth.hostNeedsIt(target.framebuffer))) {
        if (const Status ready = floatDepth.ensure(size))
            out.drawn.framebuffer = floatDepth.framebuffer();
        else
            report.warnings << ready.message();
        if (out.drawn.framebuffer == target.framebuffer)
            out.drawn.size = size = target.size; // no own framebuffer: the full frame
    } else if (!out.aa && !out.accumulated && !pick) {
        // Freed only when an aliased frame goes straight to its host: the editor alternates
        // aliased frames while moving with anti-aliased still ones, and would otherwise
        // allocate the target again at every move.
        floatDepth.release();
    }
    return out;
}

Renderer::Impl::SampleRange Renderer::Impl::sampleRange(const Document& doc, const Camera& camera,
                                                        const RenderTarget& target, QSize size,
                                                        const RenderOptions& options, int samples,
                                                        bool accumulated, bool pick) {
    // Accumulated anti-aliasing draws the whole aliased frame once per sample, shifted by the
    // sample's offset, into its own framebuffer, and adds it up; otherwise one frame.
    SampleRange out;
    out.offsets =
        accumulated ? accumulationOffsets(samples) : std::vector<glm::vec2>{glm::vec2(0.0f)};
    out.end = out.offsets.size();
    if (accumulated && options.progressive) {
        // One sample per call onto the sum of the calls before, while they drew the same thing.
        const ProgressKey key{&doc, doc.revision(), camera, target.framebuffer, size, options};
        const int inSum = progressKey && *progressKey == key ? accumulate.added() : 0;
        progressKey = key;
        out.first = size_t(std::clamp(inSum, 0, samples));
        out.end = std::min(out.first + 1, out.offsets.size()); // all in: none, resolved again
    } else if (!pick && !target.aov) {
        progressKey.reset();
    }
    return out;
}

Status Renderer::Impl::drawSamples(const SampleRange& range, const RenderTarget& sampleTarget,
                                   std::uint32_t framebuffer, const FrameTargets& targets,
                                   FrameCamera& fc, const std::vector<Light>& lights,
                                   const RenderOptions& options, const ValueRange& analysisRange,
                                   const QRect* pickPixel) {
    AntialiasTarget* const aa = targets.aa;
    AccumulateTarget* const accumulated = targets.accumulated;
    Status done;
    if (accumulated && range.first > 0 && range.first < range.end)
        done = accumulated->keepFirst(); // before the next sample is drawn over it
    for (size_t i = range.first; done && i < range.end; ++i) {
        fc.jitter = range.offsets[i];
        beginTarget(sampleTarget, options, pickPixel);
        if (aa) {
            aa->begin(&options.background.x);
            if (options.backgroundTop)
                drawBackground(options); // into the multisampled colour, as beginTarget did
        }
        done = options.mode == RenderMode::Exact
                   ? exact.draw(scene, options.trims, fc, lights, options, analysisRange, aa)
                   : tessellated.draw(scene, options.trims, fc, lights, options);
        // A progressive image's first sample is shown as it is, without the sum.
        if (done && accumulated && !(options.progressive && i == 0))
            done = accumulated->add(i == 0);
        clock.mark(PassTimes::Antialiasing);
    }
    fc.jitter = glm::vec2(0.0f); // the overlays are drawn once, unshifted
    if (done && accumulated)
        done = options.progressive && range.first == 0 ? accumulated->resolveFirst(framebuffer)
                                                       : accumulated->resolve(framebuffer);
    // Resolved before the overlays: they are drawn into the host's framebuffer over the
    // composite's colour and depth, as without anti-aliasing. The first failure is kept.
    if (aa)
        if (const Status composited = aa->composite(framebuffer); !composited && done)
            done = composited;
    return done;
}

Status Renderer::Impl::drawOverlays(const RenderTarget& target, const FrameCamera& fc,
                                    const RenderOptions& options) {
    // Overlays write colour only; the AOV targets keep the surfaces' values.
    if (options.writeAov)
        setDrawBuffers(target.framebuffer, kColourOutput + 1);
    Status drawn;
    if (options.wireframe)
        drawn = wireframe.draw(scene, fc, options);
    if (drawn && options.controlNet)
        drawn = controlNet.draw(scene, fc, options);
    if (drawn && options.edgeBands)
        drawn = edgeBands.draw(*options.edgeBands, fc);
    if (options.writeAov)
        setDrawBuffers(target.framebuffer,
                       options.writeCurvatureAov ? kCurvatureAovDrawBuffers : kAovDrawBuffers);
    return drawn;
}

void Renderer::Impl::reportPassFigures(FrameReport& report) const {
    report.drawCalls += exact.drawCalls + tessellated.drawCalls + wireframe.drawCalls +
                        controlNet.drawCalls + edgeBands.drawCalls;
    report.surfaces = scene.drawnCount();
    report.culled = exact.culled;
    report.solidsBackCulled = exact.solidsBackCulled;
    report.partitions.trimTestedCells = exact.trimTestedCells;
    report.partitions.trimmedAwayCells = exact.trimmedAwayCells;
    report.partitions.skirtTriangles = exact.skirtTriangles;
    report.partitions.affineSurfaces = exact.affineSurfaces;
    report.partitions.analyticSurfaces = exact.analyticSurfaces;
    report.partitions.coverSurfaces = exact.coverSurfaces;
    report.partitions.deferredSurfaces = exact.deferredSurfaces;
    report.partitions.sectionCrossedCells = exact.sectionCrossedCells;
    scene.residentBytes(report.gpuBytes);
    report.gpuBytes.perSurface += exact.residentBytes();
    report.hostCopyBytes = scene.hostCopyBytes() + exact.hostCopyBytes();
    report.gpuBytes.frameTargets = antialias.residentBytes() + accumulate.residentBytes();
    report.gpuBytes.floatDepthTarget = floatDepth.residentBytes();
}

void Renderer::Impl::rememberLastFrame(const LastFrame& now, bool drewSample, bool pickable) {
    // What pickInLastFrame may read: a sample drawn now with the deferred pass's input, or a
    // progressive image resolved again (nothing drawn) over the same view.
    if (!pickable)
        lastFrame.reset();
    else if (drewSample)
        lastFrame = exact.deferredSurfaces > 0 ? std::optional<LastFrame>(now) : std::nullopt;
    else if (lastFrame && !(*lastFrame == now))
        lastFrame.reset();
}

void Renderer::Impl::setDrawBuffers(GLuint framebuffer, int count) {
    GLenum buffers[kCurvatureAovDrawBuffers];
    for (int k = 0; k < count; ++k)
        buffers[k] = GL_COLOR_ATTACHMENT0 + GLenum(k);
    gl->glNamedFramebufferDrawBuffers(framebuffer, count, buffers);
}

Status Renderer::Impl::ensurePickTarget(QSize size) {
    if (pickFbo && pickSize == size)
        return ok();
    releasePickTarget();
    // One pixel: renderFrame shifts the viewport onto it.
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
        gl->glTextureStorage2D(t, 1, format, 1, 1);
        return t;
    };
    gl->glCreateFramebuffers(1, &pickFbo);
    for (int k = 0; k < kAovDrawBuffers; ++k) {
        pickTextures[k] = texture(k == kColourOutput ? GL_RGBA8 : GL_RGBA32F);
        gl->glNamedFramebufferTexture(pickFbo, GL_COLOR_ATTACHMENT0 + GLenum(k), pickTextures[k],
                                      0);
    }
    pickTextures[kAovDrawBuffers] = texture(kDepthFormat);
    gl->glNamedFramebufferTexture(pickFbo, GL_DEPTH_ATTACHMENT, pickTextures[kAovDrawBuffers], 0);
    setDrawBuffers(pickFbo, kAovDrawBuffers);
    if (gl->glCheckNamedFramebufferStatus(pickFbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        releasePickTarget();
        return Error(QStringLiteral("the pick framebuffer is incomplete"));
    }
    pickSize = size;
    return ok();
}

void Renderer::Impl::releasePickTarget() {
    if (pickFbo)
        gl->glDeleteFramebuffers(1, &pickFbo);
    for (GLuint& t : pickTextures)
        if (t)
            gl->glDeleteTextures(1, &t), t = 0;
    pickFbo = 0;
    pickSize = QSize();
}

std::optional<PickHit> Renderer::pick(const Document& doc, const Camera& camera, QSize viewport,
                                      QPointF pixel, const RenderOptions& options) {
    if (!d->gl)
        return std::nullopt;
    const double fx = std::floor(pixel.x()), fy = std::floor(pixel.y());
    if (viewport.isEmpty() ||
        !(fx >= 0.0 && fy >= 0.0 && fx < viewport.width() && fy < viewport.height()))
        return std::nullopt;
    if (!d->ensurePickTarget(viewport))
        return std::nullopt;
    RenderOptions o = options;
    o.wireframe = o.controlNet = false;
    // The pick reads ids and (u, v) only: no analysis colouring (and no colour range to find).
    o.analysis = {};
    const int x = int(fx), y = viewport.height() - 1 - int(fy); // GL rows run bottom-up
    const QRect at(x, y, 1, 1);
    d->renderFrame(doc, camera, {d->pickFbo, viewport, true, false, std::nullopt}, o, &at);
    d->gl->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    float a[4] = {-1.0f, 0.0f, 0.0f, 0.0f}; // id, u, v, Z
    d->gl->glGetTextureImage(d->pickTextures[kAovIdUvDepthOutput], 0, GL_RGBA, GL_FLOAT, sizeof(a),
                             a);
    if (!(a[0] >= 0.0f))
        return std::nullopt;
    const Surface* s = doc.surface(SurfaceId{std::uint32_t(std::lround(a[0]))});
    if (!s)
        return std::nullopt;
    PickHit hit;
    hit.surface = s->id;
    hit.uv = glm::dvec2(a[1], a[2]);
    hit.point = surfacePoint(s->geometry, hit.uv.x, hit.uv.y);
    hit.depth = a[3];
    return hit;
}

ValueRange Renderer::Impl::resolveAnalysisRange(const Document& doc,
                                                const AnalysisOptions& analysis) {
    if (!isColourMap(analysis.mode))
        return {};
    if (analysis.range)
        return *analysis.range;
    std::uint64_t newest = 0;
    for (int i = 0; i < int(doc.scene().surfaces.size()); ++i) {
        const Revisions r = doc.revisionsAt(i);
        newest = std::max({newest, r.points, r.knots, r.display}); // display: hidden
    }
    const RangeKey key{&doc, analysis.mode, doc.scene().surfaces.size(), newest};
    const bool held =
        analysis.holdRange && rangeKey.document == &doc && rangeKey.mode == analysis.mode;
    if (!held && !(key == rangeKey)) {
        autoAnalysisRange = autoRange(doc.scene(), analysis.mode);
        rangeKey = key;
    }
    return autoAnalysisRange;
}

void Renderer::release() {
    if (!d->gl)
        return;
    d->releasePickTarget();
    d->partial.forget();
    for (std::unique_ptr<TriangleMeshPass>& m : d->meshes)
        if (m)
            m->release(), m.reset();
    d->scene.release();
    d->exact.release();
    d->antialias.release();
    d->accumulate.release();
    d->floatDepth.release();
    d->edgeBands.release();
    d->rangeKey = {};
    if (d->backgroundVao)
        d->gl->glDeleteVertexArrays(1, &d->backgroundVao);
    d->backgroundVao = 0;
    d->shaders.clear();
    d->gl = nullptr;
}

} // namespace kw
