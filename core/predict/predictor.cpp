#include "core/predict/predictor.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/predict/exact_direct.h"
#include "core/predict/glossy_gather.h"
#include "core/predict/member_spread.h"
#include "core/util/error.h"

namespace rrf {

namespace {
/// Pixels per inference batch: big enough for efficient GEMMs, small enough that two cores share
/// the work of one object. Fixed, so batch boundaries never depend on the thread count.
constexpr size_t kBatch = 4096;

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Where one object's terms come from: a network and the first of its output rows, or nothing.
struct Source {
    const PartitionedNetwork* net = nullptr;
    int row = 0;
    bool ok() const { return net != nullptr; }
};

struct ObjectPlan {
    Source direct, indirect, global;  ///< global only when direct or indirect is missing
    bool exactDirect = false;
};

ObjectPlan planFor(const ObjectNetworks& o, bool exactDirect) {
    ObjectPlan p;
    auto get = [&](const char* t) { return o.has(t) ? &o.byTarget.at(t) : nullptr; };
    if (const PartitionedNetwork* j = get("joint")) {
        p.direct = {j, 0};
        p.indirect = {j, 3};
    }
    if (const PartitionedNetwork* d = get("direct")) p.direct = {d, 0};
    if (const PartitionedNetwork* i = get("indirect")) p.indirect = {i, 0};
    p.exactDirect = exactDirect;
    if (exactDirect) p.direct = {};
    const bool directOk = exactDirect || p.direct.ok();
    if (!(directOk && p.indirect.ok()))
        if (const PartitionedNetwork* g = get("global")) p.global = {g, 0};
    return p;
}
/// The tree the leaf overlay shows: the model that supplies indirect light, else global, else direct.
const PartitionedNetwork* overlayTree(const ObjectPlan& p) {
    return p.indirect.ok() ? p.indirect.net : p.global.ok() ? p.global.net : p.direct.net;
}
}  // namespace

std::vector<int> gatheredObjects(const Scene& scene, const ModelSet& models, const PredictionSettings& settings) {
    std::vector<int> ids;
    const bool exact = settings.direct == PredictionSettings::Direct::Exact;
    for (const Object& obj : scene.objects) {
        if (!GlossyGather::gathers(scene, obj, settings)) continue;
        const ObjectNetworks* o = models.find(obj.id);
        if (!o || o->byTarget.empty()) continue;
        const ObjectPlan plan = planFor(*o, exact);
        if (plan.global.ok() || !(plan.exactDirect || plan.direct.ok())) continue;
        ids.push_back(obj.id);
    }
    return ids;
}

std::vector<int> Predictor::leaves(const GBuffer& gb) const {
    std::vector<int> leaf(size_t(gb.width) * size_t(gb.height), -1);
    const bool exact = settings_.direct == PredictionSettings::Direct::Exact;
    for (size_t id = 0; id < gb.pixelsByObject.size(); ++id) {
        const ObjectNetworks* o = models_.find(int(id));
        if (!o || o->byTarget.empty()) continue;
        const PartitionedNetwork* t = overlayTree(planFor(*o, exact));
        if (!t) continue;
        for (uint32_t i : gb.pixelsByObject[id]) leaf[i] = t->tree.findLeaf(gb.input(i));
    }
    return leaf;
}

Predictor::Predictor(const Scene& scene, const ModelSet& models, const PredictionSettings& settings)
    : scene_(scene),
      models_(models),
      settings_(settings),
      layout_(RecordLayout::forScene(scene)),
      accel_(scene),
      tracer_(scene, accel_, Estimator::NEE, 1),
      gathered_(gatheredObjects(scene, models, settings)) {
    if (!models.inputLayout.empty() && models.inputLayout != layout_.inputs)
        throw InputError(models.dir, "/input_layout", "the networks' input layout differs from this scene's record layout");
    for (const ObjectNetworks& o : models.objects)
        for (const auto& [target, tree] : o.byTarget) {
            if (tree.spreadMembers() > 0) spread_ = true;
            const MlpArch& net = tree.arch();
            if (tree.rawInputs() != layout_.inputCount())
                throw std::invalid_argument("network " + target + " of object " + std::to_string(o.objectId) + " has " +
                                            std::to_string(tree.rawInputs()) + " inputs, the scene's records have " +
                                            std::to_string(layout_.inputCount()));
            const int want = target == "joint" ? 6 : 3;
            if (net.outputs != want)
                throw std::invalid_argument("network " + target + " of object " + std::to_string(o.objectId) + " has " +
                                            std::to_string(net.outputs) + " outputs, expected " + std::to_string(want));
        }
}

GBuffer Predictor::gbuffer(const Vec3& lightPos, int width, int height) const {
    return buildGBuffer(tracer_, layout_, lightPos, width, height);
}

std::vector<std::string> Predictor::describe() const {
    std::vector<std::string> lines;
    for (const Object& obj : scene_.objects) {
        const ObjectNetworks* o = models_.find(obj.id);
        std::string nets;
        if (o)
            for (const auto& kv : o->byTarget)
                nets += (nets.empty() ? "" : " + ") + kv.first + " " + kv.second.arch().describe() +
                        (kv.second.leafCount() > 1 ? " × " + std::to_string(kv.second.leafCount()) + " leaves" : "");
        lines.push_back(std::to_string(obj.id) + " " + obj.name + ": " + (nets.empty() ? "no network" : nets));
    }
    return lines;
}

Prediction Predictor::predict(const GBuffer& gb) const {
    Prediction pr = predictTerms(gb, settings_.directSamples, settings_.seed, spread_);
    if (!gathered_.empty()) gather(gb, pr, 0, settings_.seed);
    return pr;
}

void Predictor::gather(const GBuffer& gb, Prediction& pr, int depth, uint64_t seed) const {
    const auto t0 = std::chrono::steady_clock::now();
    const PredictionSettings::Gather& g = settings_.gather;
    const GlossyGather gatherer(tracer_, layout_, depth == 0 ? g.lobeSamples : g.secondLobeSamples,
                                depth == 0 ? g.diffuseSamples : g.secondDiffuseSamples, seed);
    if (gatherer.raysPerPixel() == 0) return;
    // The camera's gathered pixels take the diffuse part of glossy light from the light's side
    // (core/predict/glossy_caustics.h); the second bounce keeps it in its cosine rays.
    std::unique_ptr<GlossyCaustics> caustics;
    if (depth == 0 && g.causticSamples > 0 && g.diffuseSamples > 0 &&
        settings_.direct == PredictionSettings::Direct::Exact) {
        caustics = std::make_unique<GlossyCaustics>(tracer_, g.causticSamples, float(g.minExponent), seed);
        // A caster's glossy direct light is taken out of the cosine rays only where exact direct
        // light computes it there: a global network (or none) answers for its points whole.
        for (const Object& obj : scene_.objects) {
            if (!caustics->casts(obj.id)) continue;
            const ObjectNetworks* o = models_.find(obj.id);
            const ObjectPlan plan = o ? planFor(*o, true) : ObjectPlan{};
            if (!o || o->byTarget.empty() || plan.global.ok()) caustics->exclude(obj.id);
        }
        if (!caustics->anyCaster()) caustics.reset();
    }
    const Light movable = tracer_.movableLightAt(gb.lightPosition);
    // Pixels per batch: bounds the secondary buffer (raysPerPixel records each) and keeps batch
    // boundaries independent of the thread count.
    const size_t chunk = std::max<size_t>(1, (size_t(1) << 18) / size_t(std::max(1, gatherer.raysPerPixel())));
    for (const int object : gathered_) {
        const size_t id = size_t(object);
        if (id >= gb.pixelsByObject.size()) continue;
        // Objects gathered by name (diffuse receivers of caustics) gather for the camera only: seen
        // in a mirror, their own network's light is what the second bounce's few cosine rays would
        // give, without the caustic fireflies those rays would find.
        if (depth > 0 && !GlossyGather::applies(scene_.materials[size_t(scene_.objects[id].material)], float(g.minExponent)))
            continue;
        const std::vector<uint32_t>& px = gb.pixelsByObject[id];
        for (size_t b = 0; b < px.size(); b += chunk) {
            const size_t n = std::min(chunk, px.size() - b);
            const GlossyGather::Batch batch = gatherer.trace(gb, px.data() + b, n, caustics.get());
            std::vector<Vec3> caustic(caustics ? n : 0, Vec3(0.f));
            if (caustics) {
                const Vec3 kd = scene_.materials[size_t(scene_.objects[id].material)].kd;
                tbb::parallel_for(size_t(0), n, [&](size_t j) {
                    const uint32_t i = px[b + j];
                    const float* in = gb.input(i);
                    // As the cosine rays: nothing is gathered where the view is below the shading normal.
                    if (dot(gb.normal[i], Vec3(in[3], in[4], in[5])) <= 0.f) return;
                    TraceCounters counters;
                    caustic[j] = caustics->radiance(Vec3(in[0], in[1], in[2]), gb.normal[i], gb.geometricNormal[i], kd,
                                                    object, movable, i, counters);
                });
            }
            // The secondary points are keyed by their index in the batch: a stream of their own per
            // (level, object, batch), so no two batches share random numbers.
            const uint64_t batchSeed = mix64(seed ^ mix64((uint64_t(depth + 1) << 56) ^ (uint64_t(id) << 32) ^ uint64_t(b)));
            Prediction secondary = predictTerms(batch.secondary, g.directSamples, batchSeed, false);
            if (depth == 0) gather(batch.secondary, secondary, 1, mix64(batchSeed ^ kGlossyGatherStream));
            pr.nonFinite += secondary.nonFinite;
            const Image& radiance = secondary.image(Term::Global);
            for (size_t j = 0; j < n; ++j) {
                const uint32_t i = px[b + j];
                const int x = int(i % uint32_t(gb.width)), y = int(i / uint32_t(gb.width));
                Vec3 ind = gatherer.gathered(batch, radiance, j);
                if (caustics) ind += caustic[j];
                if (!ind.isFinite()) {
                    ++pr.nonFinite;
                    ind = Vec3(0.f);
                }
                pr.images[int(Term::Indirect)].set(x, y, ind);
                pr.images[int(Term::Global)].set(x, y, pr.images[int(Term::Direct)].at(x, y) + ind);
                // The gathered light is not this object's network's: its members' spread does not apply.
                if (!pr.spreadKnown.empty() && pr.spreadKnown[i]) {
                    pr.spreadKnown[i] = 0;
                    pr.spread.set(x, y, Vec3(0.f));
                    --pr.spreadPixels;
                }
            }
            pr.pixelsGathered += n;
        }
    }
    if (depth == 0) pr.gatherSeconds = since(t0);
}

Prediction Predictor::predictTerms(const GBuffer& gb, int directSamples, uint64_t seed, bool withSpread) const {
    Prediction pr;
    for (Image& im : pr.images) im = Image(gb.width, gb.height);
    pr.leaf.assign(size_t(gb.width) * size_t(gb.height), -1);
    if (withSpread) {
        pr.spread = Image(gb.width, gb.height);
        pr.spreadKnown.assign(size_t(gb.width) * size_t(gb.height), 0);
    }
    const bool exact = settings_.direct == PredictionSettings::Direct::Exact;

    // Emitters show their emission in the direct and global terms, as in the ground truth.
    for (uint32_t i : gb.emitterPixels) {
        const int x = int(i % uint32_t(gb.width)), y = int(i / uint32_t(gb.width));
        pr.images[int(Term::Direct)].set(x, y, gb.emitted[i]);
        pr.images[int(Term::Global)].set(x, y, gb.emitted[i]);
    }

    struct Job {
        size_t object, begin, end;
        ObjectPlan plan;
    };
    std::vector<Job> jobs;
    uint64_t missing[kTermCount] = {0, 0, 0};
    for (size_t id = 0; id < gb.pixelsByObject.size(); ++id) {
        const std::vector<uint32_t>& px = gb.pixelsByObject[id];
        if (px.empty()) continue;
        const ObjectNetworks* o = models_.find(int(id));
        if (!o || o->byTarget.empty()) {
            pr.objectsWithoutNetwork.push_back(int(id));
            pr.pixelsWithoutNetwork += px.size();
            continue;
        }
        const ObjectPlan plan = planFor(*o, exact);
        const bool d = plan.exactDirect || plan.direct.ok(), ind = plan.indirect.ok();
        if (!d) missing[int(Term::Direct)] += px.size();
        if (!ind) missing[int(Term::Indirect)] += px.size();
        if (!(d && ind) && !plan.global.ok()) missing[int(Term::Global)] += px.size();
        pr.pixelsPredicted += px.size();
        for (size_t b = 0; b < px.size(); b += kBatch) jobs.push_back({id, b, std::min(px.size(), b + kBatch), plan});
    }
    for (int t = 0; t < kTermCount; ++t) {
        if (!missing[t]) continue;
        pr.available[t] = false;
        pr.unavailableWhy.push_back(std::string(termName(Term(t))) + ": " + std::to_string(missing[t]) +
                                    " covered pixels belong to objects whose networks do not predict it");
    }

    auto t0 = std::chrono::steady_clock::now();
    std::vector<uint64_t> jobNonFinite(jobs.size(), 0);
    tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
        const Job& job = jobs[j];
        const std::vector<uint32_t>& px = gb.pixelsByObject[job.object];
        const Eigen::Index n = Eigen::Index(job.end - job.begin);
        MatX<float> x(gb.numInputs, n);
        for (Eigen::Index k = 0; k < n; ++k)
            x.col(k) = Eigen::Map<const VecX<float>>(gb.input(px[job.begin + size_t(k)]), gb.numInputs);
        // Each distinct network runs once per batch even when it feeds two terms (joint).
        const PartitionedNetwork* nets[3] = {job.plan.direct.net, job.plan.indirect.net, job.plan.global.net};
        MatX<float> outs[3];
        for (int a = 0; a < 3; ++a) {
            if (!nets[a]) continue;
            int same = -1;
            for (int b = 0; b < a; ++b)
                if (nets[b] == nets[a]) same = b;
            outs[a] = same >= 0 ? outs[same] : nets[a]->predict(x);
        }
        const int rows[3] = {job.plan.direct.row, job.plan.indirect.row, job.plan.global.row};
        const PartitionedNetwork* shown = overlayTree(job.plan);
        const std::vector<int> leaves = shown ? shown->findLeaves(x) : std::vector<int>(size_t(n), -1);
        for (Eigen::Index k = 0; k < n; ++k) pr.leaf[px[job.begin + size_t(k)]] = leaves[size_t(k)];
        uint64_t bad = 0;
        auto value = [&](int a, Eigen::Index k) {
            Vec3 v(outs[a](rows[a], k), outs[a](rows[a] + 1, k), outs[a](rows[a] + 2, k));
            if (!v.isFinite()) {
                ++bad;
                v = Vec3(0.f);
            }
            return v;
        };
        for (Eigen::Index k = 0; k < n; ++k) {
            const uint32_t i = px[job.begin + size_t(k)];
            const int xx = int(i % uint32_t(gb.width)), yy = int(i / uint32_t(gb.width));
            const Vec3 d = nets[0] ? value(0, k) : Vec3(0.f);
            const Vec3 ind = nets[1] ? value(1, k) : Vec3(0.f);
            if (nets[0]) pr.images[int(Term::Direct)].set(xx, yy, d);
            if (nets[1]) pr.images[int(Term::Indirect)].set(xx, yy, ind);
            // In exact mode the direct term is added to the global image after the exact pass.
            if (nets[2]) pr.images[int(Term::Global)].set(xx, yy, value(2, k));
            else pr.images[int(Term::Global)].set(xx, yy, d + ind);
        }
        jobNonFinite[j] = bad;
    });
    for (uint64_t b : jobNonFinite) pr.nonFinite += b;
    pr.inferenceSeconds = since(t0);

    if (withSpread) {
        // The members' extra forward passes, timed apart so the frame's network time stays the
        // merged network's alone.
        const auto s0 = std::chrono::steady_clock::now();
        tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
            const Job& job = jobs[j];
            const std::vector<uint32_t>& px = gb.pixelsByObject[job.object];
            const Eigen::Index n = Eigen::Index(job.end - job.begin);
            // The network part of the pixel's global term: the global network, else direct and indirect.
            std::vector<SpreadTerm> terms;
            if (job.plan.global.ok()) terms.push_back({job.plan.global.net, job.plan.global.row});
            else
                for (const Source& src : {job.plan.direct, job.plan.indirect})
                    if (src.ok()) terms.push_back({src.net, src.row});
            MatX<float> x(gb.numInputs, n), sd;
            for (Eigen::Index k = 0; k < n; ++k)
                x.col(k) = Eigen::Map<const VecX<float>>(gb.input(px[job.begin + size_t(k)]), gb.numInputs);
            if (!memberSpread(terms, x, sd)) return;
            for (Eigen::Index k = 0; k < n; ++k) {
                const uint32_t i = px[job.begin + size_t(k)];
                const Vec3 v(sd(0, k), sd(1, k), sd(2, k));
                if (!v.isFinite()) continue;
                pr.spread.set(int(i % uint32_t(gb.width)), int(i / uint32_t(gb.width)), v);
                pr.spreadKnown[i] = 1;
            }
        });
        for (uint8_t k : pr.spreadKnown) pr.spreadPixels += k;
        pr.spreadSeconds = since(s0);
    }

    if (exact) {
        t0 = std::chrono::steady_clock::now();
        const Light movable = tracer_.movableLightAt(gb.lightPosition);
        const ExactDirect direct(tracer_, directSamples, seed);
        std::vector<char> hasGlobalNet(scene_.objects.size(), 0);
        for (const Job& job : jobs) hasGlobalNet[job.object] = job.plan.global.ok();
        const Image d = direct.image(gb, movable, pr.nonFinite);
        for (int y = 0; y < gb.height; ++y)
            for (int x = 0; x < gb.width; ++x) {
                const int id = gb.object[size_t(y) * size_t(gb.width) + size_t(x)];
                if (id < 0) continue;  // emitter pixels keep their emission
                pr.images[int(Term::Direct)].set(x, y, d.at(x, y));
                // A global net already holds the direct light; add exact direct light only where none did.
                if (!hasGlobalNet[size_t(id)])
                    pr.images[int(Term::Global)].set(x, y, pr.images[int(Term::Global)].at(x, y) + d.at(x, y));
            }
        pr.directSeconds = since(t0);
    }
    return pr;
}

}  // namespace rrf
