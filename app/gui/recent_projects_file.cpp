#include "app/gui/recent_projects_file.h"

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/json_reader.h"

namespace rrf {

std::vector<std::string> readRecentProjectsFile(const std::string& file, size_t maxPaths) {
    const nlohmann::json j = readJsonFile(file);
    const JsonReader list(j, file);
    const size_t n = list.requireArray();
    std::vector<std::string> paths;
    for (size_t i = 0; i < n && paths.size() < maxPaths; ++i)
        if (list.at(i).value().is_string()) paths.push_back(list.at(i).string());
    return paths;
}

void writeRecentProjectsFile(const std::string& file, const std::vector<std::string>& paths) {
    writeFileAtomically(file, nlohmann::json(paths).dump(2) + "\n");
}

}  // namespace rrf
