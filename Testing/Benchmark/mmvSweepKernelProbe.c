// One Jacobi sweep of a 7-point stencil on an RGBA 3D texture, as a layered
// fragment draw (instanced quads + geometry shader writing gl_Layer, what
// the irradiance pass did) and as a compute dispatch with imageStore, for
// RGBA32F, RGBA16F and R32F (the scratch of a diffusion grid that diffuses
// one light) and three work-group shapes; EGL on the first device,
// no VTK. The measurement behind vtkIrradianceEstimator's compute
// dispatches (docs/performance.md, "On a GPU: NVIDIA H100"). The layered
// draw runs twice more with the voxels outside a centred ball (13 % of the
// grid inside) left alone: discarded at the shader's start, and rejected by
// a depth test against a layered depth array, as the diffusion's passes
// skip the blocks that exchange no light (docs/performance.md, "What a
// change costs").
//   mmvSweepKernelProbe [NX NY NZ]   (default 128 128 64)
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glew.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
static GLuint shader(GLenum type, const char* src)
{
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, NULL);
  glCompileShader(s);
  GLint ok;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok)
  {
    char log[4096];
    glGetShaderInfoLog(s, 4096, NULL, log);
    printf("compile: %s\n", log);
    exit(1);
  }
  return s;
}
static GLuint program(GLuint a, GLuint b, GLuint c)
{
  GLuint p = glCreateProgram();
  glAttachShader(p, a);
  if (b)
    glAttachShader(p, b);
  if (c)
    glAttachShader(p, c);
  glLinkProgram(p);
  GLint ok;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    char log[4096];
    glGetProgramInfoLog(p, 4096, NULL, log);
    printf("link: %s\n", log);
    exit(1);
  }
  return p;
}
#define STENCIL                                                                                    \
  "uniform sampler3D current; uniform sampler3D rhs; uniform ivec3 dims;\n"                        \
  "vec4 sweep(ivec3 v) { vec4 n = texelFetch(rhs, v, 0); float d = 1.0;\n"                         \
  "  for (int a = 0; a < 3; ++a) for (int s = -1; s <= 1; s += 2) { ivec3 q = v; q[a] += s;\n"     \
  "    if (q[a] >= 0 && q[a] < dims[a]) { n += 0.1 * texelFetch(current, q, 0); d += 0.1; } }\n"   \
  "  return n / d; }\n"
static const char* vs = "#version 330 core\nlayout(location=0) in vec2 p; flat out int layerVS;\n"
                        "void main(){ layerVS = gl_InstanceID; gl_Position = vec4(p, 0, 1); }\n";
static const char* gs =
  "#version 330 core\nlayout(triangles) in; layout(triangle_strip, max_vertices=3) out;\n"
  "flat in int layerVS[]; flat out int slice;\n"
  "void main(){ for(int i=0;i<3;++i){ gl_Layer = layerVS[0]; slice = layerVS[0]; gl_Position = "
  "gl_in[i].gl_Position; EmitVertex(); } EndPrimitive(); }\n";
static const char* fs =
  "#version 330 core\n" STENCIL "flat in int slice; out vec4 color; uniform bool discardOutside;\n"
  "void main(){ ivec3 v = ivec3(ivec2(gl_FragCoord.xy), slice);\n"
  "  vec3 c = (vec3(v) + 0.5) / vec3(dims) - 0.5;\n"
  "  if (discardOutside && dot(c, c) >= 0.1) discard;\n"
  "  color = sweep(v); }\n";
static const char* csf =
  "#version 430 core\nlayout(local_size_x=%d, local_size_y=%d, local_size_z=%d) in;\n" STENCIL
  "layout(%s, binding=0) uniform writeonly image3D result;\n"
  "void main(){ ivec3 v = ivec3(gl_GlobalInvocationID); if (any(greaterThanEqual(v, dims))) "
  "return;\n"
  "  imageStore(result, v, sweep(v)); }\n";

static GLuint tex3d(GLenum fmt, int w, int h, int d)
{
  GLuint t;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_3D, t);
  glTexStorage3D(GL_TEXTURE_3D, 1, fmt, w, h, d);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  float* z = calloc((size_t)w * h * d * 4, sizeof(float));
  for (size_t i = 0; i < (size_t)w * h * d * 4; ++i)
    z[i] = (i % 7) * 0.1f;
  glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, w, h, d, GL_RGBA, GL_FLOAT, z);
  free(z);
  return t;
}

// A layered depth array of the grid: 1 inside the ball, 0 outside.
static GLuint ballDepth(const int* dims)
{
  size_t n = (size_t)dims[0] * dims[1] * dims[2];
  float* depth = malloc(n * sizeof(float));
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        float x = (i + 0.5f) / dims[0] - 0.5f, y = (j + 0.5f) / dims[1] - 0.5f,
              z = (k + 0.5f) / dims[2] - 0.5f;
        depth[i + dims[0] * (j + (size_t)dims[1] * k)] = x * x + y * y + z * z < 0.1f ? 1.0f : 0.0f;
      }
  GLuint t;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D_ARRAY, t);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, dims[0], dims[1], dims[2]);
  glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, dims[0], dims[1], dims[2], GL_DEPTH_COMPONENT,
    GL_FLOAT, depth);
  free(depth);
  return t;
}

// Milliseconds per layered sweep, the best of 3 trials of `reps`.
static double timeLayered(GLuint* t, const int* dims, int reps)
{
  double best = 1e9;
  for (int trial = 0; trial < 3; ++trial)
  {
    glFinish();
    double t0 = now();
    for (int r = 0; r < reps; ++r)
    {
      int src = r % 2, dst = 1 - src;
      glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t[dst], 0);
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_3D, t[src]);
      glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, dims[2]);
      glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
    }
    glFinish();
    double dt = (now() - t0) / reps;
    if (dt < best)
      best = dt;
  }
  return 1e3 * best;
}

int main(int argc, char** argv)
{
  int dims[3] = { 128, 128, 64 };
  int reps = 200;
  if (argc > 3)
  {
    dims[0] = atoi(argv[1]);
    dims[1] = atoi(argv[2]);
    dims[2] = atoi(argv[3]);
  }
  PFNEGLQUERYDEVICESEXTPROC qd = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  PFNEGLGETPLATFORMDISPLAYEXTPROC gpd =
    (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  EGLDeviceEXT devs[4];
  EGLint n = 0;
  qd(4, devs, &n);
  EGLDisplay dpy = gpd(EGL_PLATFORM_DEVICE_EXT, devs[0], NULL);
  eglInitialize(dpy, NULL, NULL);
  EGLint ca[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
    EGL_NONE };
  EGLConfig cfg;
  EGLint nc;
  eglChooseConfig(dpy, ca, &cfg, 1, &nc);
  EGLint pa[] = { EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE };
  EGLSurface sf = eglCreatePbufferSurface(dpy, cfg, pa);
  eglBindAPI(EGL_OPENGL_API);
  EGLint xa[] = { EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
  EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, xa);
  eglMakeCurrent(dpy, sf, sf, ctx);
  glewExperimental = GL_TRUE;
  glewInit();
  glGetError();
  printf("renderer %s, grid %dx%dx%d\n", glGetString(GL_RENDERER), dims[0], dims[1], dims[2]);
  GLenum fmts[3] = { GL_RGBA32F, GL_RGBA16F, GL_R32F };
  const char* fmtNames[3] = { "rgba32f", "rgba16f", "r32f" };
  float quad[] = { -1, -1, 1, -1, -1, 1, 1, 1 };
  GLuint vao, vbo;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
  glEnableVertexAttribArray(0);
  GLuint fp = program(
    shader(GL_VERTEX_SHADER, vs), shader(GL_GEOMETRY_SHADER, gs), shader(GL_FRAGMENT_SHADER, fs));
  GLuint fbo;
  glGenFramebuffers(1, &fbo);
  for (int f = 0; f < 3; ++f)
  {
    GLuint t[3];
    for (int i = 0; i < 3; ++i)
      t[i] = tex3d(fmts[f], dims[0], dims[1], dims[2]);
    // fragment, layered
    glUseProgram(fp);
    glUniform1i(glGetUniformLocation(fp, "current"), 0);
    glUniform1i(glGetUniformLocation(fp, "rhs"), 1);
    glUniform3iv(glGetUniformLocation(fp, "dims"), 1, dims);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, dims[0], dims[1]);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_3D, t[2]);
    printf("%s fragment layered: %.4f ms per sweep (status 0x%x, err 0x%x)\n", fmtNames[f],
      timeLayered(t, dims, reps), glCheckFramebufferStatus(GL_FRAMEBUFFER), glGetError());
    glUniform1i(glGetUniformLocation(fp, "discardOutside"), 1);
    printf("%s fragment layered, outside the ball discarded: %.4f ms per sweep (err 0x%x)\n",
      fmtNames[f], timeLayered(t, dims, reps), glGetError());
    glUniform1i(glGetUniformLocation(fp, "discardOutside"), 0);
    GLuint depth = ballDepth(dims);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, depth, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS); // the quad's depth 0.5 passes where the array holds 1
    glDepthMask(GL_FALSE);
    printf("%s fragment layered, outside the ball depth-rejected: %.4f ms per sweep (err 0x%x)\n",
      fmtNames[f], timeLayered(t, dims, reps), glGetError());
    glDisable(GL_DEPTH_TEST);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, 0, 0);
    glDeleteTextures(1, &depth);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    int groups[3][3] = { { 8, 8, 4 }, { 4, 4, 4 }, { 16, 8, 1 } };
    for (int g = 0; g < 3; ++g)
    {
      char src[4096];
      snprintf(src, sizeof src, csf, groups[g][0], groups[g][1], groups[g][2], fmtNames[f]);
      GLuint cp = program(shader(GL_COMPUTE_SHADER, src), 0, 0);
      glUseProgram(cp);
      glUniform1i(glGetUniformLocation(cp, "current"), 0);
      glUniform1i(glGetUniformLocation(cp, "rhs"), 1);
      glUniform3iv(glGetUniformLocation(cp, "dims"), 1, dims);
      double best = 1e9;
      for (int trial = 0; trial < 3; ++trial)
      {
        glFinish();
        double t0 = now();
        for (int r = 0; r < reps; ++r)
        {
          int s = r % 2, d = 1 - s;
          glActiveTexture(GL_TEXTURE0);
          glBindTexture(GL_TEXTURE_3D, t[s]);
          glBindImageTexture(0, t[d], 0, GL_TRUE, 0, GL_WRITE_ONLY, fmts[f]);
          glDispatchCompute((dims[0] + groups[g][0] - 1) / groups[g][0],
            (dims[1] + groups[g][1] - 1) / groups[g][1],
            (dims[2] + groups[g][2] - 1) / groups[g][2]);
          glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        glFinish();
        double dt = (now() - t0) / reps;
        if (dt < best)
          best = dt;
      }
      printf("%s compute %dx%dx%d: %.4f ms per sweep (err 0x%x)\n", fmtNames[f], groups[g][0],
        groups[g][1], groups[g][2], 1e3 * best, glGetError());
    }
  }
  return 0;
}
