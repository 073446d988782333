#pragma once
/// A line scan of OBJ and MTL text beside tinyobjloader (core/scene/obj_loader.cpp), for what that
/// parser passes over in silence: it reads "nan", "inf", "1e400", "abc" or a missing coordinate
/// as 0 (or as infinity), reports no line number for bad face indices or unknown materials, and
/// drops faces of one or two corners with a message of its own ("Degenerated face found").
///
/// The scan reads the numbers the scene uses the way a strict reader would: every token of a `v`
/// or `vn` line up to a `#` comment must be a number representable as a finite float (3 or more
/// on `v`: x y z and an optional w or r g b; 3 or more on `vn`), and in an MTL file `Kd`, `Ks`,
/// `Ke` need 3 finite, non-negative numbers (tinyobjloader would read the spec's one-number form
/// `Kd 0.8` as red), `Ke` at most kMaxRadiance and `Ns` one number in [0, kMaxPhongExponent]
/// (core/scene/radiometric_range.h). Texture coordinates and the MTL fields the scene does not use
/// (Ka, Tf, Ni, d, illum, maps) are not read by the scene and not checked. Lines end at "\n",
/// "\r\n" or a lone "\r", as tinyobjloader splits them, so line numbers agree with its own.

#include <cstddef>
#include <string>
#include <vector>

namespace rrf {

/// Where scan errors are reported: InputError(sceneFile, where, ...) with the OBJ or MTL file and
/// line in the text, so a message points at the scene entry that named the OBJ file as well.
struct ObjScanContext {
    std::string sceneFile;
    std::string where;
};

/// What the OBJ scan found that tinyobjloader reports without a line.
struct ObjTextScan {
    /// A statement and its line: `usemtl` with the material's name.
    struct Named {
        size_t line;
        std::string name;
    };
    /// An `mtllib` line with its file names as tinyobjloader splits them (a space separates, a
    /// backslash escapes the next character); tinyobjloader loads the first one it can open.
    struct Library {
        size_t line;
        std::vector<std::string> names;
    };
    std::vector<Library> mtllibs;
    std::vector<Named> usemtls;
    size_t degenerateFaces = 0;       ///< `f` lines with fewer than 3 corners (skipped)
    size_t firstDegenerateLine = 0;   ///< the first of them (0 = none)
};

/// Scans the OBJ file `path`. Throws InputError (ctx) naming the OBJ file, the line and the field
/// for a `v`/`vn` number that is not a finite float or a missing coordinate, and for a face corner
/// whose position or normal index is out of range (1 … count, or −count … −1 relative to the
/// vertices so far; an index may not name a vertex defined later, as tinyobjloader resolves
/// relative indices as it reads).
ObjTextScan scanObjText(const std::string& path, const ObjScanContext& ctx);

/// Scans the MTL file `path` (Kd, Ks, Ke, Ns of each `newmtl`). Throws InputError (ctx) naming the
/// MTL file, the line, the material and the field for a value that is not a finite float, is
/// negative, has fewer than 3 components or lies outside the radiometric range.
void scanMtlText(const std::string& path, const ObjScanContext& ctx);

}  // namespace rrf
