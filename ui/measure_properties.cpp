// MeasuredProperties: face and model measurements, computed on a worker thread.
#include "ui/measure_properties.h"

#include "model/document.h"
#include "model/selection.h"

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

QString boxText(bool has, const glm::dvec3& lo, const glm::dvec3& hi) {
    if (!has)
        return QObject::tr("none");
    const glm::dvec3 d = hi - lo;
    return QObject::tr("min %1\nmax %2\nsize %3 × %4 × %5")
        .arg(point(lo), point(hi), num(d.x), num(d.y), num(d.z));
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
    };
    const std::uint64_t generation = m_generation;
    const SurfaceId id = m_selection->currentSurface();
    const Surface* current = m_doc->surface(id);
    auto result = std::make_shared<Result>();
    // Copies: the document may change while the worker runs.
    QThread* worker =
        QThread::create([scene = m_doc->scene(),
                         face = current ? std::optional<Surface>(*current) : std::nullopt, result] {
            if (face)
                result->face = faceProperties(*face);
            result->model = modelProperties(scene);
        });
    worker->setParent(this);
    connect(worker, &QThread::finished, this, [this, worker, generation, id, result] {
        show(generation, id, result->face, result->model);
        worker->deleteLater();
    });
    worker->start(QThread::LowPriority);
}

void MeasuredProperties::show(std::uint64_t generation, SurfaceId face,
                              const std::optional<FaceProperties>& f, const ModelProperties& m) {
    if (generation != m_generation)
        return; // a newer state is on its way
    if (f) {
        const Surface* s = m_doc->surface(face);
        m_face->setText(tr("%1\ntype %2, degree %3 × %4\narea %5\n%6")
                            .arg(s ? s->name : QString(), surfaceTypeName(f->type))
                            .arg(f->degreeU)
                            .arg(f->degreeV)
                            .arg(num(f->area), boxText(f->hasBounds, f->lo, f->hi)));
    } else {
        m_face->setText(tr("no surface selected"));
    }
    m_model->setText(
        tr("%1 surface(s)\narea %2\nvolume %3\n%4")
            .arg(m_doc->scene().surfaces.size())
            .arg(num(m.area),
                 m.volume ? tr("%1 (%2 closed shell(s))").arg(num(*m.volume)).arg(m.closedShells)
                          : tr("none (no closed solid)"),
                 boxText(m.hasBounds, m.lo, m.hi)));
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
