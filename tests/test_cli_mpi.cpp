// `mpirun -n 3 rrf generate|train|evaluate|sweep|pipeline` on localhost against the single-process
// run (issue 17): the dataset byte for byte, the model set's weights (of raw inputs, and with a hash
// grid's tables) and trees bit for bit (the files' timing fields differ, as between two
// single-process runs), the evaluation's images byte for byte and its report but for times, a
// sweep's CSV and JSON but for times, a pipeline's every output, and a failing rank (all of them,
// or only one before any collective call) ends the job with its message.
// Compiled only when rrf is built with MPI (CMake sets RRF_MPIEXEC to the launcher).
#ifdef RRF_MPIEXEC

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>
#include <string>

#include <unistd.h>

#include "core/nn/model_set.h"
#include "core/util/json_reader.h"
#include "tests/cli_runner.h"

namespace test_cli_mpi {

using namespace rrf;
using namespace rrf::test;
namespace fs = std::filesystem;

const std::string kCornell = std::string(RRF_SOURCE_DIR) + "/projects/cornell-box/project.json";
/// A small run: 64 cells × 30 directions × 4 paths, small networks for a few epochs.
const std::string kSampling = " --grid 4,4,4 --dirs 30 --spp 4 --seed 3";
/// The same data for sweep and pipeline, whose --spp and --seed mean the renders'.
const std::string kExperiment = " --grid 4,4,4 --dirs 30 --data-spp 4";
const std::string kNetwork = " --hidden 6 --trainer adam --epochs 12 --log-every 0";

/// `rrf <args>` under `mpirun -n <ranks>` on this host: oversubscribed (CI has 2 cores), unbound (each
/// rank runs its own threads), over shared memory, and allowed as root (CI's containers run as root).
/// With `perRank`, each rank runs `sh -c 'rrf <args>'`, so $OMPI_COMM_WORLD_RANK in `args` names
/// that rank's files. The job is killed after a minute, so a hang fails the test (status 124).
CliResult runMpi(int ranks, const std::string& args, bool perRank = false) {
    const std::string env = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                            "OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_btl=self,vader ";
    const std::string rrf = std::string(RRF_CLI_PATH) + " " + args;
    const std::string cmd = env + "timeout -k 5 60 " + RRF_MPIEXEC + std::string(" --oversubscribe --bind-to none -n ") +
                            std::to_string(ranks) + " " + (perRank ? "sh -c '" + rrf + "'" : rrf) + " 2>&1";
    return rrf::test::runShell(cmd);
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path testDir() {
    const fs::path dir = fs::temp_directory_path() / ("rrf_mpi_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// An evaluation report without what times the run (keys ending in "seconds") and without where each
/// reference came from (rendered by this process, or reused from the store after another rank rendered it).
nlohmann::json withoutTimesAndSources(nlohmann::json j) {
    if (j.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (auto& [key, value] : j.items()) {
            const bool timed = key.size() >= 7 && key.compare(key.size() - 7, 7, "seconds") == 0;
            if (!timed && key != "reference_source") out[key] = withoutTimesAndSources(value);
        }
        return out;
    }
    if (j.is_array())
        for (auto& value : j) value = withoutTimesAndSources(value);
    return j;
}

/// A fresh copy of the bundled Cornell box in `dir` (its reference store starts empty).
std::string copyProject(const fs::path& dir) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* f : {"project.json", "scene.json"})
        fs::copy_file(fs::path(RRF_SOURCE_DIR) / "projects" / "cornell-box" / f, dir / f);
    return (dir / "project.json").string();
}

/// models.json without the fields that time the run: "seconds", and the model files' sizes and
/// checksums, which cover the per-epoch times in their headers (the weights are compared apart).
nlohmann::json withoutTimes(nlohmann::json j) {
    if (j.is_object()) {
        for (const char* key : {"seconds", "bytes", "checksum64", "index_checksum64"}) j.erase(key);
        for (auto& [key, value] : j.items()) value = withoutTimes(value);
    } else if (j.is_array()) {
        for (auto& value : j) value = withoutTimes(value);
    }
    return j;
}

/// The model sets in directories `a` and `b` hold the same networks: the index but for times, and
/// every leaf's weights and encoding parameters bit for bit (`encoded`: the encoding has some).
void expectSameModels(const std::string& a, const std::string& b, bool encoded) {
    const ModelSet s1 = loadModelSet(a), s3 = loadModelSet(b);
    EXPECT_EQ(withoutTimes(readJsonFile(a + "/models.json")).dump(), withoutTimes(readJsonFile(b + "/models.json")).dump());
    ASSERT_EQ(s1.objects.size(), s3.objects.size());
    ASSERT_GT(s1.objects.size(), 2u);
    auto same = [](const VecX<double>& p, const VecX<double>& q) {
        return p.size() == q.size() && std::memcmp(p.data(), q.data(), size_t(p.size()) * sizeof(double)) == 0;
    };
    for (size_t i = 0; i < s1.objects.size(); ++i) {
        for (const auto& [target, net] : s1.objects[i].byTarget) {
            ASSERT_TRUE(s3.objects[i].has(target));
            const PartitionedNetwork& other = s3.objects[i].byTarget.at(target);
            ASSERT_EQ(net.leafCount(), other.leafCount());
            for (int l = 0; l < net.leafCount(); ++l) {
                const NetworkModel &x = net.leaves[size_t(l)], &y = other.leaves[size_t(l)];
                const std::string where = "object " + std::to_string(s1.objects[i].objectId) + " " + target + " leaf " +
                                          std::to_string(l);
                EXPECT_TRUE(same(x.params, y.params)) << where;
                EXPECT_EQ(x.encodingParams.size() > 0, encoded) << where;
                EXPECT_TRUE(same(x.encodingParams, y.encodingParams)) << where;
            }
        }
    }
}

/// A CSV without its timing columns (names holding "seconds": stage times, one-off and frame times,
/// break-even seconds, the curves' times), one string per line.
std::vector<std::string> csvWithoutTimes(const std::string& text) {
    std::vector<std::vector<std::string>> cells;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> row;
        // Quoted settings ("4,4,4") hold commas: split outside quotes only.
        std::string cell;
        bool quoted = false;
        for (char ch : line) {
            if (ch == '"') quoted = !quoted;
            if (ch == ',' && !quoted) {
                row.push_back(cell);
                cell.clear();
            } else {
                cell += ch;
            }
        }
        row.push_back(cell);
        cells.push_back(row);
    }
    std::vector<std::string> out;
    if (cells.empty()) return out;
    for (const std::vector<std::string>& row : cells) {
        std::string kept;
        for (size_t c = 0; c < row.size() && c < cells[0].size(); ++c)
            if (cells[0][c].find("seconds") == std::string::npos) kept += row[c] + ",";
        out.push_back(kept);
    }
    return out;
}

TEST(CliMpi, ThreeRanksGenerateTrainAndEvaluateWhatOneProcessDoes) {
    const fs::path dir = testDir();
    const std::string one = (dir / "one.rrfd").string(), three = (dir / "three.rrfd").string();
    const CliResult g1 = runCli("generate " + kCornell + kSampling + " --out " + one);
    ASSERT_EQ(g1.code, 0) << g1.output;
    const CliResult g3 = runMpi(3, "generate " + kCornell + kSampling + " --out " + three);
    ASSERT_EQ(g3.code, 0) << g3.output;
    // Every rank logs its share of the cells; the shares tile the 64 cells.
    EXPECT_NE(g3.output.find("rank 0/3: cells 0-"), std::string::npos) << g3.output;
    EXPECT_NE(g3.output.find("rank 1/3: cells "), std::string::npos) << g3.output;
    EXPECT_NE(g3.output.find("-63 of 64"), std::string::npos) << g3.output;
    const std::string a = readBytes(one), b = readBytes(three);
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the 3-rank dataset differs from the single-process one";

    const std::string m1 = (dir / "m1").string(), m3 = (dir / "m3").string();
    const CliResult t1 = runCli("train " + kCornell + " --data " + one + kNetwork + " --out " + m1);
    ASSERT_EQ(t1.code, 0) << t1.output;
    const CliResult t3 = runMpi(3, "train " + kCornell + " --data " + one + kNetwork + " --out " + m3);
    ASSERT_EQ(t3.code, 0) << t3.output;
    EXPECT_NE(t3.output.find("rank 2/3: objects "), std::string::npos) << t3.output;
    expectSameModels(m1, m3, false);
    // A trainable encoding: the hash grid's tables travel with the networks and join bit for bit too.
    const std::string h1 = (dir / "h1").string(), h3 = (dir / "h3").string();
    const std::string hashGrid = " --hidden 6 --trainer adam --epochs 2 --log-every 0 --encoding hash_grid";
    const CliResult th1 = runCli("train " + kCornell + " --data " + one + hashGrid + " --out " + h1);
    ASSERT_EQ(th1.code, 0) << th1.output;
    const CliResult th3 = runMpi(3, "train " + kCornell + " --data " + one + hashGrid + " --out " + h3);
    ASSERT_EQ(th3.code, 0) << th3.output;
    expectSameModels(h1, h3, true);

    // Evaluate at 3 held-out lights: the ranks render the references into the project's store, rank 0
    // evaluates. Same project and output paths for both runs, so the reports differ only in times.
    const std::string eval = " --models " + m1 + " --held-out 3 --noise 0.3 --spp-cap 8 --width 24 --height 24 --out " +
                             (dir / "e").string();
    const std::string project = copyProject(dir / "p");
    const CliResult e1 = runCli("evaluate " + project + eval);
    ASSERT_EQ(e1.code, 0) << e1.output;
    fs::rename(dir / "e", dir / "e1");
    copyProject(dir / "p");
    const CliResult e3 = runMpi(3, "evaluate " + project + eval);
    ASSERT_EQ(e3.code, 0) << e3.output;
    EXPECT_NE(e3.output.find("rank 1/3: references 2 of 3"), std::string::npos) << e3.output;
    auto json = [](const fs::path& f) { return withoutTimesAndSources(nlohmann::json::parse(readBytes(f.string()))); };
    EXPECT_EQ(json(dir / "e1" / "held_out.json").dump(), json(dir / "e" / "held_out.json").dump());
    for (const char* image : {"light_0/reference_global.exr", "light_2/prediction_global.exr", "light_1/error_relative_global.exr"}) {
        const std::string x = readBytes((dir / "e1" / image).string()), y = readBytes((dir / "e" / image).string());
        EXPECT_FALSE(x.empty()) << image;
        EXPECT_TRUE(x == y) << image;
    }
    fs::remove_all(dir);
}

TEST(CliMpi, ThreeRanksSweepWhatOneProcessDoes) {
    const fs::path dir = testDir();
    // A trainer sweep: the reference from the project's store (rank 0 obtains it and sends it), one
    // dataset for both points (generated split by cells, sent to every rank), the path tracer's series
    // and the two points as tasks on the ranks. Same project and output paths for both runs.
    const std::string project = copyProject(dir / "p");
    const std::string sweep = "sweep " + project + " --what trainer --values lm adam --width 20 --height 16 --noise 0.3 "
                              "--spp-cap 8" + kExperiment + " --hidden 6 --epochs 6 --out " + (dir / "s").string();
    const CliResult s1 = runCli(sweep);
    ASSERT_EQ(s1.code, 0) << s1.output;
    fs::rename(dir / "s", dir / "s1");
    copyProject(dir / "p");
    const CliResult s3 = runMpi(3, sweep);
    ASSERT_EQ(s3.code, 0) << s3.output;
    // Every rank logs its share: the series and each point on one rank.
    for (const char* share : {"rank 0/3: sweep ", "rank 1/3: sweep ", "rank 2/3: sweep ", "the path tracer's series", "(adam)"})
        EXPECT_NE(s3.output.find(share), std::string::npos) << share << "\n" << s3.output;
    for (const char* f : {"sweep_trainer.csv", "sweep_trainer_curves.csv"}) {
        const std::vector<std::string> a = csvWithoutTimes(readBytes((dir / "s1" / f).string()));
        EXPECT_GT(a.size(), 2u) << f;
        EXPECT_EQ(a, csvWithoutTimes(readBytes((dir / "s" / f).string()))) << f;
    }
    auto json = [](const fs::path& f) { return withoutTimesAndSources(nlohmann::json::parse(readBytes(f.string()))); };
    EXPECT_EQ(json(dir / "s1" / "sweep_trainer.json").dump(), json(dir / "s" / "sweep_trainer.json").dump());
    fs::remove_all(dir);
}

TEST(CliMpi, RanksWithOtherThreadCountsShareTheSweepAlike) {
    const fs::path dir = testDir();
    // Rank 0 estimates with 1 thread, rank 1 with 64: the training estimate divides by
    // min(threads, networks), the series' by the threads, so ranks estimating apart would order the
    // tasks differently and the join would miss one. Rank 0's estimates are sent to both. The fixed-spp
    // reference is rendered split by rows and joined into one process's, bit for bit.
    const std::string project = copyProject(dir / "p");
    const std::string sweep = "sweep " + project + " --what trainer --values lm adam --width 20 --height 16 --reference-spp 4" +
                              kExperiment + " --hidden 6 --epochs 4 --out " + (dir / "s").string();
    const CliResult s1 = runCli(sweep + " --threads 1");
    ASSERT_EQ(s1.code, 0) << s1.output;
    fs::rename(dir / "s", dir / "s1");
    const CliResult r = runMpi(2, sweep + " --threads $((1 + 63 * OMPI_COMM_WORLD_RANK))", true);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("rank 1/2: reference rows y mod 2 = 1 (8 of 16 rows"), std::string::npos) << r.output;
    // Each task on exactly one rank: both ranks quote the same total, and every task is logged once.
    std::vector<std::string> totals;
    for (const char* rank : {"rank 0/2: sweep ", "rank 1/2: sweep "}) {
        const size_t at = r.output.find(rank);
        ASSERT_NE(at, std::string::npos) << rank << "\n" << r.output;
        const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
        totals.push_back(line.substr(line.find("of the estimated")));
    }
    EXPECT_EQ(totals[0], totals[1]) << r.output;
    for (const char* task : {"the path tracer's series", "1 (lm)", "2 (adam)"}) {
        const size_t first = r.output.find(task);
        EXPECT_NE(first, std::string::npos) << task << "\n" << r.output;
        EXPECT_EQ(r.output.find(task, first + 1), std::string::npos) << task << "\n" << r.output;
    }
    const std::vector<std::string> a = csvWithoutTimes(readBytes((dir / "s1" / "sweep_trainer.csv").string()));
    EXPECT_GT(a.size(), 2u);
    EXPECT_EQ(a, csvWithoutTimes(readBytes((dir / "s" / "sweep_trainer.csv").string())));
    fs::remove_all(dir);
}

TEST(CliMpi, ThreeRanksPipelineWhatOneProcessDoes) {
    const fs::path dir = testDir();
    // Ground truth by interleaved rows, data by cells, networks by objects, held-out references by
    // lights; rank 0 writes every file. Same project and output paths for both runs.
    const std::string project = copyProject(dir / "p");
    const std::string pipeline = "pipeline " + project + " --width 20 --height 16 --spp 8 --held-out 2 --noise 0.3 "
                                 "--spp-cap 8" + kExperiment + " --hidden 6 --trainer adam --epochs 8 --out " + (dir / "o").string();
    const CliResult p1 = runCli(pipeline);
    ASSERT_EQ(p1.code, 0) << p1.output;
    fs::rename(dir / "o", dir / "o1");
    copyProject(dir / "p");
    const CliResult p3 = runMpi(3, pipeline);
    ASSERT_EQ(p3.code, 0) << p3.output;
    for (const char* share : {"rank 2/3: ground truth rows y mod 3 = 2 (5 of 16 rows", "rank 1/3: cells ", "rank 0/3: objects ",
                              "rank 1/3: references 2 of 2"})
        EXPECT_NE(p3.output.find(share), std::string::npos) << share << "\n" << p3.output;
    for (const char* f : {"dataset.rrfd", "ground_truth/global.exr", "ground_truth/variance_indirect.exr",
                          "evaluation/prediction_global.exr", "held_out/light_1/reference_global.exr",
                          "held_out/light_0/error_relative_global.exr"}) {
        const std::string x = readBytes((dir / "o1" / f).string()), y = readBytes((dir / "o" / f).string());
        EXPECT_FALSE(x.empty()) << f;
        EXPECT_TRUE(x == y) << f;
    }
    expectSameModels((dir / "o1" / "models").string(), (dir / "o" / "models").string(), false);
    auto json = [](const fs::path& f) { return withoutTimesAndSources(nlohmann::json::parse(readBytes(f.string()))); };
    for (const char* f : {"evaluation/evaluation.json", "held_out/held_out.json", "ground_truth/render.json"})
        EXPECT_EQ(json(dir / "o1" / f).dump(), json(dir / "o" / f).dump()) << f;
    fs::remove_all(dir);
}

TEST(CliMpi, AFailingRankStopsTheJobWithItsMessage) {
    const fs::path dir = testDir();
    // A dataset file that does not exist: every rank fails while loading; the job ends (no hang)
    // with the message and a non-zero status.
    const CliResult r = runMpi(2, "train " + kCornell + " --data " + (dir / "missing.rrfd").string() + " --out " +
                                      (dir / "m").string());
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("missing.rrfd"), std::string::npos) << r.output;
    // Only rank 1 fails, before any collective call (its project file does not exist); ranks 0 and 2
    // read theirs and go on. Rank 1 ends the job through MPI_Abort with its message, so the others
    // do not wait for it (under srun a rank that merely exits would leave them waiting).
    for (const char* r : {"0", "2"}) copyProject(dir / ("in" + std::string(r)));
    const CliResult one = runMpi(3, "generate " + (dir / "in$OMPI_COMM_WORLD_RANK" / "project.json").string() + kSampling +
                                        " --out " + (dir / "d$OMPI_COMM_WORLD_RANK.rrfd").string(), true);
    EXPECT_NE(one.code, 0) << one.output;
    EXPECT_NE(one.code, 124) << "the job hung\n" << one.output;
    EXPECT_NE(one.output.find("rrf: error (rank 1/3)"), std::string::npos) << one.output;
    EXPECT_NE(one.output.find("in1/project.json"), std::string::npos) << one.output;
    // Through MPI_Abort, not a plain exit: mpirun then reports "MPI_ABORT was invoked on rank 1" and
    // never its "exited with non-zero status" / "without calling init" lines. Open MPI 4.1's help
    // printer sometimes loses the abort banner ("ORTE_ERROR_LOG: Data unpack would read past end of
    // buffer"), so the test asks for the absence of the plain-exit lines, which it never prints then.
    EXPECT_EQ(one.output.find("non-zero status"), std::string::npos) << one.output;
    EXPECT_EQ(one.output.find("without calling"), std::string::npos) << one.output;
    EXPECT_FALSE(fs::exists(dir / "d0.rrfd"));
    // A command that does not split its work refuses to run N times over.
    const CliResult render = runMpi(2, "render " + kCornell + " --out " + (dir / "r").string());
    EXPECT_EQ(render.code, 2) << render.output;
    EXPECT_NE(render.output.find("does not split its work across MPI ranks"), std::string::npos) << render.output;
    fs::remove_all(dir);
}

}  // namespace test_cli_mpi

#endif  // RRF_MPIEXEC
