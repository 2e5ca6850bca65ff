#version 330 core
// Particles: one instanced quad per particle (4 corners, triangle strip).
// 2D: a flat disc; 3D: a camera-facing quad the fragment shader turns into a
// shaded sphere (an impostor). Colours come from the CPU's colour map.
layout(location = 0) in vec2 a_corner;   // (-1,-1) .. (1,1)
layout(location = 1) in vec3 a_center;   // [m] per instance
layout(location = 2) in vec4 a_color;    // per instance, normalised bytes

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_radius;                  // [m]
uniform vec3 u_keep_lo;                  // [m] 3D: particles whose centre lies outside [u_keep_lo, u_keep_hi]
uniform vec3 u_keep_hi;                  // are not drawn (cut-aways: the slice, the walls facing the camera)

out vec2 v_uv;
out vec4 v_color;
out vec3 v_center;                       // eye space

void main()
{
    if (any(lessThan(a_center, u_keep_lo)) || any(greaterThan(a_center, u_keep_hi))) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: no fragments
        return;
    }
    vec4 c = u_view * vec4(a_center, 1.0);
    v_center = c.xyz;
    v_uv = a_corner;
    v_color = a_color;
    gl_Position = u_proj * vec4(c.xy + a_corner * u_radius, c.z, 1.0);
}
