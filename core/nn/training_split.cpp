#include "core/nn/training_split.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

namespace rrf {

std::vector<int> assignLongestFirst(const std::vector<uint64_t>& costs, int ranks) {
    if (ranks < 1) throw std::invalid_argument("assignLongestFirst: ranks must be >= 1, got " + std::to_string(ranks));
    std::vector<size_t> order(costs.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return costs[a] > costs[b]; });
    std::vector<uint64_t> load(size_t(ranks), 0);
    std::vector<int> rank(costs.size(), 0);
    for (size_t item : order) {
        const size_t least = size_t(std::min_element(load.begin(), load.end()) - load.begin());
        rank[item] = int(least);
        load[least] += costs[item];
    }
    return rank;
}

std::vector<int> trainingObjectOrder(const std::vector<ObjectSamples>& samples, const ObjectTrainingOptions& options) {
    if (!options.objects.empty()) return options.objects;
    std::vector<int> ids;
    for (const ObjectSamples& s : samples) ids.push_back(s.objectId);
    return ids;
}

std::vector<uint64_t> trainingCosts(const std::vector<ObjectSamples>& samples, const std::vector<int>& order) {
    std::map<int, uint64_t> records;
    for (const ObjectSamples& s : samples) records[s.objectId] = s.size();
    std::vector<uint64_t> costs;
    for (int id : order) {
        const auto it = records.find(id);
        costs.push_back(it != records.end() ? it->second : 0);
    }
    return costs;
}

int networksPerObject(const ObjectTrainingOptions& options) { return options.targets == TargetMode::Separate ? 2 : 1; }

}  // namespace rrf
