#pragma once
/// Errors reported to users. Every message names the file, the place in it (a JSON path such as
/// `/shapes/3/albedo`) and what was expected, so a user can fix the input without reading code.

#include <stdexcept>
#include <string>

namespace rrf {

class InputError : public std::runtime_error {
public:
    InputError(const std::string& file, const std::string& where, const std::string& what)
        : std::runtime_error(format(file, where, what)), file_(file), where_(where), what_(what) {}

    const std::string& file() const { return file_; }
    const std::string& where() const { return where_; }
    const std::string& detail() const { return what_; }

private:
    static std::string format(const std::string& file, const std::string& where, const std::string& what) {
        std::string s = file.empty() ? std::string("<input>") : file;
        if (!where.empty()) s += ": " + where;
        return s + ": " + what;
    }
    std::string file_, where_, what_;
};

/// A bad value of a setting that a front end gave rather than a file (a command-line flag, a sweep
/// value, a GUI field). Core names the setting as it knows it ("shard", "sweep values"), never a
/// front end's spelling of it; each front end maps the name to its own (the CLI to its flag) when it
/// reports the error.
class SettingError : public InputError {
public:
    SettingError(const std::string& setting, const std::string& what) : InputError("settings", setting, what) {}

    const std::string& setting() const { return where(); }
};

/// An output that could not be written (a full disk, a file size limit, no permission): names the
/// output the user asked for — never the temporary file or directory the write went through
/// (core/util/atomic_file.h, directory_replace.h) — what failed, and what is there now
/// ("<path>: write failed: No space left on device; the previous file is kept").
class OutputError : public std::runtime_error {
public:
    OutputError(const std::string& path, const std::string& problem, const std::string& kept)
        : std::runtime_error(path + ": " + problem + (kept.empty() ? "" : "; " + kept)), path_(path), problem_(problem),
          kept_(kept) {}

    const std::string& path() const { return path_; }
    const std::string& problem() const { return problem_; }
    const std::string& kept() const { return kept_; }

private:
    std::string path_, problem_, kept_;
};

}  // namespace rrf
