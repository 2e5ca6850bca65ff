#version 330 core
in vec2 v_uv;
in vec4 v_color;
in vec3 v_center;

uniform mat4 u_proj;
uniform float u_radius;
uniform int u_sphere;                    // 0: flat disc (2D), 1: sphere impostor (3D)
uniform float u_rim;                     // 2D: how much darker the disc's rim is (0: none)

out vec4 o_color;

void main()
{
    float r2 = dot(v_uv, v_uv);
    if (r2 > 1.0) discard;
    if (u_sphere == 0) {
        // a thin darker rim keeps neighbouring discs of one colour apart
        float rim = step(0.72, r2);
        o_color = vec4(v_color.rgb * (1.0 - u_rim * rim), 1.0);
        return;
    }
    vec3 n = vec3(v_uv, sqrt(1.0 - r2));
    vec3 l = normalize(vec3(0.4, 0.6, 0.7));
    float diffuse = max(dot(n, l), 0.0);
    float spec = pow(max(dot(reflect(-l, n), vec3(0.0, 0.0, 1.0)), 0.0), 24.0);
    o_color = vec4(v_color.rgb * (0.3 + 0.7 * diffuse) + vec3(0.25 * spec), 1.0);
    // depth of the sphere's surface, so spheres intersect correctly
    vec4 clip = u_proj * vec4(v_center + n * u_radius, 1.0);
    gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
}
