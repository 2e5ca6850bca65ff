/* The GL entry points the renderer (src/render/) and the compute backend
 * (src/gpu/) use, as one table of function pointers.
 *
 * Why a table and not libepoxy everywhere: libepoxy resolves a GL function on
 * its first call by asking the current GLX or EGL context for it. Under an
 * OSMesa context there is neither, so epoxy's resolver finds nothing and
 * aborts the process. The OSMesa backend therefore links libOSMesa directly
 * and gets each function from OSMesaGetProcAddress, while the EGL and SDL
 * backends get them from libepoxy. The drawing code (src/render/) never calls
 * a GL symbol by name: it calls only through this table, so one renderer runs
 * under all three, and the two ways of loading are each a few lines.
 *
 * The list is an X-macro (return type, name without "gl", parameters), so the
 * struct and both loaders expand from it. Files that include this header see
 * the GL types and enums (GL/glcorearb.h, which declares no functions), but no
 * function, unless they include epoxy/gl.h first (gl_epoxy.c only). */
#ifndef SPH_GL_TABLE_H
#define SPH_GL_TABLE_H

#include <stddef.h>

#ifndef __epoxy_gl_h__
#include <GL/glcorearb.h>
#endif

#define SPH_GL_FUNCS(X)                                                                                  \
    X(void, Viewport, (GLint x, GLint y, GLsizei w, GLsizei h))                                          \
    X(void, Scissor, (GLint x, GLint y, GLsizei w, GLsizei h))                                           \
    X(void, Clear, (GLbitfield mask))                                                                    \
    X(void, ClearColor, (GLfloat r, GLfloat g, GLfloat b, GLfloat a))                                    \
    X(void, ClearDepth, (GLdouble d))                                                                    \
    X(void, Enable, (GLenum cap))                                                                        \
    X(void, Disable, (GLenum cap))                                                                       \
    X(void, BlendFunc, (GLenum s, GLenum d))                                                             \
    X(void, BlendFuncSeparate, (GLenum sc, GLenum dc, GLenum sa, GLenum da))                             \
    X(void, DepthFunc, (GLenum f))                                                                       \
    X(void, DepthMask, (GLboolean f))                                                                    \
    X(GLenum, GetError, (void))                                                                          \
    X(const GLubyte *, GetString, (GLenum name))                                                         \
    X(void, GetIntegerv, (GLenum name, GLint *v))                                                        \
    X(void, PixelStorei, (GLenum name, GLint v))                                                         \
    X(void, ReadPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void *p))           \
    X(void, Finish, (void))                                                                              \
    X(void, GenTextures, (GLsizei n, GLuint *t))                                                         \
    X(void, DeleteTextures, (GLsizei n, const GLuint *t))                                                \
    X(void, BindTexture, (GLenum target, GLuint t))                                                      \
    X(void, ActiveTexture, (GLenum unit))                                                                \
    X(void, TexImage2D, (GLenum target, GLint level, GLint ifmt, GLsizei w, GLsizei h, GLint border,     \
                         GLenum fmt, GLenum type, const void *p))                                        \
    X(void, TexParameteri, (GLenum target, GLenum name, GLint v))                                        \
    X(void, GenBuffers, (GLsizei n, GLuint *b))                                                          \
    X(void, DeleteBuffers, (GLsizei n, const GLuint *b))                                                 \
    X(void, BindBuffer, (GLenum target, GLuint b))                                                       \
    X(void, BufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage))                \
    X(void, GenVertexArrays, (GLsizei n, GLuint *a))                                                     \
    X(void, DeleteVertexArrays, (GLsizei n, const GLuint *a))                                            \
    X(void, BindVertexArray, (GLuint a))                                                                 \
    X(void, EnableVertexAttribArray, (GLuint i))                                                         \
    X(void, VertexAttribPointer, (GLuint i, GLint size, GLenum type, GLboolean norm, GLsizei stride,     \
                                  const void *p))                                                        \
    X(void, VertexAttribDivisor, (GLuint i, GLuint divisor))                                             \
    X(GLuint, CreateShader, (GLenum type))                                                               \
    X(void, ShaderSource, (GLuint s, GLsizei n, const GLchar *const *src, const GLint *len))             \
    X(void, CompileShader, (GLuint s))                                                                   \
    X(void, GetShaderiv, (GLuint s, GLenum name, GLint *v))                                              \
    X(void, GetShaderInfoLog, (GLuint s, GLsizei cap, GLsizei *len, GLchar *log))                        \
    X(void, DeleteShader, (GLuint s))                                                                    \
    X(GLuint, CreateProgram, (void))                                                                     \
    X(void, AttachShader, (GLuint p, GLuint s))                                                          \
    X(void, BindAttribLocation, (GLuint p, GLuint i, const GLchar *name))                                \
    X(void, LinkProgram, (GLuint p))                                                                     \
    X(void, GetProgramiv, (GLuint p, GLenum name, GLint *v))                                             \
    X(void, GetProgramInfoLog, (GLuint p, GLsizei cap, GLsizei *len, GLchar *log))                       \
    X(void, DeleteProgram, (GLuint p))                                                                   \
    X(void, UseProgram, (GLuint p))                                                                      \
    X(GLint, GetUniformLocation, (GLuint p, const GLchar *name))                                         \
    X(void, Uniform1i, (GLint loc, GLint v))                                                             \
    X(void, Uniform1f, (GLint loc, GLfloat v))                                                           \
    X(void, Uniform2f, (GLint loc, GLfloat a, GLfloat b))                                                \
    X(void, Uniform3f, (GLint loc, GLfloat a, GLfloat b, GLfloat c))                                     \
    X(void, UniformMatrix4fv, (GLint loc, GLsizei n, GLboolean transpose, const GLfloat *m))             \
    X(void, GenFramebuffers, (GLsizei n, GLuint *f))                                                     \
    X(void, DeleteFramebuffers, (GLsizei n, const GLuint *f))                                            \
    X(void, BindFramebuffer, (GLenum target, GLuint f))                                                  \
    X(void, FramebufferRenderbuffer, (GLenum target, GLenum att, GLenum rbtarget, GLuint rb))            \
    X(GLenum, CheckFramebufferStatus, (GLenum target))                                                   \
    X(void, GenRenderbuffers, (GLsizei n, GLuint *r))                                                    \
    X(void, DeleteRenderbuffers, (GLsizei n, const GLuint *r))                                           \
    X(void, BindRenderbuffer, (GLenum target, GLuint r))                                                 \
    X(void, RenderbufferStorage, (GLenum target, GLenum fmt, GLsizei w, GLsizei h))                      \
    X(void, BlitFramebuffer, (GLint sx0, GLint sy0, GLint sx1, GLint sy1, GLint dx0, GLint dy0,          \
                              GLint dx1, GLint dy1, GLbitfield mask, GLenum filter))                     \
    X(void, DrawArrays, (GLenum mode, GLint first, GLsizei count))                                       \
    X(void, DrawArraysInstanced, (GLenum mode, GLint first, GLsizei count, GLsizei instances))

typedef struct sph_gl {
#define SPH_GL_MEMBER(ret, name, params) ret (*name) params;
    SPH_GL_FUNCS(SPH_GL_MEMBER)
#undef SPH_GL_MEMBER
} sph_gl;

/* What the GL compute backend (src/gpu/) needs beyond the renderer's table:
 * OpenGL 4.3 compute and buffer calls, and the timer queries (core since
 * 3.3) that time its passes. A table of its own, so the OSMesa
 * loader (3.3) never asks for them. */
#define SPH_GL_COMPUTE_FUNCS(X)                                                                          \
    X(void, DispatchCompute, (GLuint x, GLuint y, GLuint z))                                             \
    X(void, MemoryBarrier, (GLbitfield barriers))                                                        \
    X(void, BindBufferBase, (GLenum target, GLuint index, GLuint b))                                     \
    X(void, BufferSubData, (GLenum target, GLintptr off, GLsizeiptr size, const void *data))             \
    X(void, GetBufferSubData, (GLenum target, GLintptr off, GLsizeiptr size, void *data))                \
    X(void, Uniform1ui, (GLint loc, GLuint v))                                                           \
    X(void, GetIntegeri_v, (GLenum name, GLuint index, GLint *v))                                        \
    X(void, GenQueries, (GLsizei n, GLuint *q))                                                          \
    X(void, DeleteQueries, (GLsizei n, const GLuint *q))                                                 \
    X(void, QueryCounter, (GLuint q, GLenum target))                                                     \
    X(void, GetQueryiv, (GLenum target, GLenum name, GLint *v))                                          \
    X(void, GetQueryObjectiv, (GLuint q, GLenum name, GLint *v))                                         \
    X(void, GetQueryObjectui64v, (GLuint q, GLenum name, GLuint64 *v))

typedef struct sph_gl_compute {
#define SPH_GL_MEMBER(ret, name, params) ret (*name) params;
    SPH_GL_COMPUTE_FUNCS(SPH_GL_MEMBER)
#undef SPH_GL_MEMBER
} sph_gl_compute;

/* Fills the compute table from libepoxy (a current EGL context). */
void sph_gl_load_compute_epoxy(sph_gl_compute *gl);

/* One shader stage of a program: its type and its source in parts, as
 * glShaderSource takes them (lens NULL: every part ends with a NUL). */
typedef struct sph_gl_stage {
    GLenum type;
    int count;
    const char *const *parts;
    const GLint *lens;
} sph_gl_stage;

/* Compiles the stages and links them into a program, through the table (so
 * under every context kind). Returns 0 with "NAME does not compile: LOG" or
 * "NAME does not link: LOG" in err; the renderer and the compute backend both
 * build their programs here (gl_program.c). */
GLuint sph_gl_program(const sph_gl *gl, const sph_gl_stage *stages, int n_stages, const char *name, char *err,
                      size_t n);

/* Fills the table from libepoxy (a current EGL or GLX context: the EGL and
 * SDL backends). Always succeeds; epoxy resolves each on first call. */
void sph_gl_load_epoxy(sph_gl *gl);

/* Fills the table by name through getproc (OSMesaGetProcAddress). Returns
 * the name of the first missing function, or NULL if all were found. */
const char *sph_gl_load_by_name(sph_gl *gl, void *(*getproc)(const char *name));

#endif
