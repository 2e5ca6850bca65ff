#version 430 core
// Particles drawn straight from the GL compute backend's storage buffers (no
// copy through the CPU): as particles.vert, but each coordinate and each
// component of the colour field is its own per-instance attribute, read
// from the field's buffer at offset d * N * 4 (the backend stores component d
// of particle i at d * N + i). The colour is mapped here as sph_color_of does
// on the CPU, through the same 256 viridis levels, and a wall particle's
// colour is dimmed as sph_color_dimmed does (the FIXED field's buffer).
layout(location = 0) in vec2 a_corner;   // (-1,-1) .. (1,1)
layout(location = 1) in float a_x;       // [m] per instance
layout(location = 2) in float a_y;
layout(location = 3) in float a_z;       // 3D only
layout(location = 4) in float a_v0;      // the colour field, per instance
layout(location = 5) in float a_v1;      // its other components (vectors: the length is the value)
layout(location = 6) in float a_v2;
layout(location = 7) in float a_wall;    // 1: a fixed wall particle (read only where u_walls)

// min and max of the field as ordered keys, from the backend's gpu_range.comp
layout(std140, binding = 0) uniform Range { uvec4 u_keys; };
layout(binding = 1) uniform sampler2D u_cmap; // 256 x 1: sph_colormap_viridis(k / 255)

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_radius;                  // [m]
uniform vec3 u_keep_lo;                  // [m] 3D: particles whose centre lies outside [u_keep_lo, u_keep_hi]
uniform vec3 u_keep_hi;                  // are not drawn (as particles.vert)
uniform int u_dim;
uniform int u_comps;                     // 1: a scalar field; 2 or 3: a vector's length
uniform int u_fixed;                     // 1: u_range instead of the keys
uniform vec2 u_range;
uniform int u_walls;                     // 1: the scene has wall particles, a_wall is bound

out vec2 v_uv;
out vec4 v_color;
out vec3 v_center;                       // eye space

float key_float(uint k)
{
    return uintBitsToFloat((k & 0x80000000u) != 0u ? (k & 0x7FFFFFFFu) : ~k);
}

void main()
{
    vec3 center = vec3(a_x, a_y, u_dim == 3 ? a_z : 0.0);
    if (any(lessThan(center, u_keep_lo)) || any(greaterThan(center, u_keep_hi))) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: no fragments
        return;
    }
    float v = a_v0;
    if (u_comps > 1) {                   // as the CPU's vec_norm: summed axis by axis
        precise float s = a_v0 * a_v0;
        s = s + a_v1 * a_v1;
        if (u_comps == 3) s = s + a_v2 * a_v2;
        v = sqrt(s);
    }
    float lo = 0.0, hi = 0.0;
    if (u_fixed != 0) {
        lo = u_range.x;
        hi = u_range.y;
    } else if (u_keys.x <= u_keys.y) {   // else no finite value: 0 and 0, as on the CPU
        lo = key_float(u_keys.x);
        hi = key_float(u_keys.y);
    }
    // a range within rounding of one value is one value: the middle colour
    float t = hi - lo > 1e-6 * max(abs(hi), abs(lo)) ? (v - lo) / (hi - lo) : 0.5;
    if (isnan(t)) {
        v_color = vec4(vec3(128.0 / 255.0), 1.0);
    } else {
        int k = int(floor(clamp(t, 0.0, 1.0) * 255.0 + 0.5));
        v_color = texelFetch(u_cmap, ivec2(k, 0), 0);
    }
    if (u_walls != 0 && a_wall != 0.0) {
        // sph_color_dimmed: 55 % of the way to grey 128, in integers as on the CPU,
        // so both paths give the same bytes
        ivec3 b = ivec3(round(v_color.rgb * 255.0));
        b = (b * (100 - 55) + 128 * 55 + 50) / 100;
        v_color = vec4(vec3(b) / 255.0, 1.0);
    }
    vec4 c = u_view * vec4(center, 1.0);
    v_center = c.xyz;
    v_uv = a_corner;
    gl_Position = u_proj * vec4(c.xy + a_corner * u_radius, c.z, 1.0);
}
