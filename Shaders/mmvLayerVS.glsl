// Vertex shader of the irradiance passes: the full-screen quad, drawn once
// per 3D-texture layer by instancing (layer = firstLayer + instance), so one
// draw call fills every slice of the target.
//VTK::System::Dec
in vec4 ndCoordIn;
in vec2 texCoordIn;
uniform int firstLayer;
out vec2 texCoordVS;
flat out int layerVS;

void main()
{
  gl_Position = ndCoordIn;
  texCoordVS = texCoordIn;
  layerVS = firstLayer + gl_InstanceID;
}
