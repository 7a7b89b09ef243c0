// LightsPanel: count, per-light kind, vector and intensities; each change is a SetLights command.
#include "ui/lightspanel.h"

#include "ui/edit/commands.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QUndoStack>

namespace kw {

namespace {

QDoubleSpinBox* spin(double lo, double hi) {
    auto* s = new QDoubleSpinBox;
    s->setRange(lo, hi);
    s->setSingleStep(0.05);
    s->setDecimals(3);
    s->setKeyboardTracking(false);
    return s;
}

} // namespace

LightsPanel::LightsPanel(Document* document, QUndoStack* stack, QWidget* parent)
    : QWidget(parent), m_doc(document), m_stack(stack) {
    auto* form = new QFormLayout(this);
    m_count = new QSpinBox;
    m_count->setRange(1, kMaxLights);
    m_count->setKeyboardTracking(false);
    form->addRow(tr("Lights"), m_count);
    m_which = new QComboBox;
    form->addRow(tr("Edit"), m_which);
    m_kind = new QComboBox;
    m_kind->addItems({tr("Directional (towards light)"), tr("Point (position)")});
    form->addRow(tr("Kind"), m_kind);
    static const char* const names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        m_vector[k] = spin(-1e6, 1e6);
        form->addRow(QLatin1String(names[k]), m_vector[k]);
    }
    m_ambient = spin(0.0, 10.0);
    m_diffuse = spin(0.0, 10.0);
    m_specular = spin(0.0, 10.0);
    form->addRow(tr("Ambient"), m_ambient);
    form->addRow(tr("Diffuse"), m_diffuse);
    form->addRow(tr("Specular"), m_specular);

    connect(m_count, &QSpinBox::valueChanged, this, &LightsPanel::setCount);
    connect(m_which, &QComboBox::currentIndexChanged, this, &LightsPanel::refresh);
    connect(m_kind, &QComboBox::currentIndexChanged, this, &LightsPanel::editLight);
    for (QDoubleSpinBox* s :
         {m_vector[0], m_vector[1], m_vector[2], m_ambient, m_diffuse, m_specular})
        connect(s, &QDoubleSpinBox::valueChanged, this, &LightsPanel::editLight);
    connect(m_doc, &Document::lightsChanged, this, &LightsPanel::refresh);
    connect(m_doc, &Document::sceneReset, this, &LightsPanel::refresh);
    refresh();
}

void LightsPanel::refresh() {
    const std::vector<Light>& lights = m_doc->scene().lights;
    const QSignalBlocker b0(m_count), b1(m_which), b2(m_kind);
    m_count->setValue(int(lights.size()));
    const int keep = std::clamp(m_which->currentIndex(), 0, int(lights.size()) - 1);
    m_which->clear();
    for (size_t k = 0; k < lights.size(); ++k)
        m_which->addItem(tr("Light %1").arg(k + 1));
    m_which->setCurrentIndex(keep);
    if (lights.empty())
        return;
    const Light& l = lights[size_t(keep)];
    m_kind->setCurrentIndex(l.kind == Light::Kind::Directional ? 0 : 1);
    for (int k = 0; k < 3; ++k) {
        const QSignalBlocker b(m_vector[k]);
        m_vector[k]->setValue(l.vector[k]);
    }
    // Intensities are edited as grey levels; coloured lights show their mean.
    auto mean = [](const glm::dvec3& c) {
        return (c.r + c.g + c.b) / 3.0;
    };
    for (auto [box, value] :
         {std::pair{m_ambient, mean(l.ambient)}, std::pair{m_diffuse, mean(l.diffuse)},
          std::pair{m_specular, mean(l.specular)}}) {
        const QSignalBlocker b(box);
        box->setValue(value);
    }
}

void LightsPanel::setCount(int count) {
    const std::vector<Light>& lights = m_doc->scene().lights;
    while (int(m_doc->scene().lights.size()) != count) {
        const int now = int(lights.size());
        const Status pushed =
            pushCommand(m_stack, count > now ? SetLights::addLight(m_doc, lights.back())
                                             : SetLights::removeLight(m_doc, now - 1));
        if (!pushed) {
            Q_EMIT editRejected(pushed.message());
            break;
        }
    }
    refresh();
}

void LightsPanel::editLight() {
    const int index = m_which->currentIndex();
    const std::vector<Light>& lights = m_doc->scene().lights;
    if (index < 0 || size_t(index) >= lights.size())
        return;
    Light l = lights[size_t(index)];
    l.kind = m_kind->currentIndex() == 0 ? Light::Kind::Directional : Light::Kind::Point;
    l.vector = glm::dvec3(m_vector[0]->value(), m_vector[1]->value(), m_vector[2]->value());
    // Keep a coloured light's hue when its level is unchanged.
    auto level = [](glm::dvec3 c, double v) {
        const double m = (c.r + c.g + c.b) / 3.0;
        return std::abs(m - v) < 5e-4 ? c : glm::dvec3(v);
    };
    l.ambient = level(l.ambient, m_ambient->value());
    l.diffuse = level(l.diffuse, m_diffuse->value());
    l.specular = level(l.specular, m_specular->value());
    if (l == lights[size_t(index)])
        return;
    if (const Status pushed = pushCommand(m_stack, SetLights::changeLight(m_doc, index, l));
        !pushed) {
        Q_EMIT editRejected(pushed.message());
        refresh();
    }
}

} // namespace kw
