// A validating reader over a parsed JSON document: every value carries its RFC 6901 JSON pointer,
// so any check on it is one line and any failure is one InputError line
// "<file>: <pointer>: <what is wrong>". Objects remember which keys were read; finish() refuses
// the rest as unknown keys. Internal to host/scene (the scene loaders), not a general JSON API.
#pragma once
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace vkp::json {

/// Documents keep their keys in file order (materials are indexed in file order).
using Json = nlohmann::ordered_json;

/// Escape one reference token of a JSON pointer (RFC 6901 sec. 3: "~" -> "~0", "/" -> "~1").
std::string escapePointerToken(std::string_view token);

/// A short, one-line rendering of a value for messages: numbers and literals as written,
/// strings quoted, long values cut with "...".
std::string describeValue(const Json& value);

/// "<file>: <where>: <message>" with the message forced onto one line. An empty pointer (the
/// document itself) is written as "(document)".
std::string formatError(const std::string& file, std::string_view where, std::string_view message);

/// Parse text as JSON. Refuses invalid JSON with "<file>: line L, column C: invalid JSON: ...",
/// duplicate keys and numbers out of double range with "<file>: <pointer>: ...".
Json parseDocument(const std::string& text, const std::string& file);

/// An allowed interval of numbers, closed or open at either end.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool loOpen = false;
    bool hiOpen = false;

    static Range any() { return {}; }
    static Range atLeast(double lo) { return {lo, any().hi, false, false}; }    ///< [lo, inf)
    static Range above(double lo) { return {lo, any().hi, true, false}; }       ///< (lo, inf)
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }  ///< [lo, hi]
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }      ///< (lo, hi)
    static Range closedOpen(double lo, double hi) { return {lo, hi, false, true}; }  ///< [lo, hi)

    bool contains(double x) const;
    /// "must be > 0", "must be in [0, 1]", ... (empty for any()).
    std::string requirement() const;
};

class Object;

/// One value of the document and where it is.
class Value {
public:
    Value(const Json& json, std::string pointer, const std::string& file)
        : json_(&json), pointer_(std::move(pointer)), file_(&file) {}

    const Json& json() const { return *json_; }
    const std::string& pointer() const { return pointer_; }
    const std::string& file() const { return *file_; }

    /// Throw InputError "<file>: <pointer>: <message>".
    [[noreturn]] void fail(std::string_view message) const;

    Object object() const;                  ///< must be a JSON object
    std::vector<Value> array() const;       ///< must be an array; elements with their pointers
    /// Element i of a value already known to be an array with more than i elements.
    Value element(std::size_t i) const { return Value((*json_)[i], child(i), *file_); }
    std::string string() const;             ///< must be a string
    bool boolean() const;                   ///< must be true or false
    /// A number that is finite as a 32-bit float and inside r.
    float number(const Range& r = Range::any()) const;
    /// A number inside r, in double precision (positions and transforms: the scene is composed
    /// in double and made camera-relative before anything becomes float; docs/design.md
    /// "Camera-relative space"). Every JSON number is a finite double (parseDocument checks).
    double real(const Range& r = Range::any()) const;
    /// An array of exactly 3 numbers, each checked like real(r) at its own pointer.
    glm::dvec3 dvec3(const Range& r = Range::any()) const;
    /// An integer (written with or without a fraction of zero) in [lo, hi].
    std::uint64_t integer(std::uint64_t lo, std::uint64_t hi) const;
    /// An array of exactly 3 numbers, each checked like number(r) at its own pointer.
    glm::vec3 vec3(const Range& r = Range::any()) const;
    /// A string that is one of the choices.
    std::string choice(std::initializer_list<std::string_view> choices) const;

    /// The value's member or element pointer.
    std::string child(std::string_view key) const { return pointer_ + "/" + escapePointerToken(key); }
    std::string child(std::size_t index) const { return pointer_ + "/" + std::to_string(index); }

private:
    [[noreturn]] void failType(std::string_view expected) const;

    const Json* json_;
    std::string pointer_;
    const std::string* file_;
};

/// A JSON object being read: every key asked for is remembered, finish() refuses any other.
class Object {
public:
    explicit Object(Value v) : v_(std::move(v)) {}

    const Value& value() const { return v_; }
    [[noreturn]] void fail(std::string_view message) const { v_.fail(message); }

    bool has(std::string_view key);                 ///< present (and now a known key)
    Value required(std::string_view key);           ///< must be present
    std::optional<Value> optional(std::string_view key);

    float number(std::string_view key, const Range& r) { return required(key).number(r); }
    float number(std::string_view key, const Range& r, float def);
    std::uint32_t uint32(std::string_view key, std::uint32_t lo, std::uint32_t hi);
    std::uint32_t uint32(std::string_view key, std::uint32_t lo, std::uint32_t hi, std::uint32_t def);
    glm::vec3 vec3(std::string_view key, const Range& r = Range::any()) { return required(key).vec3(r); }
    glm::vec3 vec3(std::string_view key, const Range& r, glm::vec3 def);
    glm::dvec3 dvec3(std::string_view key, const Range& r = Range::any()) { return required(key).dvec3(r); }
    bool boolean(std::string_view key, bool def);
    std::string string(std::string_view key) { return required(key).string(); }
    std::string choice(std::string_view key, std::initializer_list<std::string_view> choices) {
        return required(key).choice(choices);
    }
    std::string choice(std::string_view key, std::initializer_list<std::string_view> choices,
                       std::string_view def);

    /// Every member in file order, as (key, value); every key is then known (for an object whose
    /// keys the file chooses, such as "materials"). Linear in the number of members.
    std::vector<std::pair<std::string, Value>> members();

    /// Refuse the first key (in file order) that was never asked for.
    void finish() const;

private:
    Value v_;
    std::vector<std::string> known_;  // in the order they were asked for (for messages)
    bool allKnown_ = false;           // members() was called
};

}  // namespace vkp::json
