#include "core/util/directory_replace.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/staged_files.h"
#include "core/util/temp_files.h"

#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)  // linux/fs.h; older C libraries do not declare it
#endif

namespace rrf {

namespace fs = std::filesystem;

namespace {

/// Exchanges two paths atomically; false with errno set where the kernel or file system cannot.
bool exchange(const fs::path& a, const fs::path& b) {
#ifdef SYS_renameat2
    return ::syscall(SYS_renameat2, AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
#else
    errno = ENOSYS;
    return false;
#endif
}

[[noreturn]] void fail(const fs::path& target, const std::string& what) {
    throw std::runtime_error(target.string() + ": " + what);
}

/// True if `inner` is `outer` or lies below it (both canonical).
bool within(const fs::path& inner, const fs::path& outer) {
    const fs::path rel = inner.lexically_relative(outer);
    return !rel.empty() && *rel.begin() != "..";
}

/// Hard-links (copies where linking fails) the entries of `from` that are not members into `to`.
void carryOver(const fs::path& from, const fs::path& to, const std::function<bool(const std::string&)>& isMember) {
    std::error_code ec;
    for (fs::directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        // Members, and temporary files of members that a killed writer left, go with the old set.
        const std::string temporaryOf = temporaryFileTarget(name);
        if (isMember(name) || (!temporaryOf.empty() && isMember(temporaryOf))) continue;
        std::error_code linkError;
        fs::copy(it->path(), to / name,
                 fs::copy_options::recursive | fs::copy_options::create_hard_links | fs::copy_options::copy_symlinks,
                 linkError);
        if (!linkError) continue;
        std::error_code copyError;
        fs::remove_all(to / name, copyError);
        fs::copy(it->path(), to / name, fs::copy_options::recursive | fs::copy_options::copy_symlinks, copyError);
        if (copyError) fail(from, "cannot keep '" + name + "' (not part of the set) in the new directory: " + copyError.message());
    }
    if (ec) fail(from, "cannot list the directory: " + ec.message());
}

/// `text` with every occurrence of the staging directory's path replaced by the target's, so that a
/// message about a file being written into the new set names the file the user will look for.
std::string namingTarget(std::string text, const std::string& staging, const std::string& target) {
    for (size_t at = text.find(staging); at != std::string::npos; at = text.find(staging, at + target.size()))
        text.replace(at, staging.size(), target);
    return text;
}

/// Rethrows what `fill` threw with the target's paths for the staging directory's and what the
/// failed replacement kept: OutputError and InputError keep their type (callers tell them apart),
/// other runtime errors (an image refused by its encoder) become std::runtime_error and invalid
/// arguments std::invalid_argument; anything else (bad_alloc, a logic error) propagates as it is.
[[noreturn]] void rethrowNamingTarget(const std::string& staging, const std::string& target, bool replacing) {
    const std::string kept =
        replacing ? "the previous contents of '" + target + "' are kept" : "'" + target + "' was not created";
    try {
        throw;
    } catch (const OutputError& e) {
        throw OutputError(namingTarget(e.path(), staging, target), namingTarget(e.problem(), staging, target), kept);
    } catch (const InputError& e) {
        throw InputError(namingTarget(e.file(), staging, target), namingTarget(e.where(), staging, target),
                         namingTarget(e.detail(), staging, target) + "; " + kept);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(namingTarget(e.what(), staging, target) + "; " + kept);
    } catch (const std::invalid_argument& e) {
        // An encoder's refused argument (a non-finite exposure) names the file it was writing too.
        throw std::invalid_argument(namingTarget(e.what(), staging, target) + "; " + kept);
    }
}

}  // namespace

int removeStaleDirectoryTemporaries(const std::string& targetPath) {
    const fs::path target(targetPath);
    const std::string name = target.filename().string();
    int count = 0;
    std::error_code ec;
    for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
        const std::string entry = it->path().filename().string();
        if (entry.empty() || entry[0] != '.') continue;
        const long pid = temporaryOwnerPid(entry, name, {"tmp", "old"});
        if (pid < 0 || processAlive(pid)) continue;
        std::error_code e;
        const bool old = entry.size() > 4 && entry.compare(entry.size() - 4, 4, ".old") == 0;
        // A writer killed between the fallback's two renames left the old set aside and no target.
        if (old && !fs::exists(target, e)) {
            fs::rename(it->path(), target, e);
            if (!e) ++count;
        } else if (fs::remove_all(it->path(), e) > 0 && !e) {
            ++count;
        }
    }
    return count;
}

void replaceDirectory(const std::string& targetPath, const std::function<bool(const std::string& name)>& isMember,
                      const std::function<void(const std::string& staging)>& fill) {
    std::error_code ec;
    // The real directory (not a symbolic link to it, not "dir/"), so the swap replaces what readers open.
    fs::path target = fs::weakly_canonical(fs::absolute(targetPath), ec);
    if (ec) fail(targetPath, "cannot resolve the output directory: " + ec.message());
    if (target.filename().empty()) target = target.parent_path();
    const fs::path parent = target.parent_path();
    const std::string name = target.filename().string();
    if (name.empty() || target == parent) fail(targetPath, "cannot replace the root directory as a whole");
    const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
    if (!ec && within(cwd, target))
        fail(targetPath, "is the current directory or contains it: write the set into a directory of its own (e.g. " +
                             targetPath + "/out)");
    fs::create_directories(parent, ec);
    if (ec || !fs::is_directory(parent)) fail(parent, "cannot create output directory" + (ec ? ": " + ec.message() : ""));
    // Stale temporaries first: cleaning them up may put a killed writer's moved-aside set back at the
    // target, whose other files must then be carried over like any old set's.
    removeStaleDirectoryTemporaries(target.string());
    const bool replacing = fs::exists(target);
    if (replacing && !fs::is_directory(target)) fail(targetPath, "exists and is not a directory");

    const fs::path staging = temporaryDirectoryFor(target.string(), "tmp");
    fs::create_directory(staging, ec);
    // The new set is built beside the target: what stops that (permissions, space) stops the target.
    if (ec)
        throw OutputError(targetPath, "cannot write into its directory: " + ec.message(),
                          replacing ? "the previous contents are kept" : "it was not created");
    try {
        fill(staging.string());
        if (replacing) carryOver(target, staging, isMember);
        // The set's files and their names are durable before the swap makes them the target's;
        // members written with writeStagedFile have not been synced yet.
        syncStagedDirectory(staging.string());
    } catch (...) {
        fs::remove_all(staging, ec);
        // The user's spelling of the target (less trailing separators), not the resolved path.
        std::string shown = targetPath;
        while (shown.size() > 1 && shown.back() == '/') shown.pop_back();
        rethrowNamingTarget(staging.string(), shown, replacing);
    }
    crashPoint("replace " + name + ": before swap");
    if (!replacing) {
        if (std::rename(staging.c_str(), target.c_str()) == 0) {
            syncDirectory(parent.string());
            return;
        }
        // A target that another writer created meanwhile (ENOTEMPTY) is exchanged like an old set.
        if (errno != ENOTEMPTY && errno != EEXIST) {
            const std::string err = std::strerror(errno);
            fs::remove_all(staging, ec);
            fail(targetPath, "cannot move the new set into place: " + err + "; it was not created");
        }
    }
    if (exchange(staging, target)) {
        crashPoint("replace " + name + ": after swap");
    } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) {
        // No atomic exchange here: old aside, new into place, old back if that fails. A kill between
        // the renames leaves the old set at `aside`, which the next write puts back.
        const fs::path aside = temporaryDirectoryFor(target.string(), "old");
        if (std::rename(target.c_str(), aside.c_str()) != 0) {
            const std::string err = std::strerror(errno);
            fs::remove_all(staging, ec);
            fail(targetPath, "cannot move the old set aside (it is kept): " + err);
        }
        crashPoint("replace " + name + ": between renames");
        if (std::rename(staging.c_str(), target.c_str()) != 0) {
            const std::string err = std::strerror(errno);
            std::rename(aside.c_str(), target.c_str());
            fs::remove_all(staging, ec);
            fail(targetPath, "cannot move the new set into place (the old one is kept): " + err);
        }
        fs::remove_all(aside, ec);
        syncDirectory(parent.string());
        return;
    } else {
        const std::string err = std::strerror(errno);
        fs::remove_all(staging, ec);
        fail(targetPath, "cannot swap the new set into place (the old one is kept): " + err);
    }
    syncDirectory(parent.string());
    // After an exchange `staging` holds the old set.
    fs::remove_all(staging, ec);
}

}  // namespace rrf
