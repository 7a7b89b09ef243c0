#pragma once
// Knotwork's one error type, used across model, render, ui and app.
//
// A failure is a kw::Error: the user-facing message (the exact wording the user sees, which
// already names the file and the place), plus the file and the place as separate fields, so
// that a caller can add context or a dialog can show them apart. A function that can fail
// returns kw::Expected<T> (or kw::Status when it has no value); it never reports through an
// out-parameter, a bare bool or a lastError(). std::expected is C++23 and this project is
// C++20, so Expected is a small equivalent with the same spelling for the common uses:
//
//     kw::Expected<Scene> readProject(const QString &path);
//     auto scene = readProject(path);
//     if (!scene)
//         return scene.error();          // propagate, wording unchanged
//     use(*scene);
//
//     kw::Status save(...);              // return kw::ok(); or return kw::Error{...};

#include <QString>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

namespace kw {

struct Error {
    QString message;  ///< What the user reads, whole: it names the file and place itself.
    QString file;     ///< The file concerned, when there is one (may be empty).
    QString location; ///< The place in it: "line 12", "entity #45", "surface 3" (may be empty).

    Error() = default;
    Error(QString text) : message(std::move(text)) {}
    Error(const char* text) : message(QString::fromUtf8(text)) {}
    Error(QString text, QString filePath, QString place = {})
        : message(std::move(text)), file(std::move(filePath)), location(std::move(place)) {}

    /// The message prefixed with "<file>: " unless it already names the file.
    QString withFile() const {
        if (file.isEmpty() || message.contains(file))
            return message;
        return file + QStringLiteral(": ") + message;
    }
    bool operator==(const Error&) const = default;
};

template <class T> class [[nodiscard]] Expected {
    static_assert(!std::is_same_v<std::decay_t<T>, Error>, "Expected<Error> is ambiguous");

public:
    using value_type = T;
    using error_type = Error;

    Expected() requires std::is_default_constructible_v<T> : m_v(std::in_place_index<0>) {}
    Expected(const T& value) : m_v(std::in_place_index<0>, value) {}
    Expected(T&& value) : m_v(std::in_place_index<0>, std::move(value)) {}
    Expected(Error error) : m_v(std::in_place_index<1>, std::move(error)) {}

    bool has_value() const noexcept { return m_v.index() == 0; }
    explicit operator bool() const noexcept { return has_value(); }

    T& value() & { return std::get<0>(m_v); }
    const T& value() const& { return std::get<0>(m_v); }
    T&& value() && { return std::get<0>(std::move(m_v)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    template <class U> T value_or(U&& fallback) const& {
        return has_value() ? value() : static_cast<T>(std::forward<U>(fallback));
    }

    const Error& error() const& { return std::get<1>(m_v); }
    Error&& error() && { return std::get<1>(std::move(m_v)); }
    /// The error's message, or an empty string on success (for status lines and logs).
    QString message() const { return has_value() ? QString() : error().message; }

private:
    std::variant<T, Error> m_v;
};

template <> class [[nodiscard]] Expected<void> {
public:
    using value_type = void;
    using error_type = Error;

    Expected() = default;
    Expected(Error error) : m_error(std::move(error)) {}

    bool has_value() const noexcept { return !m_error.has_value(); }
    explicit operator bool() const noexcept { return has_value(); }
    const Error& error() const& { return *m_error; }
    Error&& error() && { return std::move(*m_error); }
    QString message() const { return m_error ? m_error->message : QString(); }

private:
    std::optional<Error> m_error;
};

/// Success or an Error, for functions that have no value to return.
using Status = Expected<void>;
inline Status ok() {
    return {};
}

} // namespace kw
