/* Building a GL program from shader stages, for the renderer and the compute
 * backend alike: compile each stage, link, and turn a failure into one line
 * that names the program and carries the driver's log. */
#include <stdio.h>

#include "gl_table.h"

GLuint sph_gl_program(const sph_gl *gl, const sph_gl_stage *stages, int n_stages, const char *name, char *err,
                      size_t n)
{
    GLuint prog = gl->CreateProgram();
    GLint ok = 0;
    for (int k = 0; k < n_stages; k++) {
        GLuint sh = gl->CreateShader(stages[k].type);
        gl->ShaderSource(sh, stages[k].count, stages[k].parts, stages[k].lens);
        gl->CompileShader(sh);
        gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[1024] = "";
            gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
            snprintf(err, n, "%s does not compile: %.900s", name, log);
            gl->DeleteShader(sh);
            gl->DeleteProgram(prog);
            return 0;
        }
        gl->AttachShader(prog, sh);
        gl->DeleteShader(sh); /* freed with the program */
    }
    gl->LinkProgram(prog);
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
        snprintf(err, n, "%s does not link: %.900s", name, log);
        gl->DeleteProgram(prog);
        return 0;
    }
    return prog;
}
