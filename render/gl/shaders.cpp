// The GLSL of the frame renderer's programs (shaders.h).
#include "render/gl/shaders.h"

#include "render/assets/textures.h"

namespace sylva::glsl {


// Shared lighting: sun + hemispheric ambient, shadow lookups with normal offset and PCF.
const char* const lighting_glsl = R"(
uniform vec3 u_sun_dir; uniform vec3 u_sun_light; uniform vec3 u_sh[4];
uniform sampler2DShadow u_shadow; uniform mat4 u_light_viewproj; uniform int u_shadows; uniform int u_pcf;
uniform float u_bias; uniform float u_normal_offset; uniform float u_shadow_texel;
const vec2 poisson16[16] = vec2[](
  vec2(-0.94201624,-0.39906216), vec2(0.94558609,-0.76890725), vec2(-0.09418410,-0.92938870), vec2(0.34495938,0.29387760),
  vec2(-0.91588581,0.45771432), vec2(-0.81544232,-0.87912464), vec2(-0.38277543,0.27676845), vec2(0.97484398,0.75648379),
  vec2(0.44323325,-0.97511554), vec2(0.53742981,-0.47373420), vec2(-0.26496911,-0.41893023), vec2(0.79197514,0.19090188),
  vec2(-0.24188840,0.99706507), vec2(-0.81409955,0.91437590), vec2(0.19984126,0.78641367), vec2(0.14383161,-0.14100790));
float shadow_at(vec3 world, vec3 n) {
  if (u_shadows == 0) return 1.0;
  // Normal offset (seed 001: acne vs peter-panning): move the lookup off the surface, more at grazing light.
  float ndl = clamp(dot(n, u_sun_dir), -1.0, 1.0);
  vec3 p = world + n * (u_normal_offset * u_shadow_texel * sqrt(1.0 - ndl * ndl));
  vec4 c = u_light_viewproj * vec4(p, 1.0);
  vec3 s = c.xyz / c.w * 0.5 + 0.5;
  if (s.x < 0.0 || s.y < 0.0 || s.x > 1.0 || s.y > 1.0 || s.z > 1.0) return 1.0;  // outside the map: lit
  float ref = s.z - u_bias;
  vec2 texel = vec2(1.0 / float(textureSize(u_shadow, 0).x));
  float sum = 0.0, count = 0.0;
  if (u_pcf == 2) {
    for (int i = 0; i < 16; ++i) { sum += texture(u_shadow, vec3(s.xy + poisson16[i] * 2.5 * texel, ref)); count += 1.0; }
  } else {
    int k = u_pcf == 0 ? 1 : 2;
    for (int y = -k; y <= k; ++y)
      for (int x = -k; x <= k; ++x) { sum += texture(u_shadow, vec3(s.xy + vec2(x, y) * texel, ref)); count += 1.0; }
  }
  return sum / count;
}
// Sky light: irradiance / pi from the sky's first two SH bands (render/gl/sky.h; Ramamoorthi & Hanrahan 2001).
vec3 ambient_light(vec3 n) {
  return max(u_sh[0] + u_sh[1] * n.x + u_sh[2] * n.y + u_sh[3] * n.z, vec3(0.0));
}
)";

const char* const bark_vs = R"(#version 330 core
layout(location = 0) in vec3 a_position; layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv; layout(location = 3) in uint a_node; layout(location = 4) in float a_ao;
uniform mat4 u_viewproj; uniform samplerBuffer u_radius;
out vec3 v_world; out vec3 v_normal; out vec2 v_uv; out float v_alive; out float v_ao; out float v_height;
void main() {
  v_height = a_position.y;   // above the ground, at rest: the bark tint's blend (render/mesh/bark_tint.h)
  // Per node: (where the wood pass had the node at the shown step minus where the mesh has it,
  // radius at the shown step minus the radius the vertex was built with, or -1e30 when not alive)
  vec4 r = texelFetch(u_radius, int(a_node));
  v_alive = r.w > -1e29 ? 1.0 : 0.0;
  v_world = a_position + r.xyz + a_normal * (v_alive > 0.5 ? r.w : 0.0);
  // Wind (render/mesh/wind.h; a no-op while it is off): the normal turns with the sway.
  vec3 n = a_normal, t_unused = vec3(0.0), b_unused = vec3(0.0);
  v_world = wind_sway_frame(v_world, int(a_node), n, t_unused, b_unused);
  v_normal = n; v_uv = a_uv; v_ao = a_ao;
  gl_Position = u_viewproj * vec4(v_world, 1.0);
}
)";

// The bark's tint by height, shared by the viewport's bark and the impostor atlas's: the base colour
// at the ground shading to the bark colour (render/mesh/bark_tint.h, bark_tint::at). The uniforms
// are set by set_bark_tint_uniforms (render/gl/renderer_resources.h).
const char* const bark_tint_glsl = R"(
uniform vec3 u_bark_color; uniform vec3 u_bark_base_color; uniform float u_bark_base_height;
vec3 bark_tint(float y) {
  return u_bark_base_height > 0.0 ? mix(u_bark_base_color, u_bark_color, smoothstep(0.0, u_bark_base_height, y)) : u_bark_color;
}
)";

const char* const bark_fs_body = R"(
in vec3 v_world; in vec3 v_normal; in vec2 v_uv; in float v_alive; in float v_ao; in float v_height;
uniform sampler2D u_bark; uniform sampler2D u_bark_normal; uniform sampler2D u_bark_rough;
uniform vec3 u_eye;
out vec4 o_color;
// Tangent frame from screen-space derivatives (Schüler 2006), so the mesh needs no tangents.
mat3 cotangent_frame(vec3 n, vec3 p, vec2 uv) {
  vec3 dp1 = dFdx(p), dp2 = dFdy(p);
  vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
  float inv = inversesqrt(max(max(dot(t, t), dot(b, b)), 1e-30));
  return mat3(t * inv, b * inv, n);
}
void main() {
  if (v_alive < 0.999) discard;  // a triangle touching a dead or unborn node
  vec3 n0 = normalize(v_normal);
  vec3 m = texture(u_bark_normal, v_uv).xyz * 2.0 - 1.0;
  m.y = -m.y;   // the map's +Y points up the image, against increasing v
  vec3 n = normalize(cotangent_frame(n0, v_world, v_uv) * m);
  if (dot(n, n0) < 0.2) n = n0;
  // tinted_texture's formula (render/assets/textures.h): albedo = min(1, gain * tint * texel), texel linear.
  vec3 albedo = min(vec3(1.0), TINT_GAIN * bark_tint(v_height) * texture(u_bark, v_uv).rgb);
  float sh = shadow_at(v_world, n);
  float ndl = max(dot(n, u_sun_dir), 0.0);
  // A mild dielectric highlight (F0 = 0.04) from the roughness map: Blinn-Phong with the exponent
  // that matches a Beckmann lobe of width a = roughness^2, 2 / a^2 - 2 (Walter et al. 2007, §5.2),
  // normalised by (s + 8) / (8 pi) (Akenine-Moller et al., Real-Time Rendering, 3rd ed., §7.6).
  float rough = clamp(texture(u_bark_rough, v_uv).g, 0.05, 1.0);
  float a2 = rough * rough * rough * rough;
  float s = max(2.0 / a2 - 2.0, 1.0);
  vec3 h = normalize(normalize(u_eye - v_world) + u_sun_dir);
  float spec = 0.04 * (s + 8.0) / 25.1327 * pow(max(dot(n, h), 0.0), s) * ndl;
  vec3 c = albedo * (u_sun_light * ndl * sh + ambient_light(n) * v_ao) + u_sun_light * sh * spec;
  o_color = vec4(c, 1.0);
}
)";

const char* const depth_fs = R"(#version 330 core
in float v_alive;
void main() { if (v_alive < 0.999) discard; }
)";

const char* const leaf_vs = R"(#version 330 core
layout(location = 1) in vec3 i_position; layout(location = 2) in vec4 i_rotation; layout(location = 3) in float i_size;
layout(location = 4) in uvec2 i_born_died; layout(location = 5) in uint i_texture; layout(location = 6) in float i_ao;
layout(location = 7) in uint i_node;
uniform mat4 u_viewproj; uniform int u_step; uniform float u_variation; uniform float u_sun_tone; uniform int u_layers; uniform samplerBuffer u_radius;
// The coarse blade grids (render/mesh/leaf_blade.h): per archetype, then the flat card, BLADE_VERTICES
// vertices of two texels each, (position xyz, u) and (normal xyz, v), in card units.
uniform samplerBuffer u_blade;
uniform int u_shadow_pass;   // 1 in the shadow pass: the impostor's sun card (render/gl/impostor.h) instead of its camera card
// The season (render/mesh/season.h season_look): deciduous archetypes' colour range, share kept, size.
uniform vec3 u_leaf_color; uniform vec3 u_autumn_a; uniform vec3 u_autumn_b; uniform uvec2 u_deciduous;
uniform uint u_fruit;   // bit k: archetype k is a cone's or fruit's card, in its own colours (season.h archetype_is_fruit)
// Bit k: archetype k is a needle shoot (render/mesh/leaf_shoot.h), drawn by the second call (u_shoot_pass
// 1) from its SHOOT_VERTICES spikes after the blade table; each call collapses the other's leaves.
uniform uint u_shoots; uniform int u_shoot_pass;
uniform float u_keep; uniform float u_season_scale;
uniform vec3 u_crown_centre; uniform vec3 u_crown_radii;   // the leaves' ellipsoid (render/mesh/leaf_shading.h)
out vec3 v_world; out vec3 v_normal; out vec3 v_tangent; out vec3 v_bitangent; out vec2 v_uv; flat out float v_layer;
flat out vec3 v_tint; flat out float v_ao; flat out vec3 v_color; flat out float v_plain; flat out vec3 v_outward;
vec3 rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }
float hash(vec3 p) { return fract(sin(dot(p, vec3(12.9898, 78.233, 37.719))) * 43758.5453); }
float leaf_random(uint i, uint salt) {   // season_leaf_random (render/mesh/season.cpp), line for line
  uint x = i ^ (salt * 0x9e3779b9u);
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x >> 8) * (1.0 / 16777216.0);
}
void main() {
  bool alive = int(i_born_died.x) <= u_step && u_step < int(i_born_died.y);
  bool deciduous = i_texture < 32u ? ((u_deciduous.x >> i_texture) & 1u) != 0u
                                   : i_texture < 64u && ((u_deciduous.y >> (i_texture - 32u)) & 1u) != 0u;
  bool fruit = i_texture < 32u && ((u_fruit >> i_texture) & 1u) != 0u;
  float size = i_size;
  v_color = u_leaf_color;
  if (deciduous) {
    alive = alive && leaf_random(uint(gl_InstanceID), 0u) < u_keep;
    size *= u_season_scale;
    v_color = mix(u_autumn_a, u_autumn_b, leaf_random(uint(gl_InstanceID), 1u));
  }
  bool plain = i_texture >= 128u;
  // Blade in local XY, normal +Z, petiole at the origin pointing along -Y (skeleton.h): the grid of
  // the leaf's archetype, or the flat card for fruit, baked cards and the impostor.
  int proto = (!plain && !fruit && i_texture < uint(BLADE_PROTOTYPES - 1)) ? int(i_texture) : BLADE_PROTOTYPES - 1;
  bool shoot = !plain && !fruit && i_texture < 32u && ((u_shoots >> i_texture) & 1u) != 0u;
  if (shoot != (u_shoot_pass != 0)) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }
  int at = shoot ? 2 * (BLADE_PROTOTYPES * BLADE_VERTICES + proto * SHOOT_VERTICES + gl_VertexID)
                 : 2 * (proto * BLADE_VERTICES + gl_VertexID);
  vec4 pa = texelFetch(u_blade, at), pb = texelFetch(u_blade, at + 1);
  vec3 local = pa.xyz * size;
  v_world = i_position + texelFetch(u_radius, int(i_node)).xyz + rotate(i_rotation, local);  // follows its node's bend
  v_normal = rotate(i_rotation, pb.xyz);
  // The card's frame is the normal map's tangent frame: +X across, +Y toward the tip (up the image),
  // here made orthogonal to the bent blade's normal.
  vec3 across = rotate(i_rotation, vec3(1.0, 0.0, 0.0));
  v_tangent = normalize(across - v_normal * dot(v_normal, across));
  v_bitangent = cross(v_normal, v_tangent);
  // Wind (render/mesh/wind.h): the card and its frame follow its branch, and its tip flaps along the normal.
  // An impostor card (texture >= 128, render/gl/impostor.h) carries final colours and does not flutter.
  v_world = wind_sway_frame(v_world, int(i_node), v_normal, v_tangent, v_bitangent);
  // Texture + 64 marks the impostor's sun card: shadow pass only; its camera card: lit pass only.
  if (plain && (i_texture >= 192u) != (u_shadow_pass != 0)) alive = false;
  v_plain = plain ? 1.0 : 0.0;
  if (!plain)
    v_world = wind_flutter_frame(v_world, v_normal, v_bitangent, pa.y, size, 6.2831853 * hash(i_position.zxy));
  v_uv = vec2(pa.w, pb.w);   // image rows run tip (top) to petiole (bottom)
  v_layer = float(int(plain ? i_texture & 63u : i_texture) % u_layers);
  v_ao = i_ao;
  // crown_outward (render/mesh/leaf_shading.cpp): the gradient of the ellipsoid through the leaf.
  vec3 g = (i_position - u_crown_centre) / (u_crown_radii * u_crown_radii);
  v_outward = length(g) > 1e-6 ? normalize(g) : vec3(0.0, 1.0, 0.0);
  // leaf_color_factor (render/mesh/leaf_shading.cpp), line for line: sun and shade leaves, twig and leaf.
  float t_sky = clamp((i_ao - 0.35) / 0.65, 0.0, 1.0);
  vec3 light = mix(vec3(1.0), mix(vec3(0.8, 0.84, 0.92), vec3(1.12, 1.1, 0.9), t_sky), clamp(u_sun_tone, 0.0, 1.0));
  float hue = 0.7 * (leaf_random(i_node, 11u) - 0.5) + 0.3 * (leaf_random(uint(gl_InstanceID), 12u) - 0.5);
  float lightness = 0.7 * (leaf_random(i_node, 13u) - 0.5) + 0.3 * (leaf_random(uint(gl_InstanceID), 14u) - 0.5);
  vec3 twig = vec3(1.0) + clamp(u_variation, 0.0, 1.0) * vec3(hue + lightness, 0.6 * hue + lightness, -0.5 * hue + lightness);
  v_tint = light * max(twig, vec3(0.0));
  if (plain || fruit) { v_tint = vec3(1.0); v_color = vec3(1.0); }   // texture_tint_gain is 1 (render/assets/textures.h)
  gl_Position = alive ? u_viewproj * vec4(v_world, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
)";

const char* const leaf_fs_body = R"(
in vec3 v_world; in vec3 v_normal; in vec3 v_tangent; in vec3 v_bitangent; in vec2 v_uv; flat in float v_layer;
flat in vec3 v_tint; flat in float v_ao; flat in vec3 v_color; flat in float v_plain; flat in vec3 v_outward;
uniform float u_normal_blend;
uniform sampler2DArray u_leaf; uniform sampler2DArray u_leaf_normal; uniform sampler2DArray u_leaf_thickness;
uniform float u_cutoff; uniform float u_translucency;
out vec4 o_color;
void main() {
  vec3 uvl = vec3(v_uv, v_layer);
  vec4 t = texture(u_leaf, uvl);
  if (t.a < u_cutoff) discard;
  vec3 m = texture(u_leaf_normal, uvl).xyz * 2.0 - 1.0;
  vec3 n0 = normalize(v_normal);
  vec3 n = normalize(mat3(normalize(v_tangent), normalize(v_bitangent), n0) * m);
  if (!gl_FrontFacing) { n = -n; n0 = -n0; }   // two-sided: light the side we see
  // Lit as a volume (blend_leaf_normal, render/mesh/leaf_shading.cpp): the side we see, bent toward
  // the crown's outward direction. The impostor's card keeps its atlas normals.
  if (v_plain < 0.5) {
    vec3 bent = mix(n, v_outward, clamp(u_normal_blend, 0.0, 1.0));
    if (length(bent) > 1e-4) {
      bent = normalize(bent);
      float c = dot(bent, n);   // kept within about 75 degrees of its side (min_leaf_normal_cos)
      vec3 across = bent - c * n;
      n = c >= 0.25 ? bent : (length(across) > 1e-4 ? 0.25 * n + 0.9682458 * normalize(across) : n);
    }
  }
  float ndl = dot(n, u_sun_dir), ndl0 = dot(n0, u_sun_dir);
  // tinted_texture's formula (render/assets/textures.h), then the per-leaf variation.
  vec3 albedo = min(vec3(1.0), TINT_GAIN * v_color * t.rgb) * v_tint;
  // The impostor's camera card crosses its sun card, which would shade half of it: its atlas
  // normals shade it instead.
  float sh = v_plain > 0.5 ? 1.0 : shadow_at(v_world, ndl0 >= 0.0 ? n0 : -n0);
  // Transmission: sunlight arriving on the far side glows through the blade, tinted by it, more
  // where the blade is thin (thickness map: white = thin) than through veins and stems.
  float thin = texture(u_leaf_thickness, uvl).r;
  vec3 transmitted = u_translucency * thin * max(-ndl0, 0.0) * albedo * vec3(1.1, 1.25, 0.6);
  vec3 c = albedo * (u_sun_light * max(ndl, 0.0) * sh + ambient_light(n) * v_ao) + u_sun_light * sh * transmitted;
  o_color = vec4(c, 1.0);
}
)";

const char* const leaf_depth_fs = R"(#version 330 core
in vec2 v_uv; flat in float v_layer;
uniform sampler2DArray u_leaf; uniform float u_cutoff;
void main() { if (texture(u_leaf, vec3(v_uv, v_layer)).a < u_cutoff) discard; }
)";

// A full-screen triangle from gl_VertexID; no vertex buffer.
const char* const fullscreen_vs = R"(#version 330 core
out vec2 v_uv;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  v_uv = p * 0.5 + 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// Sky direction for a screen position, shared by the sky and the occlusion pass.
const char* const sky_glsl = R"(
uniform mat4 u_inv_viewproj; uniform vec3 u_eye; uniform vec3 u_sun_dir;
vec3 view_dir(vec2 uv) {
  vec4 w = u_inv_viewproj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
  return normalize(w.xyz / w.w - u_eye);
}
float sun_disc(vec3 d) {   // ~0.8° disc with a soft rim
  return smoothstep(0.99985, 0.99992, dot(d, u_sun_dir));
}
// The daylight sky (render/gl/sky.cpp): Preetham et al. 1999 with the Perez et al. 1993 distribution
// F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ), or the hand-set gradient.
uniform int u_physical; uniform vec3 u_perez[5]; uniform vec3 u_zenith; uniform vec3 u_perez_zenith;
uniform float u_sky_scale; uniform vec3 u_sky_zenith; uniform vec3 u_sky_horizon;
vec3 sky_color(vec3 d) {
  if (u_physical == 0)
    return d.y >= 0.0 ? mix(u_sky_horizon, u_sky_zenith, pow(d.y, 0.45)) : u_sky_horizon * 0.9;
  float ct = max(d.y, 0.01), cg = clamp(dot(d, u_sun_dir), -1.0, 1.0), g = acos(cg);
  vec3 f = (1.0 + u_perez[0] * exp(u_perez[1] / ct)) * (1.0 + u_perez[2] * exp(u_perez[3] * g) + u_perez[4] * cg * cg);
  vec3 Yxy = u_zenith * f / u_perez_zenith;
  float Y = Yxy.x, x = Yxy.y, y = max(Yxy.z, 1e-4);
  vec3 XYZ = vec3(x / y * Y, Y, (1.0 - x - y) / y * Y);
  vec3 rgb = mat3(3.2406, -0.9689, 0.0557, -1.5372, 1.8758, -0.2040, -0.4986, 0.0415, 1.0570) * XYZ;
  return max(rgb, vec3(0.0)) * u_sky_scale;
}
)";

const char* const sky_fs_body = R"(
in vec2 v_uv;
uniform vec3 u_sun_light;
out vec4 o_color;
void main() {
  vec3 d = view_dir(v_uv);
  vec3 c = sky_color(d);
  float cs = max(dot(d, u_sun_dir), 0.0);
  c += u_sun_light * (0.03 * pow(cs, 64.0) + 0.15 * pow(cs, 800.0));   // glow around the sun
  c += u_sun_light * 8.0 * sun_disc(d);
  o_color = vec4(c, 1.0);
}
)";

const char* const ground_vs = R"(#version 330 core
uniform mat4 u_viewproj; uniform vec3 u_center; uniform float u_extent;
out vec3 v_world;
void main() {
  vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  v_world = vec3(u_center.x + c.x * u_extent, 0.0, u_center.z + c.y * u_extent);
  gl_Position = u_viewproj * vec4(v_world, 1.0);
}
)";

// Ground: procedural grass and soil with normal detail from the same noise, the sun's shadow,
// darker sky light under the crown and where the trunk meets it (no seam), faded into the horizon.
const char* const ground_fs_body = R"(
in vec3 v_world;
uniform vec3 u_center; uniform float u_extent; uniform vec3 u_sky_horizon; uniform vec3 u_ground_color;
uniform vec3 u_root; uniform float u_root_radius; uniform vec2 u_crown_radius;
out vec4 o_color;
float hash2(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
float vnoise(vec2 p) {
  vec2 i = floor(p), f = fract(p), u = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash2(i), hash2(i + vec2(1, 0)), u.x), mix(hash2(i + vec2(0, 1)), hash2(i + vec2(1, 1)), u.x), u.y);
}
float fbm(vec2 p) { return 0.5 * vnoise(p) + 0.25 * vnoise(p * 2.03 + 7.1) + 0.125 * vnoise(p * 4.01 + 3.3); }
void main() {
  vec2 xz = v_world.xz;
  // Patches of grass over soil (metres), fine blades as a high-frequency height.
  float patches = smoothstep(0.18, 0.42, fbm(xz * 0.35));   // mostly grass, soil showing through
  float blades = vnoise(xz * 37.0) * 0.6 + vnoise(xz * 91.0) * 0.4;
  vec3 grass = u_ground_color * (0.75 + 0.5 * blades);
  vec3 soil = vec3(0.20, 0.15, 0.10) * (0.8 + 0.4 * vnoise(xz * 9.0));
  vec3 albedo = mix(soil, grass, patches);
  // Normal detail: the gradient of the height field h = patches + blades (finite differences),
  // faded with the pixel footprint so distant ground does not shimmer.
  float e = 0.01, fw = length(fwidth(xz));
  float hb = vnoise(xz * 37.0), hx = vnoise((xz + vec2(e, 0)) * 37.0), hz = vnoise((xz + vec2(0, e)) * 37.0);
  float amp = 0.004 * (1.0 - smoothstep(0.005, 0.05, fw));
  vec3 n = normalize(vec3(-(hx - hb) / e * amp * 20.0, 1.0, -(hz - hb) / e * amp * 20.0));
  float sh = shadow_at(v_world, vec3(0.0, 1.0, 0.0));
  // Sky occlusion: under the crown's footprint, and a contact shadow around the trunk's base.
  vec2 q = (xz - u_center.xz) / max(u_crown_radius, vec2(0.01));
  float under = 1.0 - 0.45 * (1.0 - smoothstep(0.3, 1.3, length(q)));
  float contact = 1.0 - 0.6 * exp(-pow(length(xz - u_root.xz) / max(u_root_radius * 2.5, 0.01), 2.0));
  vec3 c = albedo * (u_sun_light * max(dot(n, u_sun_dir), 0.0) * sh + ambient_light(n) * under * contact);
  // Blend into the sky already drawn behind it, so the plane's edge never shows.
  float f = smoothstep(0.25, 0.9, length(v_world.xz - u_center.xz) / u_extent);
  o_color = vec4(c, 1.0 - f);
}
)";

// Occlusion (Mitchell, GPU Gems 3 ch. 13): sun disc and sky bright, geometry black.
const char* const occlusion_fs_body = R"(
in vec2 v_uv;
uniform sampler2D u_depth; uniform vec3 u_sun_color;
out vec4 o_color;
void main() {
  if (texture(u_depth, v_uv).r < 1.0) { o_color = vec4(0.0, 0.0, 0.0, 1.0); return; }
  vec3 d = view_dir(v_uv);
  float cs = max(dot(d, u_sun_dir), 0.0);
  // Kept in 0..1 (not HDR): the blur sums ~120 weighted samples, so a bright sky would wash out.
  float bright = sun_disc(d) + 0.3 * pow(cs, 400.0) + 0.005;
  o_color = vec4(u_sun_color * bright, 1.0);
}
)";

// Radial blur toward the sun: Mitchell, GPU Gems 3 ch. 13, example 13-1.
const char* const radial_fs = R"(#version 330 core
in vec2 v_uv;
uniform sampler2D u_occlusion; uniform vec2 u_light_uv; uniform int u_samples;
uniform float u_density; uniform float u_weight; uniform float u_decay; uniform float u_exposure;
out vec4 o_color;
void main() {
  vec2 tc = v_uv;
  vec2 delta = (tc - u_light_uv) * (1.0 / float(u_samples)) * u_density;
  vec3 color = texture(u_occlusion, tc).rgb;
  float illumination_decay = 1.0;
  for (int i = 0; i < u_samples; ++i) {
    tc -= delta;
    vec3 s = texture(u_occlusion, tc).rgb * illumination_decay * u_weight;
    color += s;
    illumination_decay *= u_decay;
  }
  o_color = vec4(color * u_exposure, 1.0);
}
)";

// Volumetric light shafts, at half resolution: how much of the fog's optical depth along each
// view ray lies in the sun's shadow. The ray is clipped to the shadow map's prism (outside it the
// tree casts no shadow, so the lit part there is analytic, see the composite) and marched with one
// hardware-filtered shadow lookup per sample, the start jittered per pixel by interleaved gradient
// noise (Jimenez 2014) so that few samples give fine noise instead of bands.
const char* const march_fs_body = R"(
in vec2 v_uv;
uniform sampler2D u_depth; uniform sampler2DShadow u_shadow; uniform mat4 u_light_viewproj;
uniform int u_samples; uniform float u_fog_density; uniform float u_fog_height; uniform float u_haze;
uniform float u_sky_distance; uniform float u_bias;
out vec4 o_color;
float fog_at(float y) { return u_haze + u_fog_density * exp(-max(y, 0.0) / u_fog_height); }
void main() {
  ivec2 full = textureSize(u_depth, 0);
  float depth = texelFetch(u_depth, clamp(ivec2(v_uv * vec2(full)), ivec2(0), full - 1), 0).r;
  vec3 d = view_dir(v_uv);
  float dist = u_sky_distance;
  if (depth < 1.0) {
    vec4 w = u_inv_viewproj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    dist = length(w.xyz / w.w - u_eye);
  }
  // The ray in the light's clip space (orthographic: affine in t).
  vec3 o = (u_light_viewproj * vec4(u_eye, 1.0)).xyz, v = (u_light_viewproj * vec4(d, 0.0)).xyz;
  float t0 = 0.0, t1 = dist;
  for (int k = 0; k < 2; ++k) {   // x and y inside [-1, 1]
    if (abs(v[k]) < 1e-6) { if (abs(o[k]) > 1.0) t1 = -1.0; continue; }
    float a = (-1.0 - o[k]) / v[k], b = (1.0 - o[k]) / v[k];
    t0 = max(t0, min(a, b)); t1 = min(t1, max(a, b));
  }
  // Beyond the light's near plane (toward the sun) nothing casts a shadow.
  if (abs(v.z) > 1e-6) { float c = (-1.0 - o.z) / v.z; if (v.z > 0.0) t0 = max(t0, c); else t1 = min(t1, c); }
  else if (o.z < -1.0) t1 = -1.0;
  float shadowed = 0.0;
  if (t1 > t0) {
    float dt = (t1 - t0) / float(u_samples);
    float jitter = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    for (int i = 0; i < u_samples; ++i) {
      float t = t0 + (float(i) + jitter) * dt;
      vec3 s = (o + v * t) * 0.5 + 0.5;
      // Past the far plane the map still holds what the sun hits first: shadowed if anything is there.
      float lit = texture(u_shadow, vec3(s.xy, min(s.z, 1.0) - u_bias));
      shadowed += fog_at(u_eye.y + d.y * t) * (1.0 - lit) * dt;
    }
  }
  o_color = vec4(shadowed, dist, 0.0, 1.0);
}
)";

// Auto exposure: the log-average luminance (Reinhard et al. 2002) of a 16 x 9 grid of the lit
// image, into a 1 x 1 target the composite reads. One frame, no adaptation: the same scene gives
// the same image.
const char* const exposure_fs = R"(#version 330 core
uniform sampler2D u_hdr;
out vec4 o_color;
void main() {
  float sum = 0.0;
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 16; ++x) {
      vec3 c = textureLod(u_hdr, (vec2(x, y) + 0.5) / vec2(16.0, 9.0), 0.0).rgb;
      float l = dot(c, vec3(0.2126, 0.7152, 0.0722));
      sum += log(max(l, 1e-4));
    }
  o_color = vec4(exp(sum / 144.0), 0.0, 0.0, 1.0);
}
)";

// Composite: fog (aerial perspective plus the sunlight it scatters, less what the shafts pass found
// shadowed), the radial rays, exposure, then the ACES filmic fit (Narkowicz 2015) and sRGB.
const char* const composite_fs_body = R"(
in vec2 v_uv;
uniform sampler2D u_hdr; uniform sampler2D u_rays; uniform sampler2D u_march; uniform sampler2D u_depth;
uniform sampler2D u_average;
uniform float u_ray_strength; uniform float u_exposure; uniform int u_auto_exposure; uniform int u_volumetric;
uniform float u_fog_density; uniform float u_fog_height; uniform float u_haze; uniform float u_sky_distance;
uniform float u_g; uniform vec3 u_sun_light; uniform vec3 u_fog_ambient;
out vec4 o_color;
vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 to_srgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
// Optical depth from the eye along d over [0, dist] of haze + ground fog σ0 e^(-y / H): closed form,
// written as dist e^(-y0/H) (1 - e^(-k)) / k, k = dist d.y / H, which stays finite for level rays.
float optical_depth(vec3 d, float dist) {
  float H = u_fog_height, y0 = max(u_eye.y, 0.0), k = dist * d.y / H;
  float f = abs(k) < 1e-3 ? 1.0 - 0.5 * k : (1.0 - exp(-k)) / k;
  return u_haze * dist + u_fog_density * dist * exp(-y0 / H) * max(f, 0.0);
}
// Henyey & Greenstein 1941 phase function, normalised over the sphere.
float hg(float cos_t, float g) {
  float d = max(1.0 + g * g - 2.0 * g * cos_t, 1e-4);
  return (1.0 - g * g) / (4.0 * 3.14159265 * d * sqrt(d));
}
void main() {
  vec3 c = texture(u_hdr, v_uv).rgb;
  ivec2 full = textureSize(u_depth, 0);
  ivec2 px = clamp(ivec2(v_uv * vec2(full)), ivec2(0), full - 1);
  float depth = texelFetch(u_depth, px, 0).r;
  vec3 d = view_dir(v_uv);
  float dist = u_sky_distance;
  if (depth < 1.0) {
    vec4 w = u_inv_viewproj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    dist = length(w.xyz / w.w - u_eye);
  }
  if (d.y < 0.0 && depth >= 1.0) dist = min(dist, u_eye.y / -d.y);   // past the ground's edge
  float tau = optical_depth(d, dist);
  float trans = exp(-tau);
  vec3 fog = u_fog_ambient * (1.0 - trans);
  if (u_volumetric != 0) {
    // Depth-aware upsample of the half-resolution shadowed depth: a 3 x 3 tent whose weights drop
    // for samples at another distance, so shafts do not bleed across silhouettes.
    ivec2 half_size = textureSize(u_march, 0);
    vec2 hp = v_uv * vec2(half_size) - 0.5;
    ivec2 base = ivec2(floor(hp + 0.5));
    float sum = 0.0, wsum = 0.0;
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        ivec2 q = clamp(base + ivec2(x, y), ivec2(0), half_size - 1);
        vec2 m = texelFetch(u_march, q, 0).rg;
        vec2 off = vec2(q) - hp;
        float w = max(1.5 - abs(off.x), 0.0) * max(1.5 - abs(off.y), 0.0);
        w *= 1.0 / (1e-3 + abs(m.g - dist) / (0.02 * dist + 0.05));
        sum += m.r * w; wsum += w;
      }
    float shadowed = wsum > 0.0 ? sum / wsum : 0.0;
    float lit = clamp(1.0 - shadowed / max(tau, 1e-6), 0.0, 1.0);
    // Single scattering, extinction taken as uniform along the ray: radiance E π p(θ) (1 - e^-τ) · lit share.
    fog += u_sun_light * 3.14159265 * hg(dot(d, u_sun_dir), u_g) * (1.0 - trans) * lit;
  }
  c = c * trans + fog;
  if (u_ray_strength > 0.0) c += u_ray_strength * texture(u_rays, v_uv).rgb;   // unused targets may hold NaN
  float exposure = u_exposure;
  if (u_auto_exposure != 0) exposure *= clamp(0.2 / max(texelFetch(u_average, ivec2(0), 0).r, 1e-4), 0.25, 8.0);
  // Half an 8-bit step of ordered noise before quantisation: no bands in the sky's gradient.
  float n = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715)))) - 0.5;
  o_color = vec4(to_srgb(aces(max(c, vec3(0.0)) * exposure)) + n / 255.0, 1.0);
}
)";

// Used when a lit program fails to compile: flat colour, no lighting, never a crash.
const char* const fallback_fs = R"(#version 330 core
uniform vec3 u_color; out vec4 o_color;
void main() { o_color = vec4(u_color, 1.0); }
)";

std::string lit_source(const char* body) {
  // TINT_GAIN: tinted_texture's gain (render/assets/textures.h), so shaders and exports share the formula.
  return std::string("#version 330 core\nconst float TINT_GAIN = ") + std::to_string(texture_tint_gain) + ";\n" +
         lighting_glsl + body;
}
std::string sky_source(const char* body) { return std::string("#version 330 core\n") + sky_glsl + body; }
std::string march_source() { return std::string("#version 330 core\n") + sky_glsl + march_fs_body; }

}  // namespace sylva::glsl
