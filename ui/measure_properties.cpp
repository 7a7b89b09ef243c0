// MeasuredProperties: face and model measurements, computed on a worker thread.
#include "ui/measure_properties.h"

#include "model/document/document.h"
#include "model/document/selection.h"
#include "model/document/units.h"

#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPointer>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>
#include <memory>

namespace kw {

namespace {

constexpr int kDelayMs = 150;

QString num(double v) {
    return QString::number(v, 'g', 10);
}

QString point(const glm::dvec3& p) {
    return QStringLiteral("(%1, %2, %3)").arg(num(p.x), num(p.y), num(p.z));
}

QString boxText(bool has, const glm::dvec3& lo, const glm::dvec3& hi, const QString& unit) {
    if (!has)
        return QObject::tr("none");
    const glm::dvec3 d = hi - lo;
    return QObject::tr("min %1 %6\nmax %2 %6\nsize %3 × %4 × %5 %6")
        .arg(point(lo), point(hi), num(d.x), num(d.y), num(d.z), unit);
}

std::vector<SurfaceId> surfaceIds(const Scene& scene) {
    std::vector<SurfaceId> ids;
    for (const Surface& s : scene.surfaces)
        ids.push_back(s.id);
    return ids;
}

QLabel* valueLabel(const char* name) {
    auto* l = new QLabel;
    l->setObjectName(QLatin1String(name));
    l->setTextInteractionFlags(Qt::TextSelectableByMouse);
    l->setWordWrap(true);
    return l;
}

} // namespace

MeasuredProperties::MeasuredProperties(Document* document, Selection* selection, QWidget* parent)
    : QWidget(parent), m_doc(document), m_selection(selection), m_timer(new QTimer(this)) {
    setObjectName(QStringLiteral("measuredProperties"));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* faceBox = new QGroupBox(tr("Measured face"));
    auto* faceForm = new QFormLayout(faceBox);
    faceForm->addRow(m_face = valueLabel("measuredFace"));
    auto* modelBox = new QGroupBox(tr("Model"));
    auto* modelForm = new QFormLayout(modelBox);
    modelForm->addRow(m_model = valueLabel("measuredModel"));
    layout->addWidget(faceBox);
    layout->addWidget(modelBox);

    m_timer->setSingleShot(true);
    m_timer->setInterval(kDelayMs);
    connect(m_timer, &QTimer::timeout, this, &MeasuredProperties::start);
    connect(m_selection, &Selection::changed, this, &MeasuredProperties::schedule);
    // Every aspect may change what is shown (Display holds the solid mark, Name the title).
    connect(m_doc, &Document::surfaceChanged, this, &MeasuredProperties::schedule);
    connect(m_doc, &Document::sceneReset, this, &MeasuredProperties::schedule);
    connect(m_doc, &Document::surfaceInserted, this, &MeasuredProperties::schedule);
    connect(m_doc, &Document::surfaceRemoved, this, &MeasuredProperties::schedule);
    connect(m_doc, &Document::trimLoopInserted, this, &MeasuredProperties::schedule);
    connect(m_doc, &Document::trimLoopRemoved, this, &MeasuredProperties::schedule);
    schedule();
}

MeasuredProperties::~MeasuredProperties() {
    // A worker still running holds only copies, but must end before the process does.
    for (QThread* t : findChildren<QThread*>())
        t->wait();
}

void MeasuredProperties::schedule() {
    ++m_generation;
    m_timer->start();
}

bool MeasuredProperties::pending() const {
    return m_shown != m_generation;
}

void MeasuredProperties::start() {
    struct Result {
        std::optional<FaceProperties> face;
        ModelProperties model;
        std::vector<std::pair<size_t, FaceMeasure>> measured; ///< the stale faces, by index
    };
    const std::uint64_t generation = m_generation;
    const SurfaceId id = m_selection->currentSurface();
    const Scene& scene = m_doc->scene();
    // Faces whose shape and trims are as cached keep their measure; the rest go to the worker.
    std::vector<FaceMeasure> known(scene.surfaces.size());
    std::vector<size_t> stale;
    std::vector<Cached> keys(scene.surfaces.size());
    std::optional<size_t> current;
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
        const Revisions r = m_doc->revisionsAt(int(k));
        keys[k] = {r.points, r.knots, r.trims, {}};
        const auto it = m_cache.constFind(scene.surfaces[k].id);
        if (it != m_cache.cend() && it->points == r.points && it->knots == r.knots &&
            it->trims == r.trims)
            known[k] = it->measure;
        else
            stale.push_back(k);
        if (scene.surfaces[k].id == id)
            current = k;
    }
    auto result = std::make_shared<Result>();
    // Copies: the document may change while the worker runs.
    QThread* worker =
        QThread::create([scene, known = std::move(known), stale, current, result]() mutable {
            if (!stale.empty()) {
                const std::vector<FaceMeasure> fresh = measureFaces(scene, stale);
                for (size_t k = 0; k < stale.size(); ++k) {
                    known[stale[k]] = fresh[k];
                    result->measured.push_back({stale[k], fresh[k]});
                }
            }
            result->model = modelProperties(scene, known);
            if (current)
                result->face = known[*current].props;
        });
    worker->setParent(this);
    connect(worker, &QThread::finished, this,
            [this, worker, generation, id, result, keys, ids = surfaceIds(scene)] {
                // The measures hold for the revisions they were taken at, whatever came since.
                QHash<SurfaceId, Cached> cache;
                for (size_t k = 0; k < ids.size(); ++k)
                    if (const auto it = m_cache.constFind(ids[k]); it != m_cache.cend())
                        cache.insert(ids[k], *it);
                for (const auto& [index, measure] : result->measured) {
                    Cached c = keys[index];
                    c.measure = measure;
                    cache.insert(ids[index], c);
                }
                m_cache = std::move(cache);
                m_measured += int(result->measured.size());
                show(generation, id, result->face, result->model);
                worker->deleteLater();
            });
    worker->start(QThread::LowPriority);
}

void MeasuredProperties::show(std::uint64_t generation, SurfaceId face,
                              const std::optional<FaceProperties>& f, const ModelProperties& m) {
    if (generation != m_generation)
        return; // a newer state is on its way
    const QString unit = lengthUnitKey(m_doc->scene().unit);
    if (f) {
        const Surface* s = m_doc->surface(face);
        // The unit's powers are concatenated: arg() would read "%6²" as a two-digit placeholder.
        m_face->setText(tr("%1\ntype %2, degree %3 × %4\narea %5 %6\n%7")
                            .arg(s ? s->name : QString(), surfaceTypeName(f->type))
                            .arg(f->degreeU)
                            .arg(f->degreeV)
                            .arg(num(f->area),
                                 unit + u'²' + (f->approximate ? tr(" (approximate)") : QString()),
                                 boxText(f->hasBounds, f->lo, f->hi, unit)));
    } else {
        m_face->setText(tr("no surface selected"));
    }
    m_model->setText(tr("%1 surface(s)\narea %2 %5\nvolume %3\n%4")
                         .arg(m_doc->scene().surfaces.size())
                         .arg(num(m.area),
                              m.volume ? tr("%1 %2 (%3 closed shell(s))")
                                             .arg(num(*m.volume), unit + u'³')
                                             .arg(m.closedShells)
                                       : tr("none (no closed solid)"),
                              boxText(m.hasBounds, m.lo, m.hi, unit),
                              unit + u'²' + (m.approximate ? tr(" (approximate)") : QString())));
    m_shown = generation;
    Q_EMIT updated();
}

QString MeasuredProperties::faceText() const {
    return m_face->text();
}

QString MeasuredProperties::modelText() const {
    return m_model->text();
}

} // namespace kw
