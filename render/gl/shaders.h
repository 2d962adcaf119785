// The GLSL of the frame renderer's programs (docs/design/08-renderer.md), compiled by renderer.cpp.
// Sources that share a prelude (the lighting, the sky) are assembled by the functions at the end.
#pragma once

#include <string>

namespace sylva::glsl {

extern const char* const lighting_glsl;
extern const char* const bark_vs;
extern const char* const bark_tint_glsl;
extern const char* const bark_fs_body;
extern const char* const depth_fs;
extern const char* const leaf_vs;
extern const char* const leaf_fs_body;
extern const char* const leaf_depth_fs;
extern const char* const fullscreen_vs;
extern const char* const sky_glsl;
extern const char* const sky_fs_body;
extern const char* const ground_vs;
extern const char* const ground_fs_body;
extern const char* const occlusion_fs_body;
extern const char* const radial_fs;
extern const char* const march_fs_body;
extern const char* const exposure_fs;
extern const char* const composite_fs_body;
extern const char* const fallback_fs;

std::string lit_source(const char* body);
std::string sky_source(const char* body);
std::string march_source();

}  // namespace sylva::glsl
