#include "core/eval/reference_store.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include "core/data/dataset_file.h"
#include "core/data/record_layout.h"
#include "core/eval/reference_store_file.h"
#include "core/predict/gbuffer.h"
#include "core/render/render_outputs.h"
#include "core/scene/accel.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMetaFile = kReferenceEntryFile;
constexpr const char* kStateFile = "state.rrfs";
constexpr char kStateMagic[8] = {'R', 'R', 'F', 'S', 'T', 'A', 'T', 'E'};
constexpr uint32_t kStateVersion = 1;
/// A partial render is saved this often, so a killed process (not only a cancelled one) loses little.
constexpr double kCheckpointSeconds = 120.0;

static_assert(std::is_trivially_copyable<PixelSums>::value && sizeof(PixelSums) == 128,
              "the state file stores PixelSums as 15 doubles and 2 uint32 without padding");

/// Appends the bytes of `v` (fixed-size fields of the key digest and the state file).
template <class T>
void put(std::string& out, const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string num(double v) {
    if (!std::isfinite(v)) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// ---- state file -------------------------------------------------------------------------------

/// Header fields, pixel sums, then checksum64 of everything before it.
std::string encodeState(const RenderState& st) {
    std::string out;
    out.reserve(96 + st.pixels.size() * sizeof(PixelSums));
    out.append(kStateMagic, sizeof kStateMagic);
    put(out, kStateVersion);
    put(out, uint32_t(0));
    put(out, int32_t(st.width));
    put(out, int32_t(st.height));
    put(out, int32_t(st.sppDone));
    put(out, int32_t(st.passes));
    put(out, st.samples);
    put(out, st.rays);
    put(out, st.shadowRays);
    put(out, st.nonFinite);
    put(out, st.seconds);
    put(out, uint64_t(st.pixels.size()));
    out.append(reinterpret_cast<const char*>(st.pixels.data()), st.pixels.size() * sizeof(PixelSums));
    put(out, checksum64(out.data(), out.size()));
    return out;
}

RenderState decodeState(const std::string& path, int width, int height) {
    std::string bytes;
    try {
        bytes = readFile(path);
    } catch (const std::runtime_error& e) {
        throw InputError(path, "", std::string("cannot read the reference's state: ") + e.what());
    }
    auto fail = [&](const std::string& what) {
        throw InputError(path, "", what + " (a damaged reference entry: rrf reference --prune removes it)");
    };
    size_t at = 0;
    auto get = [&](auto& v) {
        if (at + sizeof v > bytes.size()) fail("truncated state file");
        std::memcpy(&v, bytes.data() + at, sizeof v);
        at += sizeof v;
    };
    if (bytes.size() < sizeof kStateMagic + 8 || std::memcmp(bytes.data(), kStateMagic, sizeof kStateMagic) != 0)
        fail("not a reference state file (bad magic)");
    at = sizeof kStateMagic;
    uint32_t version = 0, reserved = 0;
    get(version);
    get(reserved);
    if (version != kStateVersion) fail("unsupported state file version " + std::to_string(version));
    RenderState st;
    int32_t w = 0, h = 0, spp = 0, passes = 0;
    get(w);
    get(h);
    get(spp);
    get(passes);
    get(st.samples);
    get(st.rays);
    get(st.shadowRays);
    get(st.nonFinite);
    get(st.seconds);
    uint64_t count = 0;
    get(count);
    if (w != width || h != height)
        fail("the state is " + std::to_string(w) + "x" + std::to_string(h) + ", its key says " + std::to_string(width) +
             "x" + std::to_string(height));
    if (count != uint64_t(w) * uint64_t(h) || bytes.size() != at + count * sizeof(PixelSums) + sizeof(uint64_t))
        fail("size " + std::to_string(bytes.size()) + " bytes does not match " + std::to_string(w) + "x" + std::to_string(h) +
             " pixels");
    uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
    if (stored != checksum64(bytes.data(), bytes.size() - sizeof stored)) fail("checksum mismatch: the file is corrupted");
    st.width = w;
    st.height = h;
    st.sppDone = spp;
    st.passes = passes;
    st.pixels.resize(size_t(count));
    std::memcpy(st.pixels.data(), bytes.data() + at, size_t(count) * sizeof(PixelSums));
    return st;
}

// ---- entries ----------------------------------------------------------------------------------

bool isTemporary(const fs::path& p) { return !p.filename().empty() && p.filename().string()[0] == '.'; }

/// The pixels of a state, with the variances once there are 2 samples per pixel (unknown before).
Reference referenceOf(const RenderState& st, const Vec3& lightPosition) {
    return referenceOf(Renderer::snapshotOf(st), lightPosition);
}

/// The global term's relative noise (NaN while unknown).
double globalNoise(const ReferenceNoise& n) { return n.relativeRmse[int(Term::Global)]; }

bool meets(double noise, int spp, double wanted, int cap) { return spp >= cap || (std::isfinite(noise) && noise <= wanted); }

/// Writes the entry as a whole (core/util/directory_replace.h): the id's directory is always one
/// whole entry or absent, never a mixture of an old and a new one.
void writeEntry(const fs::path& storeDir, const ReferenceKey& key, const RenderState& st, const Reference& ref,
                const ReferenceNoise& noise, bool complete, double wanted) {
    const fs::path final = storeDir / key.id();
    // Every file of an entry is the store's own: nothing in the old directory is kept.
    const auto member = [](const std::string&) { return true; };
    try {
        replaceDirectory(final.string(), member, [&](const std::string& dir) {
            const fs::path tmp(dir);
            const std::string state = encodeState(st);
            writeFileAtomically((tmp / kStateFile).string(), state);
            for (Term t : kTerms)
                writeImage((tmp / (std::string(termName(t)) + ".exr")).string(), ref.image(t), ImageFormat::EXR);
            writeReferenceEntryFiles(dir, key, ref, noise, {st.sppDone, st.seconds, st.nonFinite, complete, wanted},
                                     kStateFile, hexString16(checksum64(state.data(), state.size())));
        });
    } catch (const InputError&) {
        throw;
    } catch (const std::runtime_error& e) {
        throw InputError(final.string(), "", std::string("could not store the reference entry: ") + e.what());
    }
}

}  // namespace

// ---- ReferenceKey -----------------------------------------------------------------------------

ReferenceKey ReferenceKey::of(const Scene& scene, const Vec3& lightPosition, int width, int height,
                              const RenderSettings& render) {
    ReferenceKey k;
    k.sceneHash = scene.contentHash();
    std::string cam;
    for (const Vec3& v : {scene.camera.eye, scene.camera.target, scene.camera.up}) {
        put(cam, v.x);
        put(cam, v.y);
        put(cam, v.z);
    }
    put(cam, scene.camera.fovYDegrees);
    k.cameraHash = checksum64(cam.data(), cam.size());
    // Where setLightPosition would put it (a scene without lights has none to move).
    Scene moved = scene;
    if (!moved.lights.empty()) moved.setLightPosition(lightPosition);
    k.lightPosition = moved.lightPosition();
    k.width = width > 0 ? width : scene.camera.width;
    k.height = height > 0 ? height : scene.camera.height;
    // The estimator that runs, not the setting: an "auto" reference is keyed by what auto chose.
    k.estimator = chooseEstimator(render.estimator, Effects::derive(scene)).estimator;
    k.maxDepth = render.maxDepth;
    k.seed = render.seed;
    return k;
}

std::string ReferenceKey::id() const {
    std::string b;
    put(b, sceneHash);
    put(b, cameraHash);
    put(b, lightPosition.x);
    put(b, lightPosition.y);
    put(b, lightPosition.z);
    put(b, int32_t(width));
    put(b, int32_t(height));
    put(b, int32_t(estimator));
    put(b, int32_t(maxDepth));
    put(b, seed);
    return hexString16(checksum64(b.data(), b.size()));
}

bool ReferenceKey::operator==(const ReferenceKey& o) const {
    return sceneHash == o.sceneHash && cameraHash == o.cameraHash && lightPosition.x == o.lightPosition.x &&
           lightPosition.y == o.lightPosition.y && lightPosition.z == o.lightPosition.z && width == o.width &&
           height == o.height && estimator == o.estimator && maxDepth == o.maxDepth && seed == o.seed;
}

// ---- ReferenceStore ---------------------------------------------------------------------------

ReferenceStore::ReferenceStore(std::string dir) : dir_(std::move(dir)) {}

std::optional<StoredReference> ReferenceStore::find(const ReferenceKey& key) const {
    const fs::path dir = fs::path(dir_) / key.id();
    if (!fs::exists(dir / kMetaFile)) return std::nullopt;
    StoredReference r = readReferenceEntry(dir.string());
    if (!(r.key == key)) throw InputError((dir / kMetaFile).string(), "/key", "another key under this key's id");
    return r;
}

std::vector<StoredReference> ReferenceStore::list(uint64_t currentSceneHash) const {
    std::vector<StoredReference> out;
    std::error_code ec;
    if (!fs::is_directory(dir_, ec)) return out;
    std::vector<fs::path> dirs;
    for (const fs::directory_entry& e : fs::directory_iterator(dir_))
        if (e.is_directory() && !isTemporary(e.path())) dirs.push_back(e.path());
    std::sort(dirs.begin(), dirs.end());
    for (const fs::path& d : dirs) {
        try {
            StoredReference r = readReferenceEntry(d.string());
            r.stale = r.key.sceneHash != currentSceneHash;
            out.push_back(std::move(r));
        } catch (const InputError& e) {
            StoredReference r;
            r.dir = d.string();
            r.problem = e.what();
            out.push_back(std::move(r));
        }
    }
    return out;
}

int ReferenceStore::pruneStale(uint64_t currentSceneHash) {
    int removed = 0;
    for (const StoredReference& r : list(currentSceneHash))
        if (r.stale || !r.problem.empty()) removed += fs::remove_all(r.dir) > 0 ? 1 : 0;
    std::error_code ec;
    if (fs::is_directory(dir_, ec))
        for (const fs::directory_entry& e : fs::directory_iterator(dir_))
            if (e.is_directory() && isTemporary(e.path())) fs::remove_all(e.path(), ec);
    return removed;
}

Reference ReferenceStore::obtain(const Scene& scene, const ReferenceKey& key, const NoiseTarget& target,
                                 const std::atomic<bool>* cancel,
                                 const std::function<void(const ReferenceProgress&)>& progress,
                                 const std::function<double(const Reference&)>& measuredError,
                                 const std::function<void(const std::string&)>& log) {
    if (scene.contentHash() != key.sceneHash)
        throw std::invalid_argument("ReferenceStore::obtain: the scene's content hash is not the key's");
    auto say = [&](const std::string& m) {
        if (log) log(m);
    };
    const std::string name = "reference " + key.id();
    Scene moved = scene;
    if (!moved.lights.empty()) moved.setLightPosition(key.lightPosition);
    const Accel accel(moved);
    // The noise is measured where errors are: over the footprint mask of the G-buffer at this light.
    const PathTracer gbufferTracer(moved, accel, Estimator::NEE, 1);
    const FootprintMask mask =
        footprintMask(buildGBuffer(gbufferTracer, RecordLayout::forScene(scene), key.lightPosition, key.width, key.height));

    RenderOptions ro;
    ro.width = key.width;
    ro.height = key.height;
    ro.estimator = key.estimator;
    ro.maxDepth = key.maxDepth;
    ro.seed = key.seed;
    ro.samplesPerPass = std::max(1, target.sppPerPass);
    ro.keepCancelledPass = false;  // the saved sums must end on a pass boundary to resume bit-identically

    const std::optional<StoredReference> stored = find(key);
    RenderState state;
    if (stored) state = decodeState((fs::path(stored->dir) / kStateFile).string(), key.width, key.height);
    Reference current = stored ? referenceOf(state, key.lightPosition) : Reference();
    ReferenceNoise noise = stored ? referenceNoise(current, mask) : ReferenceNoise();
    auto wantedFor = [&](const Reference& r) {
        return target.wanted(measuredError && r.spp >= 2 ? measuredError(r) : ErrorStats::kUnknownNoise);
    };
    double wanted = stored ? wantedFor(current) : target.relativeRmse;
    if (stored && meets(globalNoise(noise), state.sppDone, wanted, target.sppCap)) {
        say(name + ": reusing the stored reference (" + std::to_string(state.sppDone) + " spp, global noise " +
            num(globalNoise(noise)) + " <= wanted " + num(wanted) + (state.sppDone >= target.sppCap ? " or spp at the cap" : "") +
            ", rendered in " + num(state.seconds) + " s) from " + stored->dir);
        if (!stored->complete) writeEntry(dir_, key, state, current, noise, true, wanted);
        return current;
    }
    if (stored)
        say(name + ": continuing the stored reference from " + std::to_string(state.sppDone) + " spp (global noise " +
            num(globalNoise(noise)) + ", wanted " + num(wanted) + ", spp cap " + std::to_string(target.sppCap) + ")");
    else
        say(name + ": rendering " + std::to_string(key.width) + "x" + std::to_string(key.height) + " to global noise " +
            num(wanted) + " (spp cap " + std::to_string(target.sppCap) + ") into " + (fs::path(dir_) / key.id()).string());

    ro.spp = std::max(target.sppCap, state.sppDone);
    Renderer renderer(moved, accel, ro);
    if (stored) renderer.restoreState(state);
    const int startSpp = state.sppDone;
    const double startSeconds = state.seconds;
    // Cancel within a pass: a watcher forwards the flag to the renderer, which drops the cut pass.
    std::atomic<bool> done{false};
    std::thread watcher;
    if (cancel)
        watcher = std::thread([&] {
            while (!done.load()) {
                if (cancel->load()) {
                    renderer.cancel();
                    return;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
        });
    bool complete = false, cancelled = false;
    double lastSave = startSeconds;
    try {
        while (true) {
            if (cancel && cancel->load()) {
                cancelled = true;
                break;
            }
            if (!renderer.runPass()) {
                cancelled = true;
                break;
            }
            state = renderer.exportState();
            current = referenceOf(state, key.lightPosition);
            noise = referenceNoise(current, mask);
            wanted = wantedFor(current);
            const double n = globalNoise(noise);
            complete = meets(n, state.sppDone, wanted, target.sppCap);
            if (progress) {
                ReferenceProgress p;
                p.spp = state.sppDone;
                p.sppCap = target.sppCap;
                p.noise = n;
                p.target = wanted;
                p.seconds = state.seconds;
                // noise ∝ 1/√spp: the spp that reach the wanted noise, at most the cap.
                const double need =
                    complete ? double(state.sppDone)
                             : std::min(double(target.sppCap),
                                        std::isfinite(n) ? state.sppDone * (n / wanted) * (n / wanted) : double(target.sppCap));
                p.fraction = need > 0 ? std::min(1.0, state.sppDone / need) : 1.0;
                const int doneNow = state.sppDone - startSpp;
                p.etaSeconds = doneNow > 0 ? (state.seconds - startSeconds) / doneNow * std::max(0.0, need - state.sppDone) : 0.0;
                progress(p);
            }
            if (complete) break;
            if (state.seconds - lastSave > kCheckpointSeconds) {
                writeEntry(dir_, key, state, current, noise, false, wanted);
                lastSave = state.seconds;
            }
        }
    } catch (...) {
        done = true;
        if (watcher.joinable()) watcher.join();
        throw;
    }
    done = true;
    if (watcher.joinable()) watcher.join();
    if (state.sppDone == 0) {  // cancelled before the first pass ended: nothing to keep
        current.cancelled = true;
        current.lightPosition = key.lightPosition;
        say(name + ": cancelled before the first pass ended; nothing stored");
        return current;
    }
    if (cancelled) state = renderer.exportState();
    current = referenceOf(state, key.lightPosition);
    noise = referenceNoise(current, mask);
    writeEntry(dir_, key, state, current, noise, complete, wanted);
    const std::string reached = "direct " + num(noise.relativeRmse[int(Term::Direct)]) + ", indirect " +
                                num(noise.relativeRmse[int(Term::Indirect)]) + ", global " + num(globalNoise(noise));
    if (cancelled)
        say(name + ": cancelled at " + std::to_string(state.sppDone) + " spp (noise " + reached +
            "); saved, the next obtain continues from here");
    else
        say(name + ": " + std::to_string(state.sppDone) + " spp in " + num(state.seconds) + " s, relative noise " + reached +
            (globalNoise(noise) <= wanted ? " (wanted " + num(wanted) + ")" : " (spp cap reached; wanted " + num(wanted) + ")"));
    current.cancelled = cancelled;
    return current;
}

}  // namespace rrf
