// Environment reflection of Zhang & Ma eq. 17: r I(x, w_r) c_r(w_r), with
// w_r the view direction mirrored about the shading normal. Only in the
// variants where some material has r > 0 (MMV_USE_REFLECTION). Mirrors the
// reference renderer (vtkMultiMaterialEnvironment::Lookup and
// vtkMultiMaterialEnvironmentLookup.h for c_r).
//
// MMV_ENVIRONMENT (mmv::EnvironmentKind) selects c_r: 0, the background's
// vertical gradient around the view-up; 1, the renderer's cube map; 2, its
// equirectangular image, both in the frame VTK's skybox uses.
// MMV_REFLECTION_VISIBILITY (mmv::ReflectionVisibility) selects I: 0, 1
// (unoccluded); 1, mmvReflectionVisibility() (mmvReflectionMarch.glsl, with
// mmvShadowRay.glsl, its prelude and mmvCutaway.glsl, before this file) from
// each shaded sample (Algorithm 1 lines 10-11 done per sample); 2, the same
// march done once per irradiance voxel when the camera or the volume
// changes (vtkReflectionVisibilityPass), interpolated here.

uniform vec3 mmv_environmentUp; // object space
uniform vec3 mmv_environmentBottom;
uniform vec3 mmv_environmentTop;
#if MMV_ENVIRONMENT != 0
// vtkRenderer's EnvironmentRight, EnvironmentUp and up x right, pulled back
// to object space: dot(w, axis) is the world direction's component.
uniform vec3 mmv_environmentFrameRight;
uniform vec3 mmv_environmentFrameUp;
uniform vec3 mmv_environmentFrameFront;
uniform int mmv_environmentGrey; // one or two components: grey in every channel
#if MMV_ENVIRONMENT == 1
uniform samplerCube mmv_environmentTexture;
#else
uniform sampler2D mmv_environmentTexture;
#endif
#endif
#if MMV_REFLECTION_VISIBILITY == 2
uniform sampler3D mmv_reflectionVisibility; // I per irradiance voxel, linear
uniform mat3 mmv_visibilityToIndex;         // object space -> irradiance grid index
uniform vec3 mmv_visibilityOrigin;          // object position of grid index (0, 0, 0)
uniform vec3 mmv_visibilityDims;
#endif

// c_r along object-space direction d (not zero).
vec3 mmvEnvironmentColor(vec3 d)
{
#if MMV_ENVIRONMENT == 0
  return mmvEnvironment(normalize(d), mmv_environmentUp, mmv_environmentBottom, mmv_environmentTop);
#else
  vec3 e = vec3(dot(d, mmv_environmentFrameRight), dot(d, mmv_environmentFrameUp),
    dot(d, mmv_environmentFrameFront));
#if MMV_ENVIRONMENT == 1
  vec4 c = textureLod(mmv_environmentTexture, e, 0.0);
#else
  float horizontal = length(e.xz);
  // atan(0, 0) is undefined in GLSL: straight up or down has longitude 0.
  float longitude = horizontal > 0.0 ? atan(e.x, e.z) : 0.0;
  vec2 uv = vec2(0.5 * longitude / 3.14159265 + 0.5, atan(e.y, horizontal) / 3.14159265 + 0.5);
  vec4 c = textureLod(mmv_environmentTexture, uv, 0.0);
#endif
  return mmv_environmentGrey != 0 ? c.rrr : c.rgb;
#endif
}


// r I c_r without r: the reflected radiance reaching object point x along
// the mirror direction of view vector v about n (unit, facing v, or zero).
vec3 mmvReflectedRadiance(vec3 x, vec3 n, vec3 v)
{
  vec3 mirrored = reflect(-v, n);
  vec3 c = mmvEnvironmentColor(mirrored);
#if MMV_REFLECTION_VISIBILITY == 1
  c *= mmvReflectionVisibility(x, n, mirrored);
#elif MMV_REFLECTION_VISIBILITY == 2
  vec3 index = mmv_visibilityToIndex * (x - mmv_visibilityOrigin);
  c *= texture(mmv_reflectionVisibility, (index + 0.5) / mmv_visibilityDims).r;
#endif
  return c;
}
