// parseDocument (json_reader.h): text to a document in one pass, linear in the text's size, keeping
// the JSON pointer of the value being read for the messages that need it (a duplicate key, a number
// out of double range, nesting too deep).
//
// nlohmann's parser with a callback (which an earlier version used to follow the pointer) scans the
// enclosing container after every object or array it ends, and an ordered_json object finds each
// new key by a linear search: both quadratic (300k spheres took 20 s, 200k materials 177 s). This
// SAX handler builds the same document, appending members without a search and finding duplicate
// keys through a hash set. docs/performance.md "Loading a JSON scene" has the measurements.
#include <algorithm>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/errors.h"
#include "scene/json_reader.h"

namespace vkp::json {

namespace {

/// Nesting deeper than any scene needs is refused while parsing: later recursive code (dump() in
/// messages, the destructor) could otherwise overflow the stack on a document like [[[[...]]]].
constexpr std::size_t kMaxNesting = 256;
/// Objects with more members than this find duplicate keys through a hash set, smaller ones by a
/// scan of their members (no allocation for the many small objects of a scene).
constexpr std::size_t kHashedKeys = 16;

/// Builds the document from nlohmann's SAX events (as its own DOM parser does) and knows the JSON
/// pointer of the value being read. Stops at the first problem, recorded in error / errorAt.
class DocumentBuilder : public nlohmann::json_sax<Json> {
public:
    explicit DocumentBuilder(Json& root) : root_(root) {}

    bool null() override { return put(Json(nullptr)) != nullptr; }
    bool boolean(bool b) override { return put(Json(b)) != nullptr; }
    bool number_integer(number_integer_t x) override { return put(Json(x)) != nullptr; }
    bool number_unsigned(number_unsigned_t x) override { return put(Json(x)) != nullptr; }
    bool number_float(number_float_t x, const string_t&) override { return put(Json(x)) != nullptr; }
    bool string(string_t& s) override { return put(Json(std::move(s))) != nullptr; }
    bool binary(binary_t& b) override { return put(Json::binary(std::move(b))) != nullptr; }

    bool start_object(std::size_t) override { return open(Json::object(), false); }
    bool start_array(std::size_t) override { return open(Json::array(), true); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        Frame& f = frames_.back();
        const auto& members = f.value->get_ref<const Json::object_t&>();
        bool seen = false;
        if (members.size() < kHashedKeys) {
            seen = std::any_of(members.begin(), members.end(), [&](const auto& m) { return m.first == k; });
        } else {
            if (f.keys.empty())
                for (const auto& m : members) f.keys.insert(m.first);
            seen = !f.keys.insert(k).second;
        }
        f.key = std::move(k);
        if (seen && duplicate.empty()) duplicate = pointer();
        return true;
    }

    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
        errorPosition = position;
        errorId = e.id;
        error = e.what();
        errorAt = pointer();
        return false;
    }

    /// The pointer of the value being read: in each enclosing container, the open member or
    /// element (an array's last one, its next one in the innermost array).
    std::string pointer() const {
        std::string p;
        for (std::size_t i = 0; i < frames_.size(); ++i) {
            const Frame& f = frames_[i];
            const bool innermost = i + 1 == frames_.size();
            p += '/';
            p += f.array ? std::to_string(f.value->size() - (innermost ? 0 : 1)) : escapePointerToken(f.key);
        }
        return p;
    }

    std::string duplicate;       ///< pointer of the first duplicate key, or empty
    std::string error;           ///< nlohmann's message of the error that stopped parsing
    int errorId = 0;             ///< its id (101: syntax, 406: number out of range), 0: too deep
    std::size_t errorPosition = 0;  ///< its byte offset (1-based: the last character read)
    std::string errorAt;         ///< the pointer where parsing stopped
    bool tooDeep = false;

private:
    struct Frame {
        Json* value;  ///< the open object or array (the last value of its parent: never moves while open)
        bool array;
        std::string key;                      ///< objects: the member being read
        std::unordered_set<std::string> keys;  ///< objects with kHashedKeys members or more: their keys
    };

    /// Append v where the parser is: the root, the next element, or the member of the last key.
    Json* put(Json&& v) {
        if (frames_.empty()) {
            root_ = std::move(v);
            return &root_;
        }
        Frame& f = frames_.back();
        if (f.array) {
            auto& a = f.value->get_ref<Json::array_t&>();
            a.push_back(std::move(v));
            return &a.back();
        }
        // The object's vector of members, appended without ordered_map's linear search for the key
        // (key() found any duplicate; the document is refused then).
        auto& members = static_cast<Json::object_t::Container&>(f.value->get_ref<Json::object_t&>());
        members.emplace_back(f.key, std::move(v));  // the key stays for pointer()
        return &members.back().second;
    }

    bool open(Json&& empty, bool array) {
        if (frames_.size() >= kMaxNesting) {
            tooDeep = true;
            errorAt = pointer();
            return false;
        }
        Json* v = put(std::move(empty));
        frames_.push_back(Frame{v, array, {}, {}});
        return true;
    }

    bool close() {
        frames_.pop_back();
        return true;
    }

    Json& root_;
    std::vector<Frame> frames_;
};

}  // namespace

Json parseDocument(const std::string& text, const std::string& file) {
    Json doc;
    DocumentBuilder builder(doc);
    const bool ok = Json::sax_parse(text, &builder, Json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/false);
    if (!ok && builder.tooDeep) {
        throw InputError(formatError(file, builder.errorAt, "nested deeper than " + std::to_string(kMaxNesting) + " levels"));
    }
    if (!ok && builder.errorId == 406) {
        // out_of_range.406: a number too large for a double. The parser stopped inside it.
        std::string what = builder.error;
        if (std::size_t b = what.find("] "); b != std::string::npos) what = what.substr(b + 2);
        throw InputError(formatError(file, builder.errorAt, what));
    }
    if (!ok) {
        // Line and column (1-based) of the last character read.
        const std::size_t pos = builder.errorPosition == 0 ? 0 : std::min<std::size_t>(builder.errorPosition - 1, text.size());
        const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
        std::size_t lineStart = text.rfind('\n', pos == 0 ? 0 : pos - 1);
        lineStart = (lineStart == std::string::npos || pos == 0) ? 0 : lineStart + 1;
        const std::size_t column = pos - lineStart + 1;
        std::string what = builder.error;
        const std::size_t col = what.find("column ");
        const std::size_t cut = col == std::string::npos ? std::string::npos : what.find(": ", col);
        if (cut != std::string::npos) what = what.substr(cut + 2);
        else if (std::size_t b = what.find("] "); b != std::string::npos) what = what.substr(b + 2);
        throw InputError(formatError(file, "line " + std::to_string(line) + ", column " + std::to_string(column),
                                     "invalid JSON: " + what));
    }
    if (!builder.duplicate.empty()) throw InputError(formatError(file, builder.duplicate, "duplicate key"));
    return doc;
}

}  // namespace vkp::json
