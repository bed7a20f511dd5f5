#pragma once
// A small reader of Wavefront OBJ meshes for predefined surfaces: v, vt, vn and f lines
// (v, v/vt, v//vn, v/vt/vn corners, negative indices counting back), polygons
// triangulated as fans. Other statements (o, g, s, usemtl, mtllib, l, comments) are
// skipped. Normals are checked but not kept: placed and blended surfaces get smooth
// normals from their shape (surface.h). A texture coordinate is kept per position when
// every corner naming the position names the same one.

#include <filesystem>
#include <istream>
#include <string>

#include "interpreters/geometry/surface.h"

namespace ontogen {

/// Reads an OBJ text; name prefixes error messages ("name:line: ..."). Throws
/// SurfaceError on malformed numbers, indices out of range, faces of fewer than 3
/// corners, or a text without faces.
Surface readObjSurface(std::istream& in, const std::string& name);

/// Reads the OBJ file at path; throws SurfaceError when it cannot be opened or read.
Surface loadObjSurface(const std::filesystem::path& path);

}  // namespace ontogen
