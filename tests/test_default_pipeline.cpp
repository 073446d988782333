// The bundled project's defaults, end to end at quick sizes (issue 11): the Cornell box with the
// project's network and trainer defaults (32-16 indirect networks, Adam with relative L2, kd-tree
// partition with the split-gain rule) and exact direct light, trained on a small grid, predicted at a
// held-out light and compared with a path-traced reference. The bound was measured (see below) and
// carries a margin; a pipeline that learns nothing from the light position fails it.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/pipeline/experiment.h"
#include "core/eval/held_out.h"
#include "core/project/project.h"
#include "core/project/project_file.h"

namespace test_default_pipeline {

using namespace rrf;

namespace {

struct Quick {
    double global = 0;    ///< global relative RMSE with the reference's noise subtracted
    double indirect = 0;  ///< the same for the indirect term, the one the networks learn
    double floor = 0;     ///< the reference's own relative noise (global)
};

Quick runQuick(const Project& p, bool decorrelateLight) {
    const Scene& scene = p.scene;
    SamplingSettings s = p.samplingOrDefault();
    s.nx = s.ny = s.nz = 5;  // rrf pipeline --quick's grid and directions
    s.directions = 150;
    s.spp = s.maxSpp = 128;  // fixed, clean-enough targets: the bound does not move with the adaptive sampler
    ObjectTrainingOptions o = p.trainingOptions();
    o.trainer.adam.maxEpochs = 150;
    const RecordLayout layout = RecordLayout::forScene(scene);
    const GeneratedData data = DataGenerator(scene, s).run();
    std::vector<ObjectSamples> samples = samplesFromGenerated(data, scene, layout);
    if (decorrelateLight)  // the light columns of each record get another record's light position
        for (ObjectSamples& obj : samples)
            for (size_t i = 0; i + 1 < obj.size(); i += 2)
                for (size_t c = 6; c < 9; ++c)
                    std::swap(obj.inputs[i * size_t(obj.numInputs) + c], obj.inputs[(i + 1) * size_t(obj.numInputs) + c]);
    const ModelSet models = modelSetFromTrained(trainObjects(samples, o), scene, layout);
    const Predictor predictor(scene, models, p.prediction);
    RenderOptions ro;
    ro.width = ro.height = 48;
    ro.spp = 1024;
    ro.seed = 77;
    const Vec3 light = heldOutLightPositions(scene.lightRange(), 1, 3).front();
    const Evaluation ev = evaluate(predictor, renderReference(scene, light, ro));
    const ErrorStats& g = ev.term(Term::Global).overall;
    return {g.relativeRmseCorrected, ev.term(Term::Indirect).overall.relativeRmseCorrected, g.relativeRmseNoiseFloor};
}

}  // namespace

TEST(DefaultPipeline, QuickRunOfTheProjectDefaultsStaysWithinItsMeasuredBound) {
    const Project p = loadProjectOrScene(RRF_SOURCE_DIR "/projects/cornell-box/project.json");
    ASSERT_EQ(p.prediction.direct, PredictionSettings::Direct::Exact) << "the default predicts direct light exactly";
    ASSERT_EQ(p.networkOrDefault().options.targets, TargetMode::Indirect);
    const Quick good = runQuick(p, false);
    const Quick broken = runQuick(p, true);
    std::printf("quick defaults: relative RMSE corrected global %.4f, indirect %.4f (reference noise %.4f); "
                "light input decorrelated: indirect %.4f\n",
                good.global, good.indirect, good.floor, broken.indirect);
    ASSERT_TRUE(std::isfinite(good.global) && std::isfinite(good.indirect));
    // Measured (deterministic): global 0.149, indirect 0.173; decorrelated indirect 0.218. At these
    // sizes (15 000 records, 150 epochs) the indirect term is far from the full defaults' 0.036 (the
    // 32-16 network has too few records per weight here; the report's 20-10 gave 0.159); the bounds
    // keep ~25 % margin and the decorrelated run must be clearly worse.
    EXPECT_LT(good.global, 0.19);
    EXPECT_LT(good.indirect, 0.22);
    EXPECT_GT(broken.indirect, 1.15 * good.indirect);
}

}  // namespace test_default_pipeline
