#pragma once
/// What the libFuzzer targets in tests/fuzz share: a private scratch directory for inputs that the
/// parsers read from a file, and the rule for what counts as a finding.
///
/// A parser given hostile bytes may only reject them with an InputError (docs/design.md §22): a
/// crash, an abort, a sanitizer report, a hang or any other exception (raw library text such as
/// nlohmann's or std::stoull's, std::bad_alloc, ...) is a finding. `expectOnlyInputErrors` turns
/// the last case into an abort with the exception's type and text, so libFuzzer saves the input.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "core/util/error.h"

namespace rrf::fuzz {

/// A directory of its own for this process (created on first use, under $TMPDIR or /tmp), so
/// targets running side by side never read each other's files.
inline const std::string& scratchDir() {
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/rrf-fuzz-XXXXXX";
        if (!mkdtemp(pattern.data())) {
            std::perror("rrf fuzz: mkdtemp");
            std::abort();
        }
        return pattern;
    }();
    return dir;
}

/// Writes `size` bytes to `<scratchDir>/<name>` (replacing it) and returns the path.
inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
    const std::string path = scratchDir() + "/" + name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::perror(("rrf fuzz: writing " + path).c_str());
        std::abort();
    }
    return path;
}

/// Copies `relativePath` of the source tree (RRF_SOURCE_DIR) into scratchDir() as `name`, so that
/// inputs can refer to it by a relative path (an OBJ file, a project's scene file).
inline void provideSourceFile(const std::string& relativePath, const std::string& name) {
    const std::string from = std::string(RRF_SOURCE_DIR) + "/" + relativePath;
    std::FILE* f = std::fopen(from.c_str(), "rb");
    if (!f) {
        std::perror(("rrf fuzz: reading " + from).c_str());
        std::abort();
    }
    std::string bytes;
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes.append(buf, n);
    std::fclose(f);
    writeInput(name, reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

/// Aborts, naming the exception, so that libFuzzer reports the input as a crash.
[[noreturn]] inline void finding(const char* type, const char* what) {
    std::fprintf(stderr, "rrf fuzz: FINDING: the parser threw %s: %s\n", type, what);
    std::abort();
}

/// Runs `parse`; an InputError is the expected way to refuse bad bytes, any other exception is a
/// finding. `alsoAccept(e)` may accept a parser's other documented error (the dataset reader's).
template <class Parse, class Accept>
void expectOnlyInputErrors(Parse&& parse, Accept&& alsoAccept) {
    try {
        parse();
    } catch (const InputError&) {
    } catch (const std::exception& e) {
        if (!alsoAccept(e)) finding(typeid(e).name(), e.what());
    } catch (...) {
        finding("a non-std exception", "");
    }
}

template <class Parse>
void expectOnlyInputErrors(Parse&& parse) {
    expectOnlyInputErrors(parse, [](const std::exception&) { return false; });
}

}  // namespace rrf::fuzz
