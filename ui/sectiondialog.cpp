// View › Section…: typed section planes, applied to the view as they change.
#include "ui/sectiondialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace kw {

namespace {

QDoubleSpinBox* coordinateBox(const QString& name) {
    auto* b = new QDoubleSpinBox;
    b->setObjectName(name);
    b->setDecimals(6);
    b->setRange(-1e9, 1e9);
    b->setSingleStep(0.1);
    b->setKeyboardTracking(true); // live: every keystroke moves the plane
    b->setAccelerated(true);
    return b;
}

} // namespace

SectionPlane SectionDialog::Row::plane() const {
    SectionPlane p;
    for (int i = 0; i < 3; ++i) {
        p.position[i] = position[size_t(i)]->value();
        p.normal[i] = normal[size_t(i)]->value();
    }
    p.flip = flip->isChecked();
    return p;
}

SectionDialog::SectionDialog(std::function<glm::dvec3()> centre, QWidget* parent)
    : QDialog(parent), m_centre(std::move(centre)) {
    setObjectName(QStringLiteral("sectionDialog"));
    setWindowTitle(tr("Section Planes"));
    auto* layout = new QVBoxLayout(this);
    auto* intro = new QLabel(tr("Each plane removes the side its normal points to; Flip keeps "
                                "that side instead. Cuts follow the exact surface; closed solids "
                                "get a hatched cap."));
    intro->setWordWrap(true);
    layout->addWidget(intro);
    const char* axes[] = {"X", "Y", "Z"};
    for (int k = 0; k < kMaxSectionPlanes; ++k) {
        Row& r = m_rows[size_t(k)];
        auto* box = new QGroupBox;
        auto* grid = new QGridLayout(box);
        r.enabled = new QCheckBox(tr("Plane %1").arg(k + 1));
        r.enabled->setObjectName(QStringLiteral("sectionEnabled%1").arg(k));
        grid->addWidget(r.enabled, 0, 0, 1, 4);
        grid->addWidget(new QLabel(tr("Point")), 1, 0);
        grid->addWidget(new QLabel(tr("Normal")), 2, 0);
        for (int i = 0; i < 3; ++i) {
            r.position[size_t(i)] = coordinateBox(
                QStringLiteral("sectionPosition%1%2").arg(k).arg(QLatin1String(axes[i])));
            r.normal[size_t(i)] = coordinateBox(
                QStringLiteral("sectionNormal%1%2").arg(k).arg(QLatin1String(axes[i])));
            r.position[size_t(i)]->setPrefix(QLatin1String(axes[i]) + QStringLiteral(" "));
            r.normal[size_t(i)]->setPrefix(QLatin1String(axes[i]) + QStringLiteral(" "));
            grid->addWidget(r.position[size_t(i)], 1, i + 1);
            grid->addWidget(r.normal[size_t(i)], 2, i + 1);
            connect(r.position[size_t(i)], &QDoubleSpinBox::valueChanged, this,
                    [this] { changed(); });
            connect(r.normal[size_t(i)], &QDoubleSpinBox::valueChanged, this,
                    [this] { changed(); });
        }
        r.normal[0]->setValue(1.0);
        r.flip = new QCheckBox(tr("Flip"));
        r.flip->setObjectName(QStringLiteral("sectionFlip%1").arg(k));
        grid->addWidget(r.flip, 3, 1);
        r.status = new QLabel;
        r.status->setObjectName(QStringLiteral("sectionStatus%1").arg(k));
        grid->addWidget(r.status, 3, 2, 1, 2);
        connect(r.flip, &QCheckBox::toggled, this, [this] { changed(); });
        connect(r.enabled, &QCheckBox::toggled, this, [this, k](bool on) { enableRow(k, on); });
        enableRow(k, false);
        layout->addWidget(box);
    }
    m_caps = new QCheckBox(tr("Caps on cut closed solids"));
    m_caps->setObjectName(QStringLiteral("sectionCaps"));
    m_caps->setChecked(true);
    connect(m_caps, &QCheckBox::toggled, this, [this] { changed(); });
    layout->addWidget(m_caps);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    QPushButton* clear = buttons->addButton(tr("Remove All"), QDialogButtonBox::ResetRole);
    clear->setObjectName(QStringLiteral("sectionRemoveAll"));
    connect(clear, &QPushButton::clicked, this, [this] {
        for (int k = 0; k < kMaxSectionPlanes; ++k)
            m_rows[size_t(k)].enabled->setChecked(false);
    });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);
    m_built = true;
    changed();
}

void SectionDialog::enableRow(int k, bool on) {
    Row& r = m_rows[size_t(k)];
    if (on && !m_quiet && m_centre) {
        // A plane starts through the model's middle, so that it cuts something.
        const glm::dvec3 c = m_centre();
        m_quiet = true;
        for (int i = 0; i < 3; ++i)
            r.position[size_t(i)]->setValue(c[i]);
        m_quiet = false;
    }
    for (int i = 0; i < 3; ++i) {
        r.position[size_t(i)]->setEnabled(on);
        r.normal[size_t(i)]->setEnabled(on);
    }
    r.flip->setEnabled(on);
    changed();
}

void SectionDialog::setSections(const std::vector<SectionPlane>& planes, bool caps) {
    m_quiet = true;
    for (int k = 0; k < kMaxSectionPlanes; ++k) {
        Row& r = m_rows[size_t(k)];
        const bool on = k < int(planes.size());
        if (on) {
            const SectionPlane& p = planes[size_t(k)];
            for (int i = 0; i < 3; ++i) {
                r.position[size_t(i)]->setValue(p.position[i]);
                r.normal[size_t(i)]->setValue(p.normal[i]);
            }
            r.flip->setChecked(p.flip);
        }
        r.enabled->setChecked(on);
        enableRow(k, on);
    }
    m_caps->setChecked(caps);
    changed(); // the rows' status, quietly
    m_quiet = false;
}

std::vector<SectionPlane> SectionDialog::sections() const {
    std::vector<SectionPlane> out;
    for (const Row& r : m_rows)
        if (r.enabled->isChecked() && checkSectionPlane(r.plane()))
            out.push_back(r.plane());
    return out;
}

bool SectionDialog::caps() const {
    return m_caps->isChecked();
}

void SectionDialog::changed() {
    if (!m_built)
        return; // the constructor is filling the fields
    for (Row& r : m_rows) {
        const QString why =
            r.enabled->isChecked() ? checkSectionPlane(r.plane()).message() : QString();
        // A zero normal gives no plane: said here, and the others still cut.
        r.status->setText(why.isEmpty() ? QString() : tr("No plane: %1").arg(why));
    }
    if (!m_quiet)
        Q_EMIT sectionsChanged(sections(), caps());
}

} // namespace kw
