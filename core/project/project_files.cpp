#include "core/project/project_files.h"

#include <filesystem>
#include <system_error>

namespace rrf {

namespace fs = std::filesystem;

namespace {
fs::path normalDir(const std::string& dir) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
    if (ec) p = fs::absolute(dir).lexically_normal();
    return p;
}

/// True when `rel` (relative to the project directory) stays inside it.
bool insideProject(const fs::path& rel) {
    if (rel.empty() || rel.is_absolute()) return false;
    const fs::path n = rel.lexically_normal();
    return !n.empty() && *n.begin() != "..";
}

/// Links (or copies) one file; counts it or names the problem.
void carryFile(const fs::path& from, const fs::path& to, CarriedFiles& out) {
    std::error_code ec;
    if (fs::exists(to, ec)) return;
    fs::create_directories(to.parent_path(), ec);
    if (ec) {
        out.problems.push_back(to.parent_path().string() + ": " + ec.message());
        return;
    }
    fs::create_hard_link(from, to, ec);
    if (!ec) {
        ++out.linked;
        return;
    }
    ec.clear();
    fs::copy_file(from, to, fs::copy_options::skip_existing, ec);
    if (ec) out.problems.push_back(from.string() + " -> " + to.string() + ": " + ec.message());
    else ++out.copied;
}

/// Carries every regular file under oldDir/rel (a file or a directory) to newDir/rel.
void carryTree(const fs::path& oldDir, const fs::path& newDir, const fs::path& rel, CarriedFiles& out) {
    std::error_code ec;
    const fs::path from = oldDir / rel;
    if (fs::is_regular_file(from, ec)) {
        carryFile(from, newDir / rel, out);
        return;
    }
    if (!fs::is_directory(from, ec)) return;
    for (fs::recursive_directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file(ec)) continue;
        carryFile(it->path(), newDir / rel / it->path().lexically_relative(from), out);
    }
    if (ec) out.problems.push_back(from.string() + ": " + ec.message());
}

/// `ref` (relative to oldDir, or absolute) as seen from newDir; absolute paths stay absolute.
std::string relink(const std::string& ref, const fs::path& oldDir, const fs::path& newDir) {
    const fs::path r(ref);
    if (r.is_absolute()) return ref;
    const fs::path rel = (oldDir / r).lexically_normal().lexically_relative(newDir);
    return rel.empty() ? (oldDir / r).lexically_normal().generic_string() : rel.generic_string();
}
}  // namespace

CarriedFiles carryProjectFiles(const std::string& oldDirText, const std::string& newDirText, std::vector<Run>& runs) {
    CarriedFiles out;
    const fs::path oldDir = normalDir(oldDirText), newDir = normalDir(newDirText);
    if (oldDir == newDir) return out;
    carryTree(oldDir, newDir, "references", out);
    carryTree(oldDir, newDir, "data", out);
    for (Run& run : runs) {
        if (!run.id.empty() && insideProject(fs::path("runs") / run.id)) carryTree(oldDir, newDir, fs::path("runs") / run.id, out);
        for (std::string& a : run.artifacts) {
            if (insideProject(a)) {
                carryTree(oldDir, newDir, a, out);  // an artifact kept elsewhere in the project
            } else {
                a = relink(a, oldDir, newDir);
                ++out.relinked;
            }
        }
        if (std::optional<std::string>& dataset = run.settings.dataset) {
            const std::string d = *dataset;
            if (insideProject(d)) carryTree(oldDir, newDir, d, out);
            else if (!fs::path(d).is_absolute()) dataset = relink(d, oldDir, newDir);
        }
    }
    return out;
}

}  // namespace rrf
