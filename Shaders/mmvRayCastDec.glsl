// Multi-material volume shading inside VTK's ray caster: declarations.
// Inserted before //VTK::Shading::Dec. The C++ side
// (vtkMultiMaterialShaderAssembly.cxx) prepends the prelude (texel layout,
// light kinds), the defines MMV_NUMBER_OF_LIGHTS, MMV_IRRADIANCE_TEXTURES,
// MMV_USE_REFLECTION, MMV_USE_PREINTEGRATION, MMV_USE_ANISOTROPY and
// MMV_USE_EMISSION, MMV_USE_RGB_IRRADIANCE, MMV_FIELDS, the light uniforms
// (vtkMultiMaterialLightUniforms.h), mmvLightModel.glsl, mmvPhaseFunction.glsl,
// mmvEmission.glsl, mmvTint.glsl and mmvReflection.glsl when those are on,
// and mmvShading.glsl.
//
// Data values are normalised to [0, 1] over the scalar range, the coordinate
// of every table below. Several fields (MMV_FIELDS > 1, the components of
// the data) stack their segment and material tables along v, field f's
// above field f - 1's (vtkMultiMaterialTextures.h), and a sample's value is
// a vec4, one component per field.

uniform sampler2D mmv_preintColor;  // (t1, t2) -> I_c (rgb, opacity-weighted), I_alpha
uniform sampler2D mmv_preintBeta;   // (t1, t2) -> I_beta, shading position in the segment
uniform sampler2D mmv_material;     // (t, row) -> parameters, as mmv::MaterialTexelLayout
uniform float mmv_tableSize;        // entries per table axis
uniform float mmv_tableStep;        // segment length the tables were built for (object units)
uniform float mmv_surfaceEqualShare; // |gradient| (normalised value per object unit) of equal surface/particle shares
uniform sampler3D mmv_gradient;     // per voxel: normalised-value gradient per index unit (vtkValueGradient.h)
uniform vec3 mmv_gradientScale;     // index units per texture-coordinate unit (the data's dimensions)
uniform vec3 mmv_gradientTexScale;  // data texture coordinate -> gradient texture coordinate
uniform vec3 mmv_gradientTexBias;   // (identity unless the gradient volume was resampled to fit)
uniform vec3 mmv_irradianceScale;   // data texture coordinate -> irradiance texture coordinate
uniform vec3 mmv_irradianceBias;
// Bricks (VTK's partitions): each block has its own texture; these map a
// block's texture coordinate to the whole volume's, which the gradient and
// irradiance textures use (identity for one block).
uniform mat4 mmv_physicalToWholeIndex; // object space -> the whole volume's point index
uniform vec3 mmv_wholeDimensions;      // points of the whole volume
uniform vec3 mmv_dataSpacing;          // |spacing| along the index axes
uniform mat3 mmv_gradientToObject;     // texture-coordinate gradient -> object-space gradient
// Cell scalars (one block only): VTK's texture coordinate spans the cells,
// texel centres on the cell centres, so it is already the coordinate of the
// cell-centre grid that the gradient and irradiance textures cover.
uniform int mmv_cellData;
#if MMV_USE_SKY
uniform sampler3D mmv_sky;  // the sky's visibility moments S0, S1 (vtkSkyVisibility.h)
uniform vec3 mmv_skyScale;  // data texture coordinate -> sky texture coordinate
uniform vec3 mmv_skyBias;
uniform vec3 mmv_skyMean;   // the sky's radiance, L(w) = mean + slope * w (object space)
uniform mat3 mmv_skySlope;
#endif
#if MMV_NUMBER_OF_LIGHTS > 0
uniform sampler3D mmv_irradiance0;  // lights 0-3, one per channel
#if MMV_IRRADIANCE_TEXTURES > 1
uniform sampler3D mmv_irradiance1;  // lights 4-7
#endif
#endif

#if MMV_FIELDS > 1
#define mmvValueType vec4
#else
#define mmvValueType float
#endif

// The back end of the previous segment.
vec3 mmv_previousPos;
mmvValueType mmv_previousValue;
bool mmv_hasPrevious;

// The current block (brick): its points per axis and the whole volume's
// index of its first point, from its texture-to-dataset matrix, which spans
// the block's points. Set by mmvBeginBlock() (ray set-up).
vec3 mmv_blockPoints;
vec3 mmv_blockFirstIndex;

void mmvBeginBlock()
{
  mat4 blockToObject = in_textureDatasetMatrix[0];
  mmv_blockPoints = vec3(length(blockToObject[0].xyz), length(blockToObject[1].xyz),
    length(blockToObject[2].xyz)) / mmv_dataSpacing + 1.0;
  mmv_blockFirstIndex = (mmv_physicalToWholeIndex * vec4(blockToObject[3].xyz, 1.0)).xyz;
}

// The block's point index at texPos. VTK 9.2 maps every block with the whole
// volume's cell-to-point matrix (texPos = 0.5 / N + u (N - 1) / N, u in [0, 1]
// over the block's points), not the block's own, so this undoes that one.
vec3 mmvBlockIndex(vec3 texPos)
{
  vec3 n = mmv_wholeDimensions;
  return (texPos - 0.5 / n) * n / max(n - 1.0, vec3(1.0)) * (mmv_blockPoints - 1.0);
}

mmvValueType mmvValue(vec3 texPos)
{
  // Fetch the point the geometry means (identical to texPos for one block
  // and for cell scalars).
  vec3 fetch = mmv_cellData != 0 ? texPos : (mmvBlockIndex(texPos) + 0.5) / mmv_blockPoints;
#if MMV_FIELDS > 1
  return texture3D(in_volume[0], fetch) * in_volume_scale[0] + in_volume_bias[0];
#else
  return texture3D(in_volume[0], fetch).r * in_volume_scale[0].r + in_volume_bias[0].r;
#endif
}

// The whole volume's texture coordinate of the block's texPos (texPos
// itself for one block).
vec3 mmvWholeTexCoord(vec3 texPos)
{
  if (mmv_cellData != 0)
  {
    return texPos;
  }
  return (mmv_blockFirstIndex + mmvBlockIndex(texPos) + 0.5) / mmv_wholeDimensions;
}

// The v coordinate of row r of mmv_material (field f's rows start at
// f * MMV_MATERIAL_ROWS).
float mmvMaterialRow(int r)
{
  return (float(r) + 0.5) / float(MMV_MATERIAL_ROWS * MMV_FIELDS);
}

// One parameter at table coordinate tc: its texel's (MMV_<NAME>_ROW) channel
// (MMV_<NAME>_CHANNEL).
float mmvMaterialParameter(float tc, int row, int channel)
{
  return texture2D(mmv_material, vec2(tc, mmvMaterialRow(row)))[channel];
}

float mmvTableCoord(float t)
{
  return (clamp(t, 0.0, 1.0) * (mmv_tableSize - 1.0) + 0.5) / mmv_tableSize;
}

// Gradient of the normalised value in object space: the voxels' central
// differences, interpolated (one fetch instead of six).
vec3 mmvGradient(vec3 texPos)
{
  vec3 gradientCoord = mmvWholeTexCoord(texPos) * mmv_gradientTexScale + mmv_gradientTexBias;
  vec3 g = texture(mmv_gradient, gradientCoord).xyz * mmv_gradientScale;
  // A gradient is a covector: it maps with the inverse transpose.
  return mmv_gradientToObject * g;
}

// What the shading of every field at one point reads: the geometry, the
// gradient's normal and surface share, and the lights' irradiance.
struct mmvSamplePoint
{
  vec3 position; // object space
  vec3 n;
  vec3 v;
  float surface;
  vec4 irradiance0;
  vec4 irradiance1;
  vec4 sky; // the sky's visibility moments (MMV_USE_SKY)
};

mmvSamplePoint mmvFetchSamplePoint(vec3 texPos)
{
  mmvSamplePoint p;
  p.position = (in_textureDatasetMatrix[0] * vec4(texPos, 1.0)).xyz;
  p.v = -normalize((in_textureDatasetMatrix[0] * vec4(g_dirStep, 0.0)).xyz);
  vec3 gradient = mmvGradient(texPos);
  float gradientLength = length(gradient);
  vec3 n = gradientLength > 0.0 ? -gradient / gradientLength : vec3(0.0);
  p.n = dot(n, p.v) < 0.0 ? -n : n; // two-sided: surfaces face the viewer
  p.surface = mmvSurfaceShare(gradientLength, mmv_surfaceEqualShare);

  p.irradiance0 = vec4(0.0);
  p.irradiance1 = vec4(0.0);
  p.sky = vec4(0.0);
#if MMV_USE_SKY
  p.sky = texture(mmv_sky, mmvWholeTexCoord(texPos) * mmv_skyScale + mmv_skyBias);
#endif
#if MMV_NUMBER_OF_LIGHTS > 0
  vec3 irradianceCoord = mmvWholeTexCoord(texPos) * mmv_irradianceScale + mmv_irradianceBias;
  p.irradiance0 = texture(mmv_irradiance0, irradianceCoord);
#if MMV_IRRADIANCE_TEXTURES > 1
  p.irradiance1 = texture(mmv_irradiance1, irradianceCoord);
#endif
#if MMV_USE_RGB_IRRADIANCE
  mmvFetchTints(irradianceCoord);
#endif
#endif
  return p;
}

// eqs. 16-17 at point p with value t of field `field` for one segment: reads
// the field's material, then mmvShadeSample() (mmvShading.glsl) does the
// arithmetic.
vec3 mmvShadeField(mmvSamplePoint p, float t, vec4 segment, int field)
{
  float tc = mmvTableCoord(t);
  int rows = field * MMV_MATERIAL_ROWS;
  vec4 material = texture2D(mmv_material, vec2(tc, mmvMaterialRow(rows + MMV_BLINN_PHONG_ROW)));
  float anisotropy = 0.0;
#if MMV_USE_ANISOTROPY
  anisotropy = mmvMaterialParameter(tc, rows + MMV_ANISOTROPY_ROW, MMV_ANISOTROPY_CHANNEL);
#endif
  float reflection = 0.0;
  vec3 environment = vec3(0.0);
#if MMV_USE_REFLECTION
  reflection = mmvMaterialParameter(tc, rows + MMV_REFLECTION_ROW, MMV_REFLECTION_CHANNEL);
  if (reflection > 0.0)
  {
    environment = mmvReflectedRadiance(p.position, p.n, p.v);
  }
#endif
  float emission = 0.0;
#if MMV_USE_EMISSION
  emission = mmvMaterialParameter(tc, rows + MMV_EMISSION_ROW, MMV_EMISSION_CHANNEL);
#endif
  vec3 radiance = mmvShadeSample(material, anisotropy, reflection, emission, segment, p.position,
    p.n, p.v, p.surface, p.irradiance0, p.irradiance1, environment);
#if MMV_USE_SKY
  radiance += mmvSkyRadiance(material, segment, p.n, p.surface, p.sky, mmv_skyMean, mmv_skySlope);
#endif
  return radiance;
}

// One field's segment shaded at texPos with value t.
vec3 mmvShadeSegment(vec3 texPos, float t, vec4 segment, int field)
{
  return mmvShadeField(mmvFetchSamplePoint(texPos), t, segment, field);
}

// The segment's length relative to the tables' step: partial first/last
// segments and VTK's automatic sample distance differ from it.
float mmvStepRatio(vec3 x1, vec3 x2)
{
  return length(x2 - x1) / max(length(g_dirStep), 1e-30) * in_sampleDistance / mmv_tableStep;
}

// A table's segment for `ratio` times its step: exact for the opacity, and
// exact for the colour of uniform segments.
vec4 mmvScaleSegment(vec4 segment, float ratio)
{
  if (segment.a > 0.0 && abs(ratio - 1.0) > 1e-3)
  {
    float alpha = 1.0 - pow(max(1.0 - segment.a, 0.0), ratio);
    segment.rgb *= alpha / segment.a;
    segment.a = alpha;
  }
  return segment;
}

#if MMV_FIELDS > 1
// The v coordinate of value t in field f's block of the stacked tables.
float mmvFieldTableCoord(int f, float t)
{
  return (float(f) * mmv_tableSize + clamp(t, 0.0, 1.0) * (mmv_tableSize - 1.0) + 0.5) /
    (mmv_tableSize * float(MMV_FIELDS));
}

// Several fields: each field's segment from its own tables; together they
// let through the product of their transmittances, and each is shaded with
// its share of the combined opacity (its colour scaled alike) at one point.
void mmvIntegrateSegment(vec3 x1, vec4 t1, vec3 x2, vec4 t2)
{
  float ratio = mmvStepRatio(x1, x2);
  if (ratio <= 0.0)
  {
    return;
  }
  vec4 segments[MMV_FIELDS];
  vec2 coords[MMV_FIELDS];
  float transmittance = 1.0;
  float opacitySum = 0.0;
  for (int f = 0; f < MMV_FIELDS; ++f)
  {
#if MMV_USE_PREINTEGRATION
    coords[f] = vec2(mmvTableCoord(t1[f]), mmvFieldTableCoord(f, t2[f]));
#else
    coords[f] = vec2(mmvTableCoord(t2[f]), mmvFieldTableCoord(f, t2[f]));
#endif
    segments[f] = mmvScaleSegment(texture2D(mmv_preintColor, coords[f]), ratio);
    transmittance *= 1.0 - segments[f].a;
    opacitySum += segments[f].a;
  }
  float alpha = 1.0 - transmittance;
  if (alpha <= 0.0)
  {
    return;
  }
  // One shading point for all fields (their shading positions weighted by
  // opacity), read once; each field is shaded there with its own value.
#if MMV_USE_PREINTEGRATION
  float beta = 0.0;
  for (int f = 0; f < MMV_FIELDS; ++f)
  {
    beta += segments[f].a * texture2D(mmv_preintBeta, coords[f]).r;
  }
  beta /= opacitySum;
#else
  float beta = 1.0;
#endif
  mmvSamplePoint point = mmvFetchSamplePoint(mix(x1, x2, beta));
  vec3 radiance = vec3(0.0);
  for (int f = 0; f < MMV_FIELDS; ++f)
  {
    if (segments[f].a > 0.0)
    {
      radiance += mmvShadeField(
        point, mix(t1[f], t2[f], beta), segments[f] * (alpha / opacitySum), f);
    }
  }
  g_fragColor.rgb += (1.0 - g_fragColor.a) * radiance;
  g_fragColor.a += (1.0 - g_fragColor.a) * alpha;
}
#else
// Integrates the segment x1 -> x2 (texture coordinates) with values t1, t2 and
// composites it front to back into g_fragColor.
void mmvIntegrateSegment(vec3 x1, float t1, vec3 x2, float t2)
{
  float ratio = mmvStepRatio(x1, x2);
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
  segment = mmvScaleSegment(segment, ratio);
#if MMV_USE_PREINTEGRATION
  float beta = texture2D(mmv_preintBeta, tc).r;
#else
  float beta = 1.0;
#endif
  vec3 radiance = mmvShadeSegment(mix(x1, x2, beta), mix(t1, t2, beta), segment, 0);
  g_fragColor.rgb += (1.0 - g_fragColor.a) * radiance;
  g_fragColor.a += (1.0 - g_fragColor.a) * segment.a;
}
#endif
