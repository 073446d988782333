// Numbers in OBJ and MTL files (core/scene/obj_text_scan.h, issue 31): tinyobjloader reads "nan",
// "inf", 1e400, words and missing coordinates as 0 or infinity without a word; the text scan
// refuses each, naming the file, the line and the field, and counts faces of one or two vertices
// (which tinyobjloader drops) in one warning with the first one's line. Real files in a temp dir,
// read as scene shapes the way the programs read them.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/scene/obj_text_scan.h"
#include "core/scene/scene_json.h"
#include "core/util/error.h"
#include "tests/test_dirs.h"

namespace test_obj_text_scan {

using namespace rrf;
using namespace rrf::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

fs::path testDir() { return freshTestDir("rrf_obj_scan"); }

const char* const kGoodMtl = "newmtl white\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 10 8 6\n";

/// Loads a scene whose only shape is `dir`/room.obj (text `obj`) with its own materials from
/// room.mtl (text `mtl`); returns the InputError's message ("" when it loaded) and the warnings.
std::string loadRoom(const fs::path& dir, const std::string& obj, const std::string& mtl = kGoodMtl,
                     std::vector<std::string>* warnings = nullptr) {
    std::ofstream(dir / "room.obj", std::ios::binary) << obj;
    std::ofstream(dir / "room.mtl", std::ios::binary) << mtl;
    const fs::path scene = dir / "scene.json";
    std::ofstream(scene) << json{{"camera", {{"eye", {0, 0.5, 3}}, {"target", {0, 0.5, 0}}, {"fov_y", 40}}},
                                 {"shapes", {{{"type", "obj"}, {"file", "room.obj"}}}}}
                                .dump();
    try {
        const Scene s = loadScene(scene.string());
        if (warnings) *warnings = s.warnings;
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// A floor quad and a lamp quad; `vertexLine` replaces the floor's second vertex (line 3).
std::string room(const std::string& vertexLine = "v 1 0 -1") {
    return "mtllib room.mtl\nv -1 0 -1\n" + vertexLine +
           "\nv 1 0 1\nv -1 0 1\nv -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\n"
           "usemtl white\nf 1 4 3 2\nusemtl lamp\nf 5 6 7 8\n";
}

}  // namespace

TEST(ObjTextScan, VerticesThatAreNotFiniteFloatsNameTheFileLineAndField) {
    const fs::path dir = testDir();
    const std::string obj = "OBJ file '" + (dir / "room.obj").string() + "' line 3: ";
    EXPECT_EQ(loadRoom(dir, room()), "");
    const struct {
        std::string line, message;
    } cases[] = {
        {"v nan 0 -1", "v x coordinate 'nan' is not a finite number"},
        {"v 1 -inf -1", "v y coordinate '-inf' is not a finite number"},
        {"v 1 0 1e400", "v z coordinate '1e400' is beyond single precision"},
        {"v 1 0 1e39", "v z coordinate '1e39' is beyond single precision (|value| <= 3.402823e+38)"},
        {"v 1 zero -1", "v y coordinate 'zero' is not a number"},
        {"v 1 0x10 -1", "v y coordinate '0x10' is not a number"},
        {"v 1.5e 0 -1", "v x coordinate '1.5e' is not a number"},
        {"v 1 0", "v has 2 numbers, expected x y z (a missing coordinate would be read as 0)"},
        {"v 1 0 # -1", "v has 2 numbers, expected x y z"},
        {"v 1 0 -1 nan", "v value 4 'nan' is not a finite number"},
        {"vn 0 nan 1", "vn y component 'nan' is not a finite number"},
    };
    for (const auto& c : cases) {
        const std::string e = loadRoom(dir, room(c.line));
        EXPECT_TRUE(contains(e, obj + c.message)) << c.line << "\n" << e;
        EXPECT_TRUE(contains(e, "/shapes/0/file")) << e;
    }
    // What strict reading still accepts: a '+' sign, a leading dot, a trailing comment, colours, tabs.
    for (const char* line : {"v +1 0 -1", "v 1. .0 -1", "v 1 0 -1 # corner", "v 1 0 -1 0.5 0.5 0.5", "v\t1\t0\t-1"})
        EXPECT_EQ(loadRoom(dir, room(line)), "") << line;
    fs::remove_all(dir);
}

TEST(ObjTextScan, MtlNumbersNameTheFileLineMaterialAndField) {
    const fs::path dir = testDir();
    const std::string mtl = "MTL file '" + (dir / "room.mtl").string() + "' line ";
    const struct {
        std::string text, message;
    } cases[] = {
        {"newmtl white\nKd nan 0.8 0.8\n", "2: material 'white': Kd 'nan' is not a finite number"},
        {"newmtl white\nKd 0.8 0.8 0.8\nKs 0.1 -0.1 0.1\n", "3: material 'white': Ks must be >= 0, but its green component is -0.1"},
        {"newmtl white\nKd 0.8\n", "2: material 'white': Kd has 1 number, expected 3 (r g b; a missing component would be read as 0)"},
        {"newmtl white\nKd spectral white.rfl\n", "2: material 'white': Kd 'spectral' is not a number (spectral and xyz colours are not supported)"},
        {"newmtl white\nKd 1 1 1\nNs 1e7\n", "3: material 'white': Ns (Phong exponent) must lie in [0, 1000000], got 1e+07"},
        {"newmtl white\nNs inf\n", "2: material 'white': Ns 'inf' is not a finite number"},
        {std::string(kGoodMtl) + "Ke 10 8 inf\n", "6: material 'lamp': Ke 'inf' is not a finite number"},
        {std::string(kGoodMtl) + "Ke 2e10 8 6\n", "6: material 'lamp': Ke must lie in [0, 1e+10]"},
    };
    for (const auto& c : cases) {
        const std::string e = loadRoom(dir, room(), c.text);
        EXPECT_TRUE(contains(e, mtl + c.message)) << c.text << "\n" << e;
    }
    // The fields the scene does not read are not checked.
    EXPECT_EQ(loadRoom(dir, room(), std::string(kGoodMtl) + "Ni nan\nd abc\nmap_Kd tex.png\n"), "");
    fs::remove_all(dir);
}

TEST(ObjTextScan, DegenerateFacesWarnWithTheirCountAndFirstLine) {
    const fs::path dir = testDir();
    std::vector<std::string> warnings;
    // Lines 14 and 16: a face of two vertices and one of one; tinyobjloader skips both.
    const std::string obj = room() + "f 1 2\nusemtl white\nf 3\n";
    ASSERT_EQ(loadRoom(dir, obj, kGoodMtl, &warnings), "");
    std::string all;
    for (const std::string& w : warnings) all += w + "\n";
    EXPECT_TRUE(contains(all, "OBJ file '" + (dir / "room.obj").string() +
                                  "': skipped 2 faces with fewer than 3 vertices (the first on line 14)"))
        << all;
    EXPECT_FALSE(contains(all, "Degenerated face")) << "no raw parser text: " << all;
    // Without such faces, no such warning.
    ASSERT_EQ(loadRoom(dir, room(), kGoodMtl, &warnings), "");
    for (const std::string& w : warnings) EXPECT_FALSE(contains(w, "fewer than 3 vertices")) << w;
    fs::remove_all(dir);
}

TEST(ObjTextScan, LinesEndAtCrLfOrALoneCrAsTinyobjloaderSplitsThem) {
    const fs::path dir = testDir();
    // The third line holds the NaN whether lines end in "\r\n" or in a lone "\r" (old Mac files),
    // which tinyobjloader splits too: a "\n"-only reader would read it all as line 1 and miss it.
    for (const std::string eol : {"\r\n", "\r"}) {
        std::string obj = room("v nan 0 -1");
        for (size_t at = obj.find('\n'); at != std::string::npos; at = obj.find('\n', at + eol.size())) obj.replace(at, 1, eol);
        const std::string e = loadRoom(dir, obj);
        EXPECT_TRUE(contains(e, "room.obj' line 3: v x coordinate 'nan'")) << e;
    }
    fs::remove_all(dir);
}

TEST(ObjTextScan, ScanAloneReportsLibrariesMaterialsAndFaces) {
    const fs::path dir = testDir();
    std::ofstream(dir / "a.obj") << "mtllib my\\ lib.mtl other.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl  red \nf 1 2\nf 1 2 3\nf -3 -2 -1\n";
    const ObjTextScan scan = scanObjText((dir / "a.obj").string(), {"scene.json", "/shapes/0/file"});
    ASSERT_EQ(scan.mtllibs.size(), 1u);
    EXPECT_EQ(scan.mtllibs[0].names, (std::vector<std::string>{"my lib.mtl", "other.mtl"}));
    ASSERT_EQ(scan.usemtls.size(), 1u);
    EXPECT_EQ(scan.usemtls[0].name, "red");
    EXPECT_EQ(scan.usemtls[0].line, 5u);
    EXPECT_EQ(scan.degenerateFaces, 1u);
    EXPECT_EQ(scan.firstDegenerateLine, 6u);
    fs::remove_all(dir);
}

}  // namespace test_obj_text_scan
