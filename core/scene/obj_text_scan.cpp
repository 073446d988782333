#include "core/scene/obj_text_scan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string_view>

#include "core/scene/radiometric_range.h"
#include "core/util/error.h"
#include "core/util/text_format.h"

namespace rrf {

namespace {

/// Calls fn(number, line) for each line of `in`, lines ending at "\n", "\r\n" or a lone "\r" as
/// tinyobjloader's reader splits them (so both count lines alike).
template <class Fn>
void forEachTextLine(std::istream& in, Fn&& fn) {
    std::string chunk;
    size_t number = 0;
    while (std::getline(in, chunk)) {
        if (!chunk.empty() && chunk.back() == '\r') chunk.pop_back();
        const std::string_view all(chunk);
        for (size_t start = 0;;) {
            const size_t cr = all.find('\r', start);
            fn(++number, all.substr(start, cr == std::string_view::npos ? std::string_view::npos : cr - start));
            if (cr == std::string_view::npos) break;
            start = cr + 1;
        }
    }
}

/// The words of `line` separated by spaces and tabs (tinyobjloader's separators).
std::vector<std::string_view> wordsOf(std::string_view line) {
    std::vector<std::string_view> words;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

/// `line` up to a `#` comment.
std::string_view withoutComment(std::string_view line) { return line.substr(0, line.find('#')); }

/// "" when `word` is a number representable as a finite float (stored in `out`); otherwise why not.
/// Strict where tinyobjloader is lenient: the whole word must be the number ("1.5x" is not one),
/// and "nan", "inf" or 1e400 are refused instead of read as 0 or infinity.
std::string finiteFloatProblem(std::string_view word, float& out) {
    std::string_view digits = word;
    if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    const std::string quoted = "'" + std::string(word) + "'";
    if (ec == std::errc::result_out_of_range)
        return quoted + " is beyond single precision (|value| <= " + formatNumber(std::numeric_limits<float>::max()) + ")";
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) return quoted + " is not a number";
    if (!std::isfinite(v)) return quoted + " is not a finite number";
    if (std::fabs(v) > double(std::numeric_limits<float>::max()))
        return quoted + " is beyond single precision (|value| <= " + formatNumber(std::numeric_limits<float>::max()) + ")";
    out = float(v);
    return "";
}

std::string lineOf(const char* kind, const std::string& path, size_t line) {
    return std::string(kind) + " file '" + path + "' line " + std::to_string(line);
}

/// Checks the numbers of a `v` or `vn` line (the words after the key); throws naming the field.
void checkVertexNumbers(const std::vector<std::string_view>& words, const std::string& key, const std::string& path,
                        size_t line, const ObjScanContext& ctx) {
    static const char* const kAxis[3] = {"x", "y", "z"};
    const char* const part = key == "v" ? " coordinate" : " component";
    if (words.size() < 4)
        throw InputError(ctx.sceneFile, ctx.where,
                         lineOf("OBJ", path, line) + ": " + key + " has " + std::to_string(words.size() - 1) +
                             " number" + (words.size() == 2 ? "" : "s") + ", expected x y z" +
                             (key == "v" ? " (a missing coordinate would be read as 0)" : ""));
    for (size_t i = 1; i < words.size(); ++i) {
        float v = 0;
        const std::string why = finiteFloatProblem(words[i], v);
        if (why.empty()) continue;
        const std::string field = i <= 3 ? std::string(kAxis[i - 1]) + part : "value " + std::to_string(i);
        throw InputError(ctx.sceneFile, ctx.where, lineOf("OBJ", path, line) + ": " + key + " " + field + " " + why);
    }
}

/// tinyobjloader's split of an `mtllib` line: spaces separate names, a backslash escapes the next
/// character (so "my\ lib.mtl" is one name).
std::vector<std::string> libraryNames(std::string_view rest) {
    std::vector<std::string> names;
    std::string name;
    bool escaping = false;
    for (const char c : rest) {
        if (escaping) {
            escaping = false;
        } else if (c == '\\') {
            escaping = true;
            continue;
        } else if (c == ' ') {
            if (!name.empty()) names.push_back(name);
            name.clear();
            continue;
        }
        name += c;
    }
    if (!name.empty()) names.push_back(name);
    return names;
}

std::string trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return std::string(s);
}

}  // namespace

ObjTextScan scanObjText(const std::string& path, const ObjScanContext& ctx) {
    ObjTextScan scan;
    std::ifstream in(path);
    long long positions = 0, normals = 0;
    forEachTextLine(in, [&](size_t number, std::string_view line) {
        const std::vector<std::string_view> words = wordsOf(withoutComment(line));
        if (words.empty()) return;
        const std::string key(words[0]);
        if (key == "v" || key == "vn") {
            checkVertexNumbers(words, key, path, number, ctx);
            ++(key == "v" ? positions : normals);
        } else if (key == "mtllib" || key == "usemtl") {
            // Names may hold '#': the statement's rest as written, not cut at a comment.
            const size_t at = line.find(key);
            const std::string_view rest = line.substr(at + key.size());
            if (key == "mtllib") scan.mtllibs.push_back({number, libraryNames(trimmed(rest))});
            else scan.usemtls.push_back({number, trimmed(rest)});
        } else if (key == "f") {
            if (words.size() < 4) {
                if (scan.degenerateFaces++ == 0) scan.firstDegenerateLine = number;
                return;
            }
            for (size_t k = 1; k < words.size(); ++k) {
                // Corner forms: v, v/t, v//n, v/t/n.
                const std::string corner(words[k]);
                const size_t s1 = corner.find('/');
                const size_t s2 = s1 == std::string::npos ? s1 : corner.find('/', s1 + 1);
                auto check = [&](const std::string& text, long long count, const char* what, const char* plural) {
                    if (text.empty()) return;
                    const long long i = std::atoll(text.c_str());
                    if (i != 0 && i <= count && -i <= count) return;
                    throw InputError(ctx.sceneFile, ctx.where,
                                     lineOf("OBJ", path, number) + ": " + what + " index " + text + " is out of range: " +
                                         std::to_string(count) + " " + (count == 1 ? what : plural) + " defined so far");
                };
                check(corner.substr(0, s1), positions, "vertex", "vertices");
                if (s2 != std::string::npos) check(corner.substr(s2 + 1), normals, "normal", "normals");
            }
        }
    });
    return scan;
}

void scanMtlText(const std::string& path, const ObjScanContext& ctx) {
    std::ifstream in(path);
    std::string material;
    forEachTextLine(in, [&](size_t number, std::string_view line) {
        const std::vector<std::string_view> words = wordsOf(line);
        if (words.empty() || words[0][0] == '#') return;
        const std::string key(words[0]);
        if (key == "newmtl") {
            material = trimmed(line.substr(line.find(key) + key.size()));
            return;
        }
        if (key != "Kd" && key != "Ks" && key != "Ke" && key != "Ns") return;
        const std::string at = lineOf("MTL", path, number) + ": material '" + material + "': " + key;
        auto refuse = [&](const std::string& why) { throw InputError(ctx.sceneFile, ctx.where, at + " " + why); };
        const std::vector<std::string_view> values = wordsOf(withoutComment(line));
        const size_t wanted = key == "Ns" ? 1 : 3, given = values.size() - 1;
        float v[3] = {0, 0, 0};
        // Words first, so that "Kd spectral file.rfl" is refused for what it is, not for its count.
        for (size_t i = 0; i < std::min(wanted, given); ++i)
            if (const std::string why = finiteFloatProblem(values[i + 1], v[i]); !why.empty())
                refuse(why + (values[i + 1] == "spectral" || values[i + 1] == "xyz" ? " (spectral and xyz colours are not supported)" : ""));
        if (given < wanted)
            refuse("has " + std::to_string(given) + " number" + (given == 1 ? "" : "s") + ", expected " +
                   (wanted == 1 ? "1" : "3 (r g b; a missing component would be read as 0)"));
        if (key == "Ns") {
            if (const std::string why = exponentProblem(v[0], "Ns"); !why.empty())
                throw InputError(ctx.sceneFile, ctx.where, lineOf("MTL", path, number) + ": material '" + material + "': " + why);
            return;
        }
        static const char* const kMtlChannel[3] = {"red", "green", "blue"};
        for (int i = 0; i < 3; ++i)
            if (v[i] < 0) refuse(std::string("must be >= 0, but its ") + kMtlChannel[i] + " component is " + formatNumber(v[i]));
        if (key == "Ke")
            if (const std::string why = emissionProblem(Vec3(v[0], v[1], v[2]), "Ke"); !why.empty())
                throw InputError(ctx.sceneFile, ctx.where, lineOf("MTL", path, number) + ": material '" + material + "': " + why);
    });
}

}  // namespace rrf
