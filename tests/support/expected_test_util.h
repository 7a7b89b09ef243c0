// Test checks for kw::Expected and kw::Status: a failure prints the error's own message.
#pragma once

#include "model/error.h"

#include <QTest>

/// QVERIFY that `expr` (a kw::Expected or kw::Status) succeeded, showing its message if not.
#define KW_VERIFY_OK(expr)                                                                         \
    do {                                                                                           \
        const auto& kwOutcome_ = (expr);                                                           \
        QVERIFY2(bool(kwOutcome_), qPrintable(kwOutcome_.message()));                              \
    } while (false)
