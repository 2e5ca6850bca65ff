#version 330 core
// Overlays, HUD, legend and text: triangles in pixels (origin top-left), one
// texture (the font atlas, which has a white patch for solid shapes).
layout(location = 0) in vec2 a_pos;     // [px]
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;

uniform vec2 u_size;                     // [px] image size

out vec2 v_uv;
out vec4 v_color;

void main()
{
    v_uv = a_uv;
    v_color = a_color;
    gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0);
}
