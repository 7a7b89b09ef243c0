// The Properties panel's measured values: the current face's surface type, degrees, trimmed
// area and bounding box, and the model's total area, closed-solid volume and bounding box,
// computed off the GUI thread from the exact geometry (model/analysis/mass_properties.h).
#pragma once

#include "model/analysis/mass_properties.h"

#include <QHash>
#include <QWidget>
#include <cstdint>

class QLabel;
class QTimer;

namespace kw {

class Document;
class Selection;

class MeasuredProperties : public QWidget {
    Q_OBJECT
public:
    /// Both must outlive the widget.
    MeasuredProperties(Document* document, Selection* selection, QWidget* parent = nullptr);
    ~MeasuredProperties() override;

    /// True while a computation for the current document state is running or scheduled.
    bool pending() const;
    /// The texts shown (for tests and copying): the face's and the model's, "" when none.
    QString faceText() const;
    QString modelText() const;
    /// Faces measured since construction (a face the cache still holds is not measured again).
    int facesMeasured() const { return m_measured; }

Q_SIGNALS:
    /// The values of the current state are shown.
    void updated();

private:
    /// Recomputes kDelayMs after the last change (a drag changes the document many times a
    /// second; one computation when it rests).
    void schedule();
    void start();
    void show(std::uint64_t generation, SurfaceId face, const std::optional<FaceProperties>& f,
              const ModelProperties& m);

    /// A face's measure while its shape and trims keep the revisions it was taken at: after an
    /// edit only the faces it changed are measured again.
    struct Cached {
        std::uint64_t points = 0, knots = 0, trims = 0;
        FaceMeasure measure;
    };
    QHash<SurfaceId, Cached> m_cache;
    int m_measured = 0;

    Document* m_doc;
    Selection* m_selection;
    QTimer* m_timer;
    QLabel* m_face;
    QLabel* m_model;
    std::uint64_t m_generation = 0; ///< of the newest request; older results are dropped
    std::uint64_t m_shown = 0;      ///< generation of the values shown
};

} // namespace kw
