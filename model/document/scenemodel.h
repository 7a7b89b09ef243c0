// SceneModel: a tree view of a Document (surfaces, their control nets, trim loops and curves).
#pragma once

#include "model/document/document.h"

#include <QAbstractItemModel>
#include <functional>

namespace kw {

/// Read-only tree over a Document, kept in step with the document's signals:
///   surface "name"                       (editable: column 0, EditRole)
///     "Control net (m × n)"
///     "Trim loop k (c curves)"             k is the loop's id
///       "Curve k, degree d, n points"        k counts from 1 within the loop
/// Loops are labelled by id, not position, so a label never changes when a sibling loop is
/// inserted or removed (views and QAbstractItemModelTester rely on unchanged neighbours).
/// Rows are addressed through typed ids (internalId = surface id << 32 | loop id), so
/// persistent indexes survive insertions and removals elsewhere.
///
/// Renaming: setData never writes the document. It passes the new name to the rename handler
/// (set with setRenameHandler), which is expected to push a RenameSurface command; the
/// document's surfaceChanged(Name) then refreshes the row. Without a handler surface rows are
/// not editable and setData returns false. A handler (rather than a signal) lets setData
/// report whether anyone took the edit.
class SceneModel : public QAbstractItemModel {
    Q_OBJECT
public:
    enum Role {
        /// The row's own typed id: SurfaceId on surface rows, TrimLoopId on trim loop rows,
        /// an invalid QVariant on other rows.
        IdRole = Qt::UserRole + 1,
        /// The SurfaceId the row belongs to (every row).
        SurfaceIdRole,
        /// The row's Kind as int.
        KindRole,
    };
    enum class Kind { Surface, ControlNet, TrimLoop, TrimCurve };
    using RenameHandler = std::function<void(SurfaceId, const QString&)>;

    /// `document` must outlive the model (a reference: there is no model without one).
    explicit SceneModel(const Document& document, QObject* parent = nullptr);

    const Document* document() const { return m_doc; }
    void setRenameHandler(RenameHandler handler) { m_rename = std::move(handler); }

    /// Invalid index for an unknown id.
    QModelIndex surfaceIndex(SurfaceId id) const;
    QModelIndex controlNetIndex(SurfaceId id) const;
    QModelIndex trimLoopIndex(SurfaceId id, TrimLoopId loop) const;
    /// The surface a row belongs to; invalid for an invalid index.
    SurfaceId surfaceOf(const QModelIndex& index) const;

    QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
    QModelIndex parent(const QModelIndex& child) const override;
    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    /// Surface rows, EditRole, a non-blank name different from the current one, and a rename
    /// handler: forwards the request and returns true. Otherwise returns false.
    bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;
    QVariant headerData(int section, Qt::Orientation orientation,
                        int role = Qt::DisplayRole) const override;

private:
    struct Node {
        Kind kind = Kind::Surface;
        const Surface* surface = nullptr;
        int loop = -1; ///< index in surface->trims for TrimLoop and TrimCurve rows
        int curve = -1;
    };
    /// Resolves an index against the current document; false if it names nothing.
    bool resolve(const QModelIndex& index, Node& node) const;
    void onSurfaceChanged(SurfaceId id, Aspects aspects);

    const Document* m_doc;
    RenameHandler m_rename;
};

} // namespace kw

Q_DECLARE_METATYPE(kw::TrimLoopId)
