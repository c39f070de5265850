// Emission (Yang et al. eq. 27): a segment whose opacity-weighted colour is
// I_c = colour * alpha emits e * I_c, the integral of e * colour * sigma_t
// along it with its own attenuation. Lights and shadows do not change it.
// Mirrors mmvEmission in Filters/vtkMultiMaterialShading.h; TestShaderMirror
// runs both. Compiled in only when some material has e != 0 (MMV_USE_EMISSION).

vec3 mmvEmission(float emission, vec4 segment)
{
  return emission * segment.rgb;
}
