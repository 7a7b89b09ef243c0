// kw::Error and kw::Expected: the one error type every module returns.
#include "model/error.h"

#include <QTest>
#include <memory>

class TestError : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void valueAndError() {
        kw::Expected<int> good = 7;
        QVERIFY(good);
        QCOMPARE(*good, 7);
        QVERIFY(good.message().isEmpty());

        kw::Expected<int> bad = kw::Error(QStringLiteral("a.knot: line 3: bad number"),
                                          QStringLiteral("a.knot"), QStringLiteral("line 3"));
        QVERIFY(!bad);
        QCOMPARE(bad.error().file, QStringLiteral("a.knot"));
        QCOMPARE(bad.error().location, QStringLiteral("line 3"));
        QCOMPARE(bad.message(), QStringLiteral("a.knot: line 3: bad number"));
        QCOMPARE(bad.value_or(-1), -1);
    }
    void qstringValueIsAValue() {
        // A QString converts to Error too; for Expected<QString> the value must win.
        kw::Expected<QString> text = QStringLiteral("hello");
        QVERIFY(text);
        QCOMPARE(*text, QStringLiteral("hello"));
    }
    void moveOnlyValue() {
        kw::Expected<std::unique_ptr<int>> p = std::make_unique<int>(4);
        QVERIFY(p);
        std::unique_ptr<int> taken = std::move(p).value();
        QCOMPARE(*taken, 4);
    }
    void status() {
        kw::Status fine = kw::ok();
        QVERIFY(fine);
        kw::Status failed = kw::Error(QStringLiteral("cannot write"), QStringLiteral("/ro/x.step"));
        QVERIFY(!failed);
        QCOMPARE(failed.error().withFile(), QStringLiteral("/ro/x.step: cannot write"));
        kw::Status named =
            kw::Error(QStringLiteral("/ro/x.step: cannot write"), QStringLiteral("/ro/x.step"));
        QCOMPARE(named.error().withFile(), QStringLiteral("/ro/x.step: cannot write"));
    }
};

QTEST_GUILESS_MAIN(TestError)
#include "tst_error.moc"
