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

void mmvVoxelMain()
{
  vec3 index = vec3(floor(texCoord * vec2(dims[0], dims[1])), float(slice));
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
