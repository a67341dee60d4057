#pragma once
// Argument checks shared by every public entry point; all throw weft::InvalidArgument.
#include <string>

#include <glm/glm.hpp>

namespace weft {

void requireFinite(float value, const char* what);
void requireFinite(const glm::vec3& value, const char* what);
void requireFinite(const glm::mat4& value, const char* what);
void requireNonNegative(const glm::vec3& value, const char* what);
void requirePositive(float value, const char* what);
/// Finite and invertible (|det| above a tolerance relative to the scale).
void requireInvertible(const glm::mat4& value, const char* what);

} // namespace weft
