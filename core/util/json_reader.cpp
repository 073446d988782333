#include "core/util/json_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/util/atomic_file.h"

namespace rrf {

using nlohmann::json;

JsonReader::JsonReader(const json& value, std::string file, std::string pointer)
    : value_(&value), file_(std::move(file)), pointer_(std::move(pointer)) {}

void JsonReader::fail(const std::string& what) const { throw InputError(file_, pointer_, what); }

void JsonReader::expected(const std::string& what) const {
    fail("expected " + what + ", got " + describe(*value_));
}

std::string JsonReader::describe(const json& v) {
    switch (v.type()) {
        case json::value_t::null: return "null";
        case json::value_t::boolean: return "boolean";
        case json::value_t::string: return "string";
        case json::value_t::number_integer:
        case json::value_t::number_unsigned:
        case json::value_t::number_float: return "number";
        case json::value_t::object: return "object";
        case json::value_t::array:
            return "array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
        default: return "binary data";
    }
}

std::string JsonReader::child(const std::string& base, const std::string& key) {
    std::string escaped;
    for (char c : key) {
        if (c == '~') escaped += "~0";
        else if (c == '/') escaped += "~1";
        else escaped += c;
    }
    return base + "/" + escaped;
}

std::string JsonReader::child(const std::string& base, size_t index) {
    return base + "/" + std::to_string(index);
}

void JsonReader::requireObject() const {
    if (!value_->is_object()) expected("object");
}

size_t JsonReader::requireArray() const {
    if (!value_->is_array()) expected("array");
    return value_->size();
}

bool JsonReader::has(const std::string& key) const {
    return value_->is_object() && value_->contains(key);
}

JsonReader JsonReader::at(const std::string& key) const {
    requireObject();
    const auto it = value_->find(key);
    if (it == value_->end()) fail("missing required field '" + key + "'");
    return JsonReader(*it, file_, child(pointer_, key));
}

std::optional<JsonReader> JsonReader::find(const std::string& key) const {
    requireObject();
    const auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return JsonReader(*it, file_, child(pointer_, key));
}

JsonReader JsonReader::at(size_t index) const {
    const size_t n = requireArray();
    if (index >= n) fail("index " + std::to_string(index) + " out of range (size " + std::to_string(n) + ")");
    return JsonReader((*value_)[index], file_, child(pointer_, index));
}

void JsonReader::checkKeys(std::initializer_list<const char*> allowed) const {
    checkKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void JsonReader::checkKeys(const std::vector<std::string>& allowed) const {
    requireObject();
    for (auto it = value_->begin(); it != value_->end(); ++it) {
        bool known = false;
        for (const std::string& a : allowed) known = known || it.key() == a;
        if (known) continue;
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw InputError(file_, child(pointer_, it.key()),
                         "unknown key '" + it.key() + "' (allowed here: " + list + ")");
    }
}

double JsonReader::number() const {
    if (!value_->is_number()) expected("number");
    const double v = value_->get<double>();
    // The parser turns out-of-range literals such as 1e999 into infinities.
    if (!std::isfinite(v)) fail("expected a finite number");
    return v;
}

double JsonReader::number(double lo, double hi, bool excludeLo) const {
    const double v = number();
    if (v < lo || v > hi || (excludeLo && v == lo))
        fail("value " + formatNumber(v) + " out of range " + (excludeLo ? "(" : "[") + formatNumber(lo) + ", " +
             formatNumber(hi) + "]");
    return v;
}

float JsonReader::floatValue() const {
    const double v = number();
    if (std::fabs(v) > double(std::numeric_limits<float>::max()))
        fail("number " + formatNumber(v) + " is too large for single precision");
    return float(v);
}

int64_t JsonReader::integer(int64_t lo, int64_t hi) const {
    if (!value_->is_number()) expected("integer");
    if (value_->is_number_float()) {
        const double d = value_->get<double>();
        if (!std::isfinite(d) || d != std::floor(d)) expected("integer");
        // Convert only values inside int64's range (2^63 itself is not): a cast of 1e300 is undefined.
        constexpr double kTwo63 = 9223372036854775808.0;
        if (d >= -kTwo63 && d < kTwo63 && int64_t(d) >= lo && int64_t(d) <= hi) return int64_t(d);
    } else if (value_->is_number_unsigned()) {
        const uint64_t u = value_->get<uint64_t>();
        if (u <= uint64_t(std::numeric_limits<int64_t>::max()) && int64_t(u) >= lo && int64_t(u) <= hi)
            return int64_t(u);
    } else {
        const int64_t i = value_->get<int64_t>();
        if (i >= lo && i <= hi) return i;
    }
    fail("integer " + value_->dump() + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

uint64_t JsonReader::unsignedInteger() const {
    if (value_->is_number_unsigned()) return value_->get<uint64_t>();
    if (value_->is_number_integer() && value_->get<int64_t>() >= 0) return uint64_t(value_->get<int64_t>());
    expected("non-negative integer");
}

bool JsonReader::boolean() const {
    if (!value_->is_boolean()) expected("true or false");
    return value_->get<bool>();
}

std::string JsonReader::string() const {
    if (!value_->is_string()) expected("string");
    return value_->get<std::string>();
}

Vec3 JsonReader::vec3() const {
    if (!value_->is_array() || value_->size() != 3) expected("array of 3 numbers");
    Vec3 v;
    for (size_t i = 0; i < 3; ++i) v[int(i)] = at(i).floatValue();
    return v;
}

float JsonReader::floatOr(const std::string& key, float fallback) const {
    const auto r = find(key);
    return r ? r->floatValue() : fallback;
}

double JsonReader::numberOr(const std::string& key, double fallback, double lo, double hi, bool excludeLo) const {
    const auto r = find(key);
    return r ? r->number(lo, hi, excludeLo) : fallback;
}

int64_t JsonReader::integerOr(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) const {
    const auto r = find(key);
    return r ? r->integer(lo, hi) : fallback;
}

bool JsonReader::booleanOr(const std::string& key, bool fallback) const {
    const auto r = find(key);
    return r ? r->boolean() : fallback;
}

std::string JsonReader::stringOr(const std::string& key, const std::string& fallback) const {
    const auto r = find(key);
    return r ? r->string() : fallback;
}

Vec3 JsonReader::vec3Or(const std::string& key, const Vec3& fallback) const {
    const auto r = find(key);
    return r ? r->vec3() : fallback;
}

uint64_t JsonReader::unsignedOr(const std::string& key, uint64_t fallback) const {
    const auto r = find(key);
    return r ? r->unsignedInteger() : fallback;
}

std::string JsonReader::choiceOr(const std::string& key, const std::string& fallback,
                                 std::initializer_list<const char*> allowed) const {
    return choiceOr(key, fallback, std::vector<std::string>(allowed.begin(), allowed.end()));
}

std::string JsonReader::choiceOr(const std::string& key, const std::string& fallback,
                                 const std::vector<std::string>& allowed) const {
    const auto r = find(key);
    if (!r) return fallback;
    const std::string s = r->string();
    std::string list;
    for (const std::string& a : allowed) {
        if (s == a) return s;
        list += (list.empty() ? "\"" : ", \"") + a + "\"";
    }
    r->fail("expected one of " + list + ", got \"" + s + "\"");
}

namespace {
/// "line 3, column 5 (byte 41)" of the 1-based byte offset `byte` in `text`, for editors.
std::string positionOf(const std::string& text, size_t byte) {
    byte = std::min(byte, text.size() + 1);
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
        if (text[i] == '\n') { ++line; column = 1; }
        else ++column;
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column) + " (byte " + std::to_string(byte) + ")";
}

/// 1-based byte offset of the first number literal `token` in `text` (0 if none): the parser names
/// the literal that overflowed, not where it is.
size_t findNumberLiteral(const std::string& text, const std::string& token) {
    auto numberChar = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; };
    for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
        const size_t end = at + token.size();
        if ((at == 0 || !numberChar(text[at - 1])) && (end == text.size() || !numberChar(text[end]))) return at + 1;
    }
    return 0;
}
}  // namespace

json parseJsonText(const std::string& text, const std::string& file) {
    try {
        return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const json::parse_error& e) {
        std::string detail = e.what();
        // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 3, column 5: " prefix.
        const size_t colon = detail.find(": ");
        if (colon != std::string::npos) detail = detail.substr(colon + 2);
        throw InputError(file, "", "malformed JSON at " + positionOf(text, e.byte) + ": " + detail);
    } catch (const json::exception& e) {
        // The one other error of the parser: a number literal beyond double's range (out_of_range.406,
        // "number overflow parsing '1e400'"), which has no position of its own.
        const std::string what = e.what();
        const size_t open = what.find('\''), close = what.rfind('\'');
        const std::string token = open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
        const size_t byte = token.empty() ? 0 : findNumberLiteral(text, token);
        throw InputError(file, "",
                         "number " + (token.empty() ? std::string("literal") : token) + (byte ? " at " + positionOf(text, byte) : "") +
                             " is out of range: numbers must lie within ±1.8e308 (double precision)");
    }
}

json readJsonFile(const std::string& path) {
    std::string text;
    try {
        text = readFile(path);
    } catch (const std::runtime_error& e) {
        throw InputError(path, "", std::string("cannot read file (") + e.what() + ")");
    }
    return parseJsonText(text, path);
}

JsonText jsonText(const nlohmann::json& value) {
    if (value.is_null() || (value.is_object() && value.empty())) return {};
    return {value.dump()};
}

nlohmann::json parseJsonText(const JsonText& text) {
    if (text.empty()) return nlohmann::json::object();
    // Written by jsonText(), so it parses; a failure here is a bug, not the user's input.
    return nlohmann::json::parse(text.text);
}

}  // namespace rrf
