// Multi-material volume shading inside VTK's ray caster: declarations.
// Inserted before //VTK::Shading::Dec. The C++ side prepends the defines
// MMV_NUMBER_OF_LIGHTS, MMV_IRRADIANCE_TEXTURES, MMV_USE_REFLECTION and
// MMV_USE_PREINTEGRATION, and mmvShading.glsl.
//
// Data values are normalised to [0, 1] over the scalar range, the coordinate
// of every table below.

uniform sampler2D mmv_preintColor;  // (t1, t2) -> I_c (rgb, opacity-weighted), I_alpha
uniform sampler2D mmv_preintBeta;   // (t1, t2) -> I_beta, shading position in the segment
uniform sampler2D mmv_material;     // (t, 0.25) -> ka kd ks ke; (t, 0.75) -> r c_t s 0
uniform float mmv_tableSize;        // entries per table axis
uniform float mmv_tableStep;        // segment length the tables were built for (object units)
uniform float mmv_gradientFade;     // |gradient| (normalised value per object unit) of full surface shading
uniform sampler3D mmv_gradient;     // per voxel: normalised-value gradient per index unit (vtkValueGradient.h)
uniform vec3 mmv_gradientScale;     // index units per texture-coordinate unit (the data's dimensions)
uniform vec3 mmv_irradianceScale;   // data texture coordinate -> irradiance texture coordinate
uniform vec3 mmv_irradianceBias;
#if MMV_NUMBER_OF_LIGHTS > 0
uniform sampler3D mmv_irradiance0;  // lights 0-3, one per channel
#if MMV_IRRADIANCE_TEXTURES > 1
uniform sampler3D mmv_irradiance1;  // lights 4-7
#endif
uniform int mmv_lightKind[MMV_NUMBER_OF_LIGHTS];       // 0 directional, 1 point, 2 spot
uniform vec3 mmv_lightVector[MMV_NUMBER_OF_LIGHTS];    // toward the light, or its position (object space)
uniform vec3 mmv_lightRadiance[MMV_NUMBER_OF_LIGHTS];  // colour * intensity
#endif
#if MMV_USE_REFLECTION
uniform vec3 mmv_environmentUp;     // object space
uniform vec3 mmv_environmentBottom;
uniform vec3 mmv_environmentTop;
#endif

// The back end of the previous segment.
vec3 mmv_previousPos;
float mmv_previousValue;
bool mmv_hasPrevious;

float mmvValue(vec3 texPos)
{
  return texture3D(in_volume[0], texPos).r * in_volume_scale[0].r + in_volume_bias[0].r;
}

float mmvTableCoord(float t)
{
  return (clamp(t, 0.0, 1.0) * (mmv_tableSize - 1.0) + 0.5) / mmv_tableSize;
}

// Gradient of the normalised value in object space: the voxels' central
// differences, interpolated (one fetch instead of six).
vec3 mmvGradient(vec3 texPos)
{
  vec3 g = texture(mmv_gradient, texPos).xyz * mmv_gradientScale;
  // A gradient is a covector: it maps with the inverse transpose.
  return transpose(mat3(in_inverseTextureDatasetMatrix[0])) * g;
}

// eqs. 16-17 at shading position texPos with value t for one segment.
vec3 mmvShadeSegment(vec3 texPos, float t, vec4 segment)
{
  float tc = mmvTableCoord(t);
  vec4 material = texture2D(mmv_material, vec2(tc, 0.25));
  vec3 position = (in_textureDatasetMatrix[0] * vec4(texPos, 1.0)).xyz;
  vec3 v = -normalize((in_textureDatasetMatrix[0] * vec4(g_dirStep, 0.0)).xyz);
  vec3 gradient = mmvGradient(texPos);
  float gradientLength = length(gradient);
  vec3 n = gradientLength > 0.0 ? -gradient / gradientLength : vec3(0.0);
  n = dot(n, v) < 0.0 ? -n : n; // two-sided: surfaces face the viewer
  // Normal-based terms fade out where the gradient vanishes (noise there).
  float directional = clamp(gradientLength / mmv_gradientFade, 0.0, 1.0);

  vec3 radiance = vec3(0.0);
#if MMV_NUMBER_OF_LIGHTS > 0
  vec3 irradianceCoord = texPos * mmv_irradianceScale + mmv_irradianceBias;
  vec4 irradiance0 = texture(mmv_irradiance0, irradianceCoord);
#if MMV_IRRADIANCE_TEXTURES > 1
  vec4 irradiance1 = texture(mmv_irradiance1, irradianceCoord);
#endif
  for (int k = 0; k < MMV_NUMBER_OF_LIGHTS; ++k)
  {
#if MMV_IRRADIANCE_TEXTURES > 1
    float irradiance = k < 4 ? irradiance0[k] : irradiance1[k - 4];
#else
    float irradiance = irradiance0[k];
#endif
    if (irradiance <= 0.0)
    {
      continue;
    }
    vec3 l = mmv_lightVector[k];
    if (mmv_lightKind[k] != 0)
    {
      vec3 toLight = mmv_lightVector[k] - position;
      float distance = length(toLight);
      l = distance > 0.0 ? toLight / distance : n;
    }
    radiance += irradiance * mmv_lightRadiance[k] *
      mmvBlinnPhong(material, segment, n, v, l, directional);
  }
#else
  // No active light: ambient emission only, so the volume stays visible.
  radiance = material.x * segment.rgb;
#endif
#if MMV_USE_REFLECTION
  float reflection = texture2D(mmv_material, vec2(tc, 0.75)).x;
  if (reflection > 0.0)
  {
    vec3 mirrored = reflect(-v, n);
    radiance += directional * reflection * segment.a *
      mmvEnvironment(mirrored, mmv_environmentUp, mmv_environmentBottom, mmv_environmentTop);
  }
#endif
  return radiance;
}

// Integrates the segment x1 -> x2 (texture coordinates) with values t1, t2 and
// composites it front to back into g_fragColor.
void mmvIntegrateSegment(vec3 x1, float t1, vec3 x2, float t2)
{
  // Length relative to the tables' step: partial first/last segments and
  // VTK's automatic sample distance differ from it.
  float ratio = length(x2 - x1) / max(length(g_dirStep), 1e-30) * in_sampleDistance / mmv_tableStep;
  if (ratio <= 0.0)
  {
    return;
  }
#if MMV_USE_PREINTEGRATION
  vec2 tc = vec2(mmvTableCoord(t1), mmvTableCoord(t2));
#else
  // Post-classification: the segment takes the value at its back end.
  vec2 tc = vec2(mmvTableCoord(t2));
#endif
  vec4 segment = texture2D(mmv_preintColor, tc);
  if (segment.a <= 0.0)
  {
    return;
  }
  if (abs(ratio - 1.0) > 1e-3)
  {
    // Exact for the opacity, and exact for the colour of uniform segments.
    float alpha = 1.0 - pow(max(1.0 - segment.a, 0.0), ratio);
    segment.rgb *= alpha / segment.a;
    segment.a = alpha;
  }
#if MMV_USE_PREINTEGRATION
  float beta = texture2D(mmv_preintBeta, tc).r;
#else
  float beta = 1.0;
#endif
  vec3 radiance = mmvShadeSegment(mix(x1, x2, beta), mix(t1, t2, beta), segment);
  g_fragColor.rgb += (1.0 - g_fragColor.a) * radiance;
  g_fragColor.a += (1.0 - g_fragColor.a) * segment.a;
}
