// The light-grid figures in JSON (see light_grid_json.h).
#include "core/eval/light_grid_json.h"

#include <cmath>

namespace rrf {

namespace {
nlohmann::json figureOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json lightGridJson(const Scene& scene, const LightGridMap& map) {
    nlohmann::json lights = nlohmann::json::array();
    for (int j = 0; j < map.grid.counts[1]; ++j)
        for (int k = 0; k < map.grid.counts[2]; ++k)
            for (int i = 0; i < map.grid.counts[0]; ++i) {
                const size_t n = map.grid.index(i, j, k);
                nlohmann::json objects = nlohmann::json::object();
                for (size_t id = 0; id < map.objects.size() && id < scene.objects.size(); ++id)
                    objects[scene.objects[id].name] = figureOrNull(map.objects[id][n]);
                const Vec3& l = map.lights[n];
                lights.push_back({{"index", {i, j, k}},
                                  {"position", {l.x, l.y, l.z}},
                                  {"global", {{"relative_rmse", figureOrNull(map.globalRaw[n])},
                                              {"relative_rmse_noise_floor", figureOrNull(map.globalNoiseFloor[n])},
                                              {"shown", figureOrNull(map.global[n])}}},
                                  {"objects", objects}});
            }
    return {{"grid", {map.grid.counts[0], map.grid.counts[1], map.grid.counts[2]}},
            {"region", {{"min", {map.region.lo.x, map.region.lo.y, map.region.lo.z}},
                        {"max", {map.region.hi.x, map.region.hi.y, map.region.hi.z}}}},
            {"figure", "relative RMSE of the global term over the kept object pixels, noise-corrected where the "
                       "reference's noise is known, else raw (\"shown\"; objects: the same per object)"},
            {"axes", "one slice per y of the grid; in its image x runs to the right and z downwards"},
            {"scale", LightGridMap::scaleOf(map.global)},
            {"lights", lights},
            {"marks", {{"source", map.marksSource}, {"count", map.marks.size()}, {"why", map.marksWhy}}}};
}

}  // namespace rrf
