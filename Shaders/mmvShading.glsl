// Shading of one ray segment: Zhang & Ma eq. 16 (Blinn-Phong with the ambient
// term inside the per-light sum, so occlusion darkens it too) and the
// environment term of eq. 17. Mirrors Filters/vtkMultiMaterialShading.h.
// Prepended after the variant's defines, the light uniforms, mmvLightModel.glsl
// and (when the variant uses them) mmvPhaseFunction.glsl and mmvEmission.glsl.
//
// material: x = ka, y = kd, z = ks, w = shininess ke
// segment:  rgb = pre-integrated opacity-weighted colour I_c, a = I_alpha
// n: unit normal facing the viewer (zero where there is no surface)
// v: unit vector toward the viewer, l: unit vector toward the light
// directional: 0..1 weight of the normal-based terms; it fades them out where
// the gradient vanishes (homogeneous regions), leaving ambient shading.

vec3 mmvBlinnPhong(vec4 material, vec4 segment, vec3 n, vec3 v, vec3 l, float directional)
{
  float ndotl = max(dot(n, l), 0.0);
  vec3 h = v + l;
  float hlen = length(h);
  // v = -l (light straight behind the surface) has no half vector.
  float ndoth = hlen > 0.0 ? max(dot(n, h / hlen), 0.0) : 0.0;
  // pow(0, 0) is undefined in GLSL: shininess 0 means a flat highlight.
  float highlight = material.w > 0.0 ? pow(ndoth, material.w) : 1.0;
  vec3 ambientDiffuse = (material.x + directional * material.y * ndotl) * segment.rgb;
  return ambientDiffuse + vec3(directional * material.z * highlight * segment.a);
}

// Environment colour seen along unit direction d: a vertical gradient from
// `bottom` to `top` around the unit `up` axis (the renderer's background
// colours when it has no environment texture).
vec3 mmvEnvironment(vec3 d, vec3 up, vec3 bottom, vec3 top)
{
  return mix(bottom, top, clamp(0.5 + 0.5 * dot(d, up), 0.0, 1.0));
}

// The radiance of one segment (the arithmetic of mmvShadeSegment() once it
// has read the textures): eq. 16 summed over the lights, eq. 17's environment
// term and emission. Mirrors mmvShadeSample in vtkMultiMaterialShading.h.
// material: the Blinn-Phong texel (ka, kd, ks, ke); anisotropy, reflection,
// emission: g, r, e; position: the shading point (object space); n, v,
// directional: as mmvBlinnPhong; irradiance0/1: each light's irradiance
// (lights 0-3, 4-7), its geometry and radiance in the light uniforms
// (vtkMultiMaterialLightUniforms.h); environment: the environment's radiance
// along the mirrored view direction.
vec3 mmvShadeSample(vec4 material, float anisotropy, float reflection, float emission,
  vec4 segment, vec3 position, vec3 n, vec3 v, float directional, vec4 irradiance0,
  vec4 irradiance1, vec3 environment)
{
  vec3 radiance = vec3(0.0);
#if MMV_NUMBER_OF_LIGHTS > 0
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
    float lightDistance;
    vec3 l = mmvDirectionToLight(
      mmv_lightKind[k], mmv_lightPosition[k], mmv_lightToLight[k], position, lightDistance);
    vec4 lit = material;
#if MMV_USE_ANISOTROPY
    // The particle (ambient) term in-scatters by the phase function.
    lit.x *= mmvHenyeyGreensteinRelative(anisotropy, -dot(v, l));
#endif
    radiance +=
      irradiance * mmv_lightRadiance[k] * mmvBlinnPhong(lit, segment, n, v, l, directional);
  }
#else
  // No active light: ambient emission only, so the volume stays visible.
  radiance = material.x * segment.rgb;
#endif
#if MMV_USE_REFLECTION
  if (reflection > 0.0)
  {
    radiance += directional * reflection * segment.a * environment;
  }
#endif
#if MMV_USE_EMISSION
  radiance += mmvEmission(emission, segment);
#endif
  return radiance;
}
