// Geometry shader of the irradiance passes: routes each instance's quad to
// its layer of a layered (whole 3D texture) attachment, and hands the layer
// to the fragment shaders as `slice` (gl_Layer is not readable there before
// GLSL 4.30). With a single-layer attachment gl_Layer is ignored.
//VTK::System::Dec
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec2 texCoordVS[];
flat in int layerVS[];
out vec2 texCoord;
flat out int slice;

void main()
{
  for (int i = 0; i < 3; ++i)
  {
    gl_Layer = layerVS[0];
    slice = layerVS[0];
    texCoord = texCoordVS[i];
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
