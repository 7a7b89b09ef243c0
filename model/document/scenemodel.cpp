// SceneModel: tree of surfaces, control nets, trim loops and trim curves over a Document.
#include "model/document/scenemodel.h"

namespace kw {

namespace {

static_assert(sizeof(quintptr) >= 8, "SceneModel packs two 32-bit ids into internalId");

quintptr packId(SurfaceId s, TrimLoopId l = {}) {
    return (quintptr(s.value) << 32) | l.value;
}
SurfaceId surfacePart(quintptr id) {
    return SurfaceId{std::uint32_t(id >> 32)};
}
TrimLoopId loopPart(quintptr id) {
    return TrimLoopId{std::uint32_t(id & 0xffffffffu)};
}

int loopIndex(const Surface& s, TrimLoopId id) {
    for (size_t i = 0; i < s.trims.size(); ++i)
        if (s.trims[i].id == id)
            return int(i);
    return -1;
}

QString plural(int n, const char* one, const char* many) {
    return QStringLiteral("%1 %2").arg(n).arg(QLatin1String(n == 1 ? one : many));
}

} // namespace

SceneModel::SceneModel(const Document& document, QObject* parent)
    : QAbstractItemModel(parent), m_doc(&document) {
    connect(m_doc, &Document::sceneAboutToBeReset, this, [this] { beginResetModel(); });
    connect(m_doc, &Document::sceneReset, this, [this] { endResetModel(); });
    connect(m_doc, &Document::surfaceAboutToBeInserted, this,
            [this](int index) { beginInsertRows({}, index, index); });
    connect(m_doc, &Document::surfaceInserted, this, [this] { endInsertRows(); });
    connect(m_doc, &Document::surfaceAboutToBeRemoved, this,
            [this](SurfaceId, int index) { beginRemoveRows({}, index, index); });
    connect(m_doc, &Document::surfaceRemoved, this, [this] { endRemoveRows(); });
    // Row 0 under a surface is its control net, so trim loop k is row k + 1.
    connect(m_doc, &Document::trimLoopAboutToBeInserted, this, [this](SurfaceId id, int index) {
        beginInsertRows(surfaceIndex(id), index + 1, index + 1);
    });
    connect(m_doc, &Document::trimLoopInserted, this, [this] { endInsertRows(); });
    connect(m_doc, &Document::trimLoopAboutToBeRemoved, this, [this](SurfaceId id, int index) {
        beginRemoveRows(surfaceIndex(id), index + 1, index + 1);
    });
    connect(m_doc, &Document::trimLoopRemoved, this, [this] { endRemoveRows(); });
    connect(m_doc, &Document::surfaceChanged, this, &SceneModel::onSurfaceChanged);
}

QModelIndex SceneModel::surfaceIndex(SurfaceId id) const {
    const int row = m_doc->indexOf(id);
    return row < 0 ? QModelIndex() : createIndex(row, 0, quintptr(0));
}

QModelIndex SceneModel::controlNetIndex(SurfaceId id) const {
    return m_doc->indexOf(id) < 0 ? QModelIndex() : createIndex(0, 0, packId(id));
}

QModelIndex SceneModel::trimLoopIndex(SurfaceId id, TrimLoopId loop) const {
    const Surface* s = m_doc->surface(id);
    const int li = s ? loopIndex(*s, loop) : -1;
    return li < 0 ? QModelIndex() : createIndex(li + 1, 0, packId(id));
}

SurfaceId SceneModel::surfaceOf(const QModelIndex& index) const {
    Node node;
    return resolve(index, node) ? node.surface->id : SurfaceId{};
}

bool SceneModel::resolve(const QModelIndex& index, Node& node) const {
    if (!index.isValid() || index.model() != this || index.column() != 0 || index.row() < 0)
        return false;
    const auto& surfaces = m_doc->scene().surfaces;
    const quintptr packed = index.internalId();
    if (packed == 0) {
        if (size_t(index.row()) >= surfaces.size())
            return false;
        node = Node{Kind::Surface, &surfaces[size_t(index.row())]};
        return true;
    }
    const Surface* s = m_doc->surface(surfacePart(packed));
    if (!s)
        return false;
    const TrimLoopId loop = loopPart(packed);
    if (!loop.isValid()) {
        if (index.row() == 0) {
            node = Node{Kind::ControlNet, s};
            return true;
        }
        if (size_t(index.row()) > s->trims.size())
            return false;
        node = Node{Kind::TrimLoop, s, index.row() - 1};
        return true;
    }
    const int li = loopIndex(*s, loop);
    if (li < 0 || size_t(index.row()) >= s->trims[size_t(li)].curves.size())
        return false;
    node = Node{Kind::TrimCurve, s, li, index.row()};
    return true;
}

QModelIndex SceneModel::index(int row, int column, const QModelIndex& parent) const {
    if (!hasIndex(row, column, parent))
        return {};
    if (!parent.isValid())
        return createIndex(row, column, quintptr(0));
    Node p;
    if (!resolve(parent, p))
        return {};
    if (p.kind == Kind::Surface)
        return createIndex(row, column, packId(p.surface->id));
    if (p.kind == Kind::TrimLoop)
        return createIndex(row, column, packId(p.surface->id, p.surface->trims[size_t(p.loop)].id));
    return {};
}

QModelIndex SceneModel::parent(const QModelIndex& child) const {
    if (!child.isValid() || child.internalId() == 0)
        return {};
    const SurfaceId sid = surfacePart(child.internalId());
    const TrimLoopId loop = loopPart(child.internalId());
    return loop.isValid() ? trimLoopIndex(sid, loop) : surfaceIndex(sid);
}

int SceneModel::rowCount(const QModelIndex& parent) const {
    if (!parent.isValid())
        return int(m_doc->scene().surfaces.size());
    Node p;
    if (!resolve(parent, p))
        return 0;
    if (p.kind == Kind::Surface)
        return 1 + int(p.surface->trims.size());
    if (p.kind == Kind::TrimLoop)
        return int(p.surface->trims[size_t(p.loop)].curves.size());
    return 0;
}

int SceneModel::columnCount(const QModelIndex& parent) const {
    Node p;
    return !parent.isValid() || resolve(parent, p) ? 1 : 0;
}

QVariant SceneModel::data(const QModelIndex& index, int role) const {
    Node n;
    if (!resolve(index, n))
        return {};
    const Surface& s = *n.surface;
    switch (role) {
    case Qt::DisplayRole:
        switch (n.kind) {
        case Kind::Surface:
            return s.name;
        case Kind::ControlNet:
            return QStringLiteral("Control net (%1 × %2)")
                .arg(s.geometry.countU)
                .arg(s.geometry.countV);
        case Kind::TrimLoop:
            return QStringLiteral("Trim loop %1 (%2)")
                .arg(s.trims[size_t(n.loop)].id.value)
                .arg(plural(int(s.trims[size_t(n.loop)].curves.size()), "curve", "curves"));
        case Kind::TrimCurve: {
            const NurbsCurve2& c = s.trims[size_t(n.loop)].curves[size_t(n.curve)];
            return QStringLiteral("Curve %1, degree %2, %3")
                .arg(n.curve + 1)
                .arg(c.degree)
                .arg(plural(int(c.points.size()), "point", "points"));
        }
        }
        return {};
    case Qt::EditRole:
        return n.kind == Kind::Surface ? QVariant(s.name) : QVariant();
    case IdRole:
        if (n.kind == Kind::Surface)
            return QVariant::fromValue(s.id);
        if (n.kind == Kind::TrimLoop)
            return QVariant::fromValue(s.trims[size_t(n.loop)].id);
        return {};
    case SurfaceIdRole:
        return QVariant::fromValue(s.id);
    case KindRole:
        return int(n.kind);
    default:
        return {};
    }
}

bool SceneModel::setData(const QModelIndex& index, const QVariant& value, int role) {
    Node n;
    if (role != Qt::EditRole || !m_rename || !resolve(index, n) || n.kind != Kind::Surface)
        return false;
    const QString name = value.toString();
    if (name.trimmed().isEmpty() || name == n.surface->name)
        return false;
    m_rename(n.surface->id, name);
    return true;
}

Qt::ItemFlags SceneModel::flags(const QModelIndex& index) const {
    Node n;
    if (!resolve(index, n))
        return Qt::NoItemFlags;
    Qt::ItemFlags f = Qt::ItemIsEnabled | Qt::ItemIsSelectable;
    if (n.kind == Kind::Surface && m_rename)
        f |= Qt::ItemIsEditable;
    if (n.kind == Kind::ControlNet || n.kind == Kind::TrimCurve)
        f |= Qt::ItemNeverHasChildren;
    return f;
}

QVariant SceneModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (section == 0 && orientation == Qt::Horizontal && role == Qt::DisplayRole)
        return QStringLiteral("Scene");
    return {};
}

void SceneModel::onSurfaceChanged(SurfaceId id, Aspects aspects) {
    const QModelIndex surface = surfaceIndex(id);
    if (!surface.isValid())
        return;
    if (aspects & Aspect::Name)
        Q_EMIT dataChanged(surface, surface, {Qt::DisplayRole, Qt::EditRole});
    if (aspects & Aspect::Knots) {
        const QModelIndex net = controlNetIndex(id);
        Q_EMIT dataChanged(net, net, {Qt::DisplayRole});
    }
    const int loops = rowCount(surface) - 1;
    if ((aspects & Aspect::Trims) && loops > 0) {
        Q_EMIT dataChanged(index(1, 0, surface), index(loops, 0, surface), {Qt::DisplayRole});
        for (int k = 1; k <= loops; ++k) {
            const QModelIndex loop = index(k, 0, surface);
            const int curves = rowCount(loop);
            if (curves > 0)
                Q_EMIT dataChanged(index(0, 0, loop), index(curves - 1, 0, loop),
                                   {Qt::DisplayRole});
        }
    }
}

} // namespace kw
