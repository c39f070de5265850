#include "vtkIrradianceComputeProgram.h"

#include "vtkObjectFactory.h"
#include "vtk_glew.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkIrradianceComputeProgram);

//------------------------------------------------------------------------------
bool vtkIrradianceComputeProgram::IsSupported()
{
  return GLEW_VERSION_4_3 != 0;
}

//------------------------------------------------------------------------------
bool vtkIrradianceComputeProgram::IsSoftwareRenderer()
{
  const GLubyte* name = glGetString(GL_RENDERER);
  const std::string renderer = name ? reinterpret_cast<const char*>(name) : "";
  for (const char* software : { "llvmpipe", "softpipe", "swrast", "Software Rasterizer" })
  {
    if (renderer.find(software) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

namespace
{
std::string InfoLog(GLuint object, bool program)
{
  GLint length = 0;
  program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
          : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  program ? glGetProgramInfoLog(object, length, nullptr, log.data())
          : glGetShaderInfoLog(object, length, nullptr, log.data());
  return std::string(log.data());
}
} // namespace

//------------------------------------------------------------------------------
bool vtkIrradianceComputeProgram::Build(const std::string& source)
{
  if (!IsSupported())
  {
    this->Error = "compute shaders need OpenGL 4.3";
    return false;
  }
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint status = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
  if (status != GL_TRUE)
  {
    this->Error = "compute shader: " + InfoLog(shader, false);
    glDeleteShader(shader);
    return false;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  // The program keeps the compiled code; the shader object is not needed.
  glDetachShader(program, shader);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &status);
  if (status != GL_TRUE)
  {
    this->Error = "compute program: " + InfoLog(program, true);
    glDeleteProgram(program);
    return false;
  }
  // What vtkShaderProgram::Bind() and the uniform setters look at; its
  // ReleaseGraphicsResources() deletes the program.
  this->Handle = static_cast<int>(program);
  this->Linked = true;
  this->Compiled = true;
  return true;
}
