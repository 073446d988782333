#include "core/data/generator_stats.h"

namespace rrf {

GeneratorStats& GeneratorStats::operator+=(const GeneratorStats& other) {
    records += other.records;
    cellsDroppedInsideObject += other.cellsDroppedInsideObject;
    cellsDroppedOutsideScene += other.cellsDroppedOutsideScene;
    cellsDroppedBehindSurface += other.cellsDroppedBehindSurface;
    recordsAtSppCap += other.recordsAtSppCap;
    raysEscaped += other.raysEscaped;
    raysHitEmitter += other.raysHitEmitter;
    recordsWithoutFiniteSample += other.recordsWithoutFiniteSample;
    nonFiniteSamplesDropped += other.nonFiniteSamplesDropped;
    recordsPerCell.insert(recordsPerCell.end(), other.recordsPerCell.begin(), other.recordsPerCell.end());
    if (recordsPerObject.size() < other.recordsPerObject.size()) recordsPerObject.resize(other.recordsPerObject.size(), 0);
    for (size_t i = 0; i < other.recordsPerObject.size(); ++i) recordsPerObject[i] += other.recordsPerObject[i];
    paths += other.paths;
    rays += other.rays;
    shadowRays += other.shadowRays;
    noisePerObject.clear();
    return *this;
}

}  // namespace rrf
