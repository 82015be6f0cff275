#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/errors.h"

namespace vkp::json {

namespace {

/// Shortest "%g"-style text of a double that reads back to the same number ("0.65", "-1", "1e+30").
std::string formatNumber(double x) {
    char buf[40];
    for (int precision = 6; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, x);
        if (std::strtod(buf, nullptr) == x) break;
    }
    return buf;
}

/// Levenshtein distance, for "did you mean" hints on misspelt keys.
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
            diag = up;
        }
    }
    return row[b.size()];
}

std::string joinKeys(const std::vector<std::string>& keys) {
    std::string out;
    for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
    return out;
}

}  // namespace

std::string escapePointerToken(std::string_view token) {
    std::string out;
    for (char c : token) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

std::string describeValue(const Json& value) {
    constexpr std::size_t kMax = 40;
    std::string text;
    if (value.is_number_float()) {
        text = formatNumber(value.get<double>());
    } else {
        text = value.dump(-1, ' ', true, Json::error_handler_t::replace);
    }
    if (text.size() > kMax) text = text.substr(0, kMax - 3) + "...";
    if (value.is_string()) return "string " + text;
    if (value.is_array()) return "array " + text;
    if (value.is_object()) return "object " + text;
    return text;
}

std::string formatError(const std::string& file, std::string_view where, std::string_view message) {
    std::string line = file + ": " + (where.empty() ? std::string("(document)") : std::string(where)) +
                       ": " + std::string(message);
    // One line of printable text, whatever the document or a library put into the message.
    for (char& c : line) {
        auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) c = ' ';
    }
    return line;
}

bool Range::contains(double x) const {
    bool okLo = loOpen ? x > lo : x >= lo;
    bool okHi = hiOpen ? x < hi : x <= hi;
    return okLo && okHi;
}

std::string Range::requirement() const {
    const bool hasLo = std::isfinite(lo), hasHi = std::isfinite(hi);
    if (hasLo && hasHi) {
        return "must be in " + std::string(loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
               (hiOpen ? ")" : "]");
    }
    if (hasLo) return std::string(loOpen ? "must be > " : "must be >= ") + formatNumber(lo);
    if (hasHi) return std::string(hiOpen ? "must be < " : "must be <= ") + formatNumber(hi);
    return {};
}

// ---- Value ------------------------------------------------------------------------------------

void Value::fail(std::string_view message) const { throw InputError(formatError(*file_, pointer_, message)); }

void Value::failType(std::string_view expected) const {
    fail("must be " + std::string(expected) + " (got " + describeValue(*json_) + ")");
}

Object Value::object() const {
    if (!json_->is_object()) failType("an object");
    return Object(*this);
}

std::vector<Value> Value::array() const {
    if (!json_->is_array()) failType("an array");
    std::vector<Value> out;
    out.reserve(json_->size());
    for (std::size_t i = 0; i < json_->size(); ++i) out.push_back(element(i));
    return out;
}

std::string Value::string() const {
    if (!json_->is_string()) failType("a string");
    return json_->get<std::string>();
}

bool Value::boolean() const {
    if (!json_->is_boolean()) failType("true or false");
    return json_->get<bool>();
}

float Value::number(const Range& r) const {
    if (!json_->is_number()) failType("a number");
    const double x = json_->get<double>();
    const float f = static_cast<float>(x);
    if (!std::isfinite(f)) fail("must be a finite 32-bit float (got " + describeValue(*json_) + ")");
    if (!r.contains(x)) fail(r.requirement() + " (got " + describeValue(*json_) + ")");
    return f;
}

double Value::real(const Range& r) const {
    if (!json_->is_number()) failType("a number");
    const double x = json_->get<double>();
    if (!std::isfinite(x)) fail("must be finite (got " + describeValue(*json_) + ")");
    if (!r.contains(x)) fail(r.requirement() + " (got " + describeValue(*json_) + ")");
    return x;
}

glm::dvec3 Value::dvec3(const Range& r) const {
    if (!json_->is_array() || json_->size() != 3) failType("an array of 3 numbers");
    glm::dvec3 out;
    for (std::size_t i = 0; i < 3; ++i) out[static_cast<int>(i)] = element(i).real(r);
    return out;
}

std::uint64_t Value::integer(std::uint64_t lo, std::uint64_t hi) const {
    const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!json_->is_number()) failType(range);
    double x = json_->get<double>();
    if (json_->is_number_float() && std::trunc(x) != x) failType(range);  // also NaN/inf
    if (json_->is_number_integer() && !json_->is_number_unsigned()) {
        if (json_->get<std::int64_t>() < 0 && lo == 0) failType(range);
    }
    if (x < static_cast<double>(lo) || x > static_cast<double>(hi)) failType(range);
    std::uint64_t v = json_->is_number_unsigned() ? json_->get<std::uint64_t>() : static_cast<std::uint64_t>(x);
    if (v < lo || v > hi) failType(range);  // exact check where the double comparison rounded
    return v;
}

glm::vec3 Value::vec3(const Range& r) const {
    if (!json_->is_array() || json_->size() != 3) failType("an array of 3 numbers");
    glm::vec3 out;
    for (std::size_t i = 0; i < 3; ++i) out[static_cast<int>(i)] = element(i).number(r);
    return out;
}

std::string Value::choice(std::initializer_list<std::string_view> choices) const {
    std::string list;
    for (auto c : choices) list += (list.empty() ? "\"" : ", \"") + std::string(c) + "\"";
    if (!json_->is_string()) failType("one of " + list);
    std::string s = json_->get<std::string>();
    for (auto c : choices) {
        if (s == c) return s;
    }
    failType("one of " + list);
}

// ---- Object -----------------------------------------------------------------------------------

bool Object::has(std::string_view key) {
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
    return v_.json().contains(key);
}

std::optional<Value> Object::optional(std::string_view key) {
    if (!has(key)) return std::nullopt;
    return Value(v_.json().at(std::string(key)), v_.child(key), v_.file());
}

Value Object::required(std::string_view key) {
    if (auto v = optional(key)) return *v;
    // A misspelt key would otherwise be reported only as this missing one: name it. Only a close
    // match (at most 2 edits, fewer than half the key) so that "u" is not offered for "Q".
    std::string hint;
    for (const auto& [k, unused] : v_.json().items()) {
        (void)unused;
        const std::size_t d = editDistance(k, key);
        if (std::find(known_.begin(), known_.end(), k) == known_.end() && d <= 2 && 2 * d < key.size()) {
            hint = " (is \"" + k + "\" a misspelling?)";
            break;
        }
    }
    throw InputError(formatError(v_.file(), v_.child(key), "missing required key" + hint));
}

float Object::number(std::string_view key, const Range& r, float def) {
    auto v = optional(key);
    return v ? v->number(r) : def;
}

std::uint32_t Object::uint32(std::string_view key, std::uint32_t lo, std::uint32_t hi) {
    return static_cast<std::uint32_t>(required(key).integer(lo, hi));
}

std::uint32_t Object::uint32(std::string_view key, std::uint32_t lo, std::uint32_t hi, std::uint32_t def) {
    auto v = optional(key);
    return v ? static_cast<std::uint32_t>(v->integer(lo, hi)) : def;
}

glm::vec3 Object::vec3(std::string_view key, const Range& r, glm::vec3 def) {
    auto v = optional(key);
    return v ? v->vec3(r) : def;
}

bool Object::boolean(std::string_view key, bool def) {
    auto v = optional(key);
    return v ? v->boolean() : def;
}

std::string Object::choice(std::string_view key, std::initializer_list<std::string_view> choices,
                           std::string_view def) {
    auto v = optional(key);
    return v ? v->choice(choices) : std::string(def);
}

std::vector<std::pair<std::string, Value>> Object::members() {
    allKnown_ = true;
    std::vector<std::pair<std::string, Value>> out;
    out.reserve(v_.json().size());
    for (const auto& [k, member] : v_.json().items()) out.emplace_back(k, Value(member, v_.child(k), v_.file()));
    return out;
}

void Object::finish() const {
    if (allKnown_) return;
    for (const auto& [k, unused] : v_.json().items()) {
        (void)unused;
        if (std::find(known_.begin(), known_.end(), k) == known_.end()) {
            // A misspelling of an optional key (as required() names one of a required key).
            std::string hint;
            for (const std::string& known : known_) {
                const std::size_t d = editDistance(k, known);
                if (d <= 2 && 2 * d < known.size()) {
                    hint = "; is it a misspelling of \"" + known + "\"?";
                    break;
                }
            }
            throw InputError(
                formatError(v_.file(), v_.child(k), "unknown key (allowed here: " + joinKeys(known_) + ")" + hint));
        }
    }
}

}  // namespace vkp::json
