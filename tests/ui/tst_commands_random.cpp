// Random command sequences: ≥ 1000 seeded commands of every kind, then undo all / redo all must
// reproduce every intermediate scene exactly, the item model signals each row change, and revisions
// move for exactly the signalled aspects.
// Reproduce a failure with KW_TEST_SEED=<seed printed in the log>.
#include "model/document/scenemodel.h"
#include "model_fixtures.h"
#include "signallog.h"
#include "ui/edit/commands.h"

#include <QAbstractItemModelTester>
#include <QTest>
#include <QUndoStack>
#include <algorithm>
#include <map>
#include <numeric>
#include <random>

using namespace kw;
using namespace kw::test;

namespace {

enum Kind {
    KMove,
    KWeight,
    KPartitions,
    KKnotVector,
    KInsertKnot,
    KElevate,
    KAddSurface,
    KRemoveSurface,
    KRename,
    KAddLoop,
    KRemoveLoop,
    KMoveTrim,
    KMaterial,
    KLights,
    KCamera,
    KindCount
};

/// Rows the model should insert/remove when a command runs (top level = surfaces, loops).
struct RowDelta {
    int surfacesIn = 0, surfacesOut = 0, loopsIn = 0, loopsOut = 0;
    bool operator==(const RowDelta&) const = default;
};

/// The kind a command actually is (make() redirects some requests, e.g. remove -> add).
int kindOf(const QUndoCommand* c) {
    if (dynamic_cast<const MoveControlPoints*>(c))
        return KMove;
    if (dynamic_cast<const SetWeight*>(c))
        return KWeight;
    if (dynamic_cast<const SetPartitions*>(c))
        return KPartitions;
    if (dynamic_cast<const SetKnotVector*>(c))
        return KKnotVector;
    if (dynamic_cast<const InsertKnot*>(c))
        return KInsertKnot;
    if (dynamic_cast<const ElevateDegree*>(c))
        return KElevate;
    if (dynamic_cast<const AddSurface*>(c))
        return KAddSurface;
    if (dynamic_cast<const RemoveSurface*>(c))
        return KRemoveSurface;
    if (dynamic_cast<const RenameSurface*>(c))
        return KRename;
    if (dynamic_cast<const AddTrimLoop*>(c))
        return KAddLoop;
    if (dynamic_cast<const RemoveTrimLoop*>(c))
        return KRemoveLoop;
    if (dynamic_cast<const MoveTrimPoints*>(c))
        return KMoveTrim;
    if (dynamic_cast<const SetMaterial*>(c))
        return KMaterial;
    if (dynamic_cast<const SetLights*>(c))
        return KLights;
    if (dynamic_cast<const SetCamera*>(c))
        return KCamera;
    return KindCount;
}

RowDelta expectedRows(const QUndoCommand* c, bool undo) {
    RowDelta d;
    int* in = nullptr;
    int* out = nullptr;
    if (dynamic_cast<const AddSurface*>(c))
        in = &d.surfacesIn, out = &d.surfacesOut;
    else if (dynamic_cast<const RemoveSurface*>(c))
        in = &d.surfacesOut, out = &d.surfacesIn;
    else if (dynamic_cast<const AddTrimLoop*>(c))
        in = &d.loopsIn, out = &d.loopsOut;
    else if (dynamic_cast<const RemoveTrimLoop*>(c))
        in = &d.loopsOut, out = &d.loopsIn;
    if (in)
        ++*(undo ? out : in);
    return d;
}

class Runner {
public:
    explicit Runner(std::uint32_t seed) : m_rng(seed), m_log(&m_doc) {
        m_stack.setUndoLimit(0);
        if (!m_doc.resetScene(threeSurfaceScene()))
            qFatal("fixture scene invalid");
        QObject::connect(&m_model, &QAbstractItemModel::rowsInserted, [this](const QModelIndex& p) {
            ++(p.isValid() ? m_rows.loopsIn : m_rows.surfacesIn);
        });
        QObject::connect(&m_model, &QAbstractItemModel::rowsRemoved, [this](const QModelIndex& p) {
            ++(p.isValid() ? m_rows.loopsOut : m_rows.surfacesOut);
        });
        QObject::connect(&m_doc, &Document::surfaceChanged,
                         [this](SurfaceId id, Aspects a) { m_changed[id.value] |= a; });
        m_snapshots.push_back(m_doc.scene());
    }

    Document m_doc;
    QUndoStack m_stack;
    SceneModel m_model{m_doc};
    QAbstractItemModelTester m_tester{&m_model,
                                      QAbstractItemModelTester::FailureReportingMode::Fatal};
    std::mt19937 m_rng;
    SignalLog m_log;
    RowDelta m_rows;
    std::map<std::uint32_t, Aspects> m_changed; ///< surfaceChanged aspects since beginStep()
    std::map<std::uint32_t, Revisions> m_revisionsBefore;
    std::vector<Scene> m_snapshots; ///< scene at each stack index
    int m_pushed[KindCount] = {};
    int m_rejected = 0;
    QString m_lastError; ///< reason of the last rejection, for failure messages
    // Last nudge / weight target, reused now and then so merges happen.
    SurfaceId m_nudgeSurface;
    std::vector<int> m_nudgeIndices;
    SurfaceId m_weightSurface;
    int m_weightIndex = -1;

    double uniform(double a, double b) { return std::uniform_real_distribution<>(a, b)(m_rng); }
    int pick(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(m_rng); }
    bool coin(double p = 0.5) { return uniform(0, 1) < p; }
    const Surface* randomSurface() {
        const auto& s = m_doc.scene().surfaces;
        return s.empty() ? nullptr : &s[size_t(pick(0, int(s.size()) - 1))];
    }

    /// The factory's command, or nullptr with its reason kept in m_lastError.
    template <class C> std::unique_ptr<QUndoCommand> made(Expected<std::unique_ptr<C>> command) {
        if (!command) {
            m_lastError = command.message();
            return nullptr;
        }
        return std::move(*command);
    }
    /// Builds one random command; `expectReject` is set when it was made invalid on purpose.
    std::unique_ptr<QUndoCommand> make(Kind kind, bool& expectReject);
    /// Makes and pushes one command, checking signals, revisions, rows and the snapshot.
    void step(Kind kind);
    void undoOne();
    void redoOne();
    void checkModel() const;
    /// Resets the signal counters and remembers every surface's revisions.
    void beginStep();
    /// Each surface present before and after: exactly the aspects it signalled got new
    /// revisions, the others kept theirs.
    void checkRevisions() const;
};

std::unique_ptr<QUndoCommand> Runner::make(Kind kind, bool& expectReject) {
    expectReject = false;
    const Surface* s = randomSurface();
    if (!s)
        kind = KAddSurface;
    const SurfaceId id = s ? s->id : SurfaceId{};
    switch (kind) {
    case KMove: {
        std::vector<int> idx;
        MoveKind mk = coin() ? MoveKind::Nudge : MoveKind::Drag;
        const bool reusable = m_nudgeSurface == id &&
                              std::all_of(m_nudgeIndices.begin(), m_nudgeIndices.end(), [&](int i) {
                                  return size_t(i) < s->geometry.points.size();
                              });
        if (mk == MoveKind::Nudge && reusable && coin(0.7)) {
            idx = m_nudgeIndices;
        } else {
            const int n = pick(1, 3);
            while (int(idx.size()) < n) {
                const int i = pick(0, int(s->geometry.points.size()) - 1);
                if (std::find(idx.begin(), idx.end(), i) == idx.end())
                    idx.push_back(i);
            }
        }
        if (mk == MoveKind::Nudge)
            m_nudgeSurface = id, m_nudgeIndices = idx;
        std::vector<glm::dvec3> from, to;
        for (int i : idx) {
            from.push_back(s->geometry.points[size_t(i)]);
            to.push_back(from.back() + glm::dvec3(uniform(-1, 1), uniform(-1, 1), 0.25));
        }
        return made(MoveControlPoints::create(&m_doc, id, idx, from, to, mk));
    }
    case KWeight: {
        if (!(m_weightSurface == id && coin(0.6)) ||
            size_t(m_weightIndex) >= s->geometry.weights.size())
            m_weightSurface = id, m_weightIndex = pick(0, int(s->geometry.weights.size()) - 1);
        return made(SetWeight::create(&m_doc, id, m_weightIndex, uniform(0.5, 2.0)));
    }
    case KPartitions:
        if (coin(0.1)) {
            expectReject = true;
            return made(SetPartitions::create(&m_doc, id, 0, pick(1, 500)));
        }
        return made(SetPartitions::create(&m_doc, id, pick(1, 64), pick(1, 64)));
    case KKnotVector: {
        const Direction dir = coin() ? Direction::U : Direction::V;
        const NurbsSurface& g = s->geometry;
        std::vector<double> k = dir == Direction::U ? g.knotsU : g.knotsV;
        const int p = dir == Direction::U ? g.degreeU : g.degreeV;
        // Interior knots that can move (their neighbours differ); none after some elevations.
        std::vector<int> movable;
        for (int i = p + 1; i < int(k.size()) - p - 1; ++i)
            if (k[size_t(i - 1)] < k[size_t(i + 1)])
                movable.push_back(i);
        if (coin(0.15)) { // decreasing: must be rejected
            expectReject = true;
            k[k.size() / 2] = k.front() - 1.0;
        } else if (!movable.empty()) {
            const int i = movable[size_t(pick(0, int(movable.size()) - 1))];
            const double old = k[size_t(i)];
            do
                k[size_t(i)] = uniform(k[size_t(i - 1)], k[size_t(i + 1)]);
            while (k[size_t(i)] == old || k[size_t(i)] == k[size_t(i - 1)]);
        } else {
            const double scale = uniform(0.5, 2.0);
            for (double& x : k)
                x *= scale;
        }
        return made(SetKnotVector::create(&m_doc, id, dir, k));
    }
    case KInsertKnot: {
        const Direction dir = coin() ? Direction::U : Direction::V;
        const NurbsSurface& g = s->geometry;
        const Interval d = dir == Direction::U ? surfaceDomainU(g) : surfaceDomainV(g);
        if ((dir == Direction::U ? g.countU : g.countV) >= 9 || coin(0.1)) {
            expectReject = true; // outside the domain
            return made(InsertKnot::create(&m_doc, id, dir, d.last + 1.0));
        }
        return made(InsertKnot::create(&m_doc, id, dir, uniform(d.first, d.last)));
    }
    case KElevate: {
        const Direction dir = coin() ? Direction::U : Direction::V;
        const NurbsSurface& g = s->geometry;
        const int p = dir == Direction::U ? g.degreeU : g.degreeV;
        const int n = dir == Direction::U ? g.countU : g.countV;
        if (p >= 4 || n >= 9) {
            expectReject = true;
            return made(ElevateDegree::create(&m_doc, id, dir, kMaxDegree));
        }
        return made(ElevateDegree::create(&m_doc, id, dir));
    }
    case KAddSurface: {
        if (m_doc.scene().surfaces.size() >= 7)
            return make(KRemoveSurface, expectReject);
        Surface n = makeSurface(0, QStringLiteral("S%1").arg(pick(0, 999)),
                                patch(pick(2, 6), pick(2, 6), uniform(-5, 5), uniform(0, 2)));
        if (coin())
            n.trims.push_back(rectLoop({}, 0.1, 0.1, uniform(0.2, 0.9), 0.8, coin()));
        return made(AddSurface::create(&m_doc, n, pick(0, int(m_doc.scene().surfaces.size()))));
    }
    case KRemoveSurface:
        if (m_doc.scene().surfaces.size() <= 2)
            return make(KAddSurface, expectReject);
        return made(RemoveSurface::create(&m_doc, id));
    case KRename:
        return made(RenameSurface::create(&m_doc, id, QStringLiteral("N%1").arg(pick(0, 1 << 20))));
    case KAddLoop: {
        const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
        const double u0 = uniform(du.first, du.last), v0 = uniform(dv.first, dv.last);
        const double u1 = uniform(u0, du.last), v1 = uniform(v0, dv.last);
        if (s->trims.size() >= 4)
            return make(KRemoveLoop, expectReject);
        return made(AddTrimLoop::create(&m_doc, id, rectLoop({}, u0, v0, u1, v1, coin()),
                                        pick(0, int(s->trims.size()))));
    }
    case KRemoveLoop:
        if (s->trims.empty())
            return make(KAddLoop, expectReject);
        return made(RemoveTrimLoop::create(&m_doc, id,
                                           s->trims[size_t(pick(0, int(s->trims.size()) - 1))].id));
    case KMoveTrim: {
        if (s->trims.empty())
            return make(KAddLoop, expectReject);
        const TrimLoop& l = s->trims[size_t(pick(0, int(s->trims.size()) - 1))];
        const int c = pick(0, int(l.curves.size()) - 1);
        const int i = pick(0, int(l.curves[size_t(c)].points.size()) - 1);
        const glm::dvec2 p = l.curves[size_t(c)].points[size_t(i)];
        // A curve's end point is shared with the next curve (or its own start): moving it alone
        // opens the loop, which the document's rule refuses.
        expectReject = i == 0 || i == int(l.curves[size_t(c)].points.size()) - 1;
        return made(
            MoveTrimPoints::create(&m_doc, {{id, l.id, c, i}}, {p},
                                   {p + glm::dvec2(uniform(-0.05, 0.05), uniform(-0.05, 0.05))},
                                   coin() ? MoveKind::Nudge : MoveKind::Drag));
    }
    case KMaterial: {
        Material m;
        m.color = {uniform(0, 1), uniform(0, 1), uniform(0, 1)};
        m.kd = uniform(0, 1);
        m.shininess = uniform(1, 100);
        if (coin(0.1)) {
            expectReject = true;
            m.ks = -1.0;
        }
        return made(SetMaterial::create(&m_doc, id, m));
    }
    case KLights: {
        const int n = int(m_doc.scene().lights.size());
        Light l;
        l.kind = coin() ? Light::Kind::Point : Light::Kind::Directional;
        l.vector = {uniform(-1, 1), uniform(-1, 1), uniform(0.5, 1)};
        const int which = pick(0, 2);
        if (which == 0 && n < kMaxLights)
            return made(SetLights::addLight(&m_doc, l));
        if (which == 1 && n > 1)
            return made(SetLights::removeLight(&m_doc, pick(0, n - 1)));
        return made(SetLights::changeLight(&m_doc, pick(0, n - 1), l));
    }
    case KCamera: {
        Camera c = m_doc.scene().camera;
        c.eye = {uniform(-9, 9), uniform(-9, -1), uniform(1, 9)};
        c.authored = true;
        return made(SetCamera::create(&m_doc, c));
    }
    case KindCount:
        break;
    }
    return nullptr;
}

void Runner::checkModel() const {
    const auto& surfaces = m_doc.scene().surfaces;
    QCOMPARE(m_model.rowCount(), int(surfaces.size()));
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const QModelIndex si = m_model.index(int(i), 0);
        QCOMPARE(m_model.data(si, SceneModel::IdRole).value<SurfaceId>(), surfaces[i].id);
        QCOMPARE(m_model.rowCount(si), 1 + int(surfaces[i].trims.size()));
    }
}

void Runner::beginStep() {
    m_rows = {};
    m_changed.clear();
    m_revisionsBefore.clear();
    for (const Surface& s : m_doc.scene().surfaces)
        m_revisionsBefore[s.id.value] = m_doc.revisions(s.id);
}

void Runner::checkRevisions() const {
    for (const auto& [id, before] : m_revisionsBefore) {
        if (m_doc.indexOf(SurfaceId{id}) < 0)
            continue;
        const Revisions after = m_doc.revisions(SurfaceId{id});
        const auto it = m_changed.find(id);
        const Aspects a = it == m_changed.end() ? Aspects() : it->second;
        const auto check = [&](Aspect aspect, std::uint64_t b, std::uint64_t n) {
            return (a & aspect) ? n > b : n == b;
        };
        QVERIFY2(check(Aspect::Points, before.points, after.points) &&
                     check(Aspect::Knots, before.knots, after.knots) &&
                     check(Aspect::Trims, before.trims, after.trims) &&
                     check(Aspect::Display, before.display, after.display),
                 qPrintable(QStringLiteral("surface %1: revisions do not match signalled %2")
                                .arg(id)
                                .arg(aspectsText(a))));
    }
}

void Runner::step(Kind kind) {
    const Scene before = m_doc.scene();
    const int indexBefore = m_stack.index();
    bool expectReject = false;
    std::unique_ptr<QUndoCommand> cmd = make(kind, expectReject);
    if (!cmd) {
        QVERIFY2(expectReject,
                 qPrintable(QStringLiteral("a valid random edit of kind %1 was rejected: %2")
                                .arg(kind)
                                .arg(m_lastError)));
        QCOMPARE(m_doc.scene(), before); // rejection changes nothing, allocates no id
        QCOMPARE(m_stack.index(), indexBefore);
        ++m_rejected;
        return;
    }
    QVERIFY2(!expectReject, qPrintable(cmd->text()));
    const RowDelta expected = expectedRows(cmd.get(), false);
    const bool isMove = dynamic_cast<MoveControlPoints*>(cmd.get()) != nullptr;
    m_log.take();
    beginStep();
    const std::uint64_t nextBefore = m_doc.scene().nextId;
    const int actual = kindOf(cmd.get());
    QVERIFY(actual < KindCount);
    ++m_pushed[actual];
    pushCommand(&m_stack, std::move(cmd));
    QCOMPARE(m_rows, expected);
    QVERIFY(m_doc.scene().nextId >= nextBefore);
    const QStringList log = m_log.take();
    if (isMove) {
        // One move: exactly one Points change of one surface, and no other signal.
        QCOMPARE(log.size(), 1);
        QVERIFY2(log[0].startsWith(QStringLiteral("changed ")) &&
                     log[0].endsWith(QStringLiteral(" Points")),
                 qPrintable(log[0]));
    }
    const int index = m_stack.index();
    QVERIFY(index == indexBefore + 1 || index == indexBefore || index == indexBefore - 1);
    if (index < indexBefore) // merged into an edit that now changes nothing
        QVERIFY(sameContent(m_doc.scene(), m_snapshots[size_t(index)]));
    m_snapshots.resize(size_t(index) + 1);
    m_snapshots[size_t(index)] = m_doc.scene();
    checkModel();
    checkRevisions();
}

void Runner::undoOne() {
    const QUndoCommand* c = m_stack.command(m_stack.index() - 1);
    const RowDelta expected = expectedRows(c, true);
    beginStep();
    m_stack.undo();
    QCOMPARE(m_rows, expected);
    QVERIFY(sameContent(m_doc.scene(), m_snapshots[size_t(m_stack.index())]));
    checkModel();
    checkRevisions();
}

void Runner::redoOne() {
    const QUndoCommand* c = m_stack.command(m_stack.index());
    const RowDelta expected = expectedRows(c, false);
    beginStep();
    m_stack.redo();
    QCOMPARE(m_rows, expected);
    QVERIFY(sameContent(m_doc.scene(), m_snapshots[size_t(m_stack.index())]));
    checkModel();
    checkRevisions();
}

} // namespace

class TestCommandsRandom : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void randomSequence_data();
    void randomSequence();
};

void TestCommandsRandom::randomSequence_data() {
    QTest::addColumn<std::uint32_t>("seed");
    bool fromEnv = false;
    const std::uint32_t env = qEnvironmentVariable("KW_TEST_SEED").toUInt(&fromEnv);
    if (fromEnv) {
        QTest::addRow("seed %u", env) << env;
        return;
    }
    for (std::uint32_t s : {20261121u, 7u, 424242u})
        QTest::addRow("seed %u", s) << s;
}

void TestCommandsRandom::randomSequence() {
    QFETCH(std::uint32_t, seed);
    qInfo("random command sequence, seed %u (rerun with KW_TEST_SEED=%u)", seed, seed);
    Runner r(seed);
    const Scene original = r.m_doc.scene();
    int pushes = 0;
    while (pushes < 1200) {
        r.step(Kind(r.pick(0, KindCount - 1)));
        if (QTest::currentTestFailed())
            return;
        pushes = std::accumulate(std::begin(r.m_pushed), std::end(r.m_pushed), 0);
        // Now and then step back and forth inside the history, then carry on (which drops
        // the redo tail), as a user would.
        if (r.coin(0.03)) {
            const int back = std::min(r.pick(1, 6), r.m_stack.index());
            for (int k = 0; k < back; ++k)
                r.undoOne();
            for (int k = r.pick(0, back); k > 0; --k)
                r.redoOne();
            if (QTest::currentTestFailed())
                return;
        }
    }
    for (int k = 0; k < KindCount; ++k)
        QVERIFY2(r.m_pushed[k] > 0, qPrintable(QStringLiteral("kind %1 never pushed").arg(k)));
    QVERIFY(r.m_rejected > 0);
    qInfo("%d commands pushed, %d invalid edits rejected, %d undo steps", pushes, r.m_rejected,
          r.m_stack.index());

    while (r.m_stack.canRedo()) // the last excursion may have left a redo tail
        r.redoOne();
    const Scene end = r.m_doc.scene();
    const int endIndex = r.m_stack.index();
    QVERIFY(endIndex > 100);
    while (r.m_stack.canUndo()) {
        r.undoOne();
        if (QTest::currentTestFailed())
            return;
    }
    QVERIFY(sameContent(r.m_doc.scene(), original));
    QCOMPARE(r.m_stack.index(), 0);
    while (r.m_stack.canRedo()) {
        r.redoOne();
        if (QTest::currentTestFailed())
            return;
    }
    QCOMPARE(r.m_stack.index(), endIndex);
    QCOMPARE(r.m_doc.scene(), end); // redo allocates nothing: exactly the end state
}

QTEST_GUILESS_MAIN(TestCommandsRandom)
#include "tst_commands_random.moc"
