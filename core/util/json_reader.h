#pragma once
/// Typed, validating access to a parsed JSON document. Every reader knows the file it came from
/// and its JSON pointer (RFC 6901, e.g. `/shapes/2/material`), so every complaint becomes an
/// InputError that tells the user exactly where to look and what was expected.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "core/util/json_text.h"
#include "core/util/text_format.h"
#include "core/util/vec3.h"

namespace rrf {

class JsonReader {
public:
    /// Wraps `value`, which sits at JSON pointer `pointer` ("" for the root) inside `file`.
    /// The referenced JSON must outlive the reader.
    JsonReader(const nlohmann::json& value, std::string file, std::string pointer = "");

    const nlohmann::json& value() const { return *value_; }
    const std::string& file() const { return file_; }
    const std::string& pointer() const { return pointer_; }

    /// Throws InputError(file, pointer, what).
    [[noreturn]] void fail(const std::string& what) const;

    // ---- structure ---------------------------------------------------------------------------
    bool isObject() const { return value_->is_object(); }
    bool isArray() const { return value_->is_array(); }
    /// Throws unless the value is an object ("expected object, got array").
    void requireObject() const;
    /// Throws unless the value is an array; returns its size.
    size_t requireArray() const;
    /// True if the value is an object with member `key`.
    bool has(const std::string& key) const;
    /// Required member: throws "missing required field 'key'" (at this reader's pointer).
    JsonReader at(const std::string& key) const;
    /// Optional member: nullopt if absent.
    std::optional<JsonReader> find(const std::string& key) const;
    /// Array element (the value must be an array; index is bounds-checked).
    JsonReader at(size_t index) const;
    /// Rejects members not in `allowed`, naming the offending key and listing the allowed ones
    /// (catches typos such as "albdo"). The value must be an object.
    void checkKeys(std::initializer_list<const char*> allowed) const;
    /// checkKeys with a list known only at run time (e.g. a script step's keys).
    void checkKeys(const std::vector<std::string>& allowed) const;

    // ---- scalars -------------------------------------------------------------------------------
    /// Finite number (integers accepted).
    double number() const;
    /// Finite number in [lo, hi], or in (lo, hi] when `excludeLo` ("value 0 out of range (0, 1]").
    double number(double lo, double hi, bool excludeLo = false) const;
    /// Finite number that is also finite as a float.
    float floatValue() const;
    /// Integer (a float with an integral value such as 256.0 is accepted) in [lo, hi].
    int64_t integer(int64_t lo, int64_t hi) const;
    /// Non-negative integer up to 2^64-1 (seeds).
    uint64_t unsignedInteger() const;
    bool boolean() const;
    std::string string() const;
    /// Array of exactly 3 finite numbers ("expected array of 3 numbers, got string").
    Vec3 vec3() const;

    // ---- members with defaults -----------------------------------------------------------------
    float floatOr(const std::string& key, float fallback) const;
    double numberOr(const std::string& key, double fallback, double lo, double hi, bool excludeLo = false) const;
    int64_t integerOr(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) const;
    bool booleanOr(const std::string& key, bool fallback) const;
    std::string stringOr(const std::string& key, const std::string& fallback) const;
    Vec3 vec3Or(const std::string& key, const Vec3& fallback) const;
    uint64_t unsignedOr(const std::string& key, uint64_t fallback) const;
    /// A string member that must be one of `allowed` ("expected one of \"nee\", \"naive\", got \"bidir\"").
    std::string choiceOr(const std::string& key, const std::string& fallback,
                         std::initializer_list<const char*> allowed) const;
    /// choiceOr with names known only at run time (a registry's names, e.g. nn/trainers/registry.h).
    std::string choiceOr(const std::string& key, const std::string& fallback,
                         const std::vector<std::string>& allowed) const;

    /// JSON pointer of `key` below `base` (escapes '~' and '/').
    static std::string child(const std::string& base, const std::string& key);
    static std::string child(const std::string& base, size_t index);
    /// "string", "number", "array of 2 elements", ... for messages.
    static std::string describe(const nlohmann::json& value);

private:
    [[noreturn]] void expected(const std::string& what) const;

    const nlohmann::json* value_;
    std::string file_;
    std::string pointer_;
};

/// Parses JSON text (comments allowed). Malformed input throws InputError naming `file` and the
/// line, column and byte offset where the parser gave up.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);

/// `value` as JsonText (compact; an empty object or null gives an empty JsonText).
JsonText jsonText(const nlohmann::json& value);
/// The value a JsonText holds; an empty one gives an empty object.
nlohmann::json parseJsonText(const JsonText& text);

/// Reads and parses a JSON file; an unreadable file throws InputError naming it.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace rrf
