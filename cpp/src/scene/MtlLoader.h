#pragma once
// Wavefront material libraries (.mtl) as weft Materials, for loadObjParts.
#include <string>
#include <unordered_map>

#include <weft/Material.h>

namespace weft {

/// The materials of an .mtl file by name: Kd -> kd, Ks -> ks, Ns -> shininess (clamped to
/// >= 1), map_Kd -> texture (a PNG relative to the .mtl, sRGB; its options such as -s or -o are
/// skipped). Other statements are ignored. Throws IoError naming the file and line for a
/// missing file, malformed numbers or a missing texture.
std::unordered_map<std::string, Material> loadMtl(const std::string& path);

} // namespace weft
