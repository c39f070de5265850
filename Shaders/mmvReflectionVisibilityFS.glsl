// The view-dependent visibility pass (vtkReflectionVisibilityPass): I(x, w_r)
// of eq. 17 at every irradiance voxel, for the camera of this frame
// (Algorithm 1 lines 10-11: recomputed when the camera or the volume
// changes). The ray cast interpolates it (MMV_REFLECTION_VISIBILITY 2).
// After mmvVoxelPassDec.glsl, mmvShadowRay.glsl and mmvReflectionMarch.glsl.
//
// At the voxel, w_r mirrors the view direction about the normal of the
// pre-filtered data (central differences at irradiance resolution: the
// gradient the ray cast shades with, smoothed to this grid), two-sided as
// the ray cast's; where the gradient vanishes, n = 0 and w_r = -v, as there.

uniform mat3 mmv_visibilityToObject; // grid index -> object space (inverse of ToIndex)
uniform vec4 mmv_eye; // object space: the camera's position (w = 1) or, parallel, toward it (w = 0)
// Normalised values outside which no material reflects
// (vtkMultiMaterialReflection::SetReflectiveValues; 0..1: all of them).
uniform vec2 mmv_reflectiveRange;

// Whether the ray cast can shade a reflecting sample whose interpolation
// reaches this voxel: some segment from it to one of its 26 neighbours has
// extinction (pre-integrated, so a thin opaque value range between the two
// counts) and spans a value that reflects.
bool mmvNearReflectiveMaterial(vec3 index)
{
  float centre = mmvSampleScalar(index);
  for (int k = -1; k <= 1; ++k)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int i = -1; i <= 1; ++i)
      {
        float neighbour = mmvSampleScalar(index + vec3(i, j, k));
        if (max(centre, neighbour) >= mmv_reflectiveRange.x &&
          min(centre, neighbour) <= mmv_reflectiveRange.y &&
          mmvShadowOpacity(centre, neighbour) > 0.0)
        {
          return true;
        }
      }
    }
  }
  return false;
}

void mmvVoxelMain()
{
  vec3 index = vec3(floor(texCoord * vec2(dims[0], dims[1])), float(slice));
  if (!mmvNearReflectiveMaterial(index))
  {
    // Empty or not reflecting: no reflection is shaded with it; the march
    // is skipped.
    mmvWrite(vec4(1.0));
    return;
  }
  vec3 x = mmv_visibilityOrigin + mmv_visibilityToObject * index;
  vec3 gradientIndex = 0.5 * vec3(
    mmvSampleScalar(index + vec3(1.0, 0.0, 0.0)) - mmvSampleScalar(index - vec3(1.0, 0.0, 0.0)),
    mmvSampleScalar(index + vec3(0.0, 1.0, 0.0)) - mmvSampleScalar(index - vec3(0.0, 1.0, 0.0)),
    mmvSampleScalar(index + vec3(0.0, 0.0, 1.0)) - mmvSampleScalar(index - vec3(0.0, 0.0, 1.0)));
  // A gradient is a covector: index -> object by the transpose of ToIndex.
  vec3 gradient = transpose(mmv_visibilityToIndex) * gradientIndex;
  vec3 v = mmv_eye.w != 0.0 ? normalize(mmv_eye.xyz - x) : normalize(mmv_eye.xyz);
  float gradientLength = length(gradient);
  vec3 n = gradientLength > 0.0 ? -gradient / gradientLength : vec3(0.0);
  n = dot(n, v) < 0.0 ? -n : n;
  mmvWrite(vec4(mmvReflectionVisibility(x, n, reflect(-v, n))));
}
