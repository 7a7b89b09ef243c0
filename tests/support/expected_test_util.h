// Test checks for kw::Expected and kw::Status: a failure prints the error's own message.
#pragma once

#include "model/error.h"
#include "tests/support/expected_test_util.h"

#include <QTest>

/// QVERIFY that `expr` (a kw::Expected or kw::Status) succeeded, showing its message if not.
#define KW_VERIFY_OK(expr)                                                                         \
    do {                                                                                           \
        const auto& kwOutcome_ = (expr);                                                           \
        QVERIFY2(bool(kwOutcome_), qPrintable(kwOutcome_.message()));                              \
    } while (false)

namespace kwtest {

/// The reason a kw::Expected or kw::Status gives for failing, or a null QString when it
/// succeeded: `why = refusal(f()); QVERIFY(!why.isNull());` and then assertions on the wording.
template <class Result> QString refusal(const Result& result) {
    if (result)
        return QString();
    const QString why = result.message();
    return why.isNull() ? QStringLiteral("") : why;
}

} // namespace kwtest
