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
// directional: 0..1 weight of the normal-based terms (the surface share).

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

// The hybrid surface/particle model (Yang et al. eqs. 5-8): the share of a
// segment's extinction that surface elements hold. With one opacity transfer
// function for both elements (the paper's Fig. 4c), mu_s / mu_p =
// |grad| / equalShare, where equalShare = Delta v_std / Delta l_std. Our
// segment opacity is the transfer function's whatever the angle, so the share
// is taken over all ray directions (|dv/dl| averages |grad| / 2 over them: the
// 1/2 is part of equalShare), which keeps a sharp boundary plain Blinn-Phong
// up to its silhouette. The share is 0 where the gradient is 0 (homogeneous
// regions get no normal, by construction rather than by a threshold) and
// tends to 1 across sharp boundaries.
// gradientLength: |grad|; equalShare > 0 (both normalised value per object unit).
float mmvSurfaceShare(float gradientLength, float equalShare)
{
  return gradientLength / (gradientLength + equalShare);
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
// The hybrid model mixes the surface's Blinn-Phong BRDF and the particles'
// phase function by the surface share w (mmvSurfaceShare): per light,
// w (ka + kd n.l) I_c + w ks h I_a + (1 - w) ka 4 pi HG(g) I_c; ka is the
// particles' albedo (inside the light sum, so shadows darken it too).
// material: the Blinn-Phong texel (ka, kd, ks, ke); anisotropy, reflection,
// emission: g, r, e; position: the shading point (object space); n, v: as
// mmvBlinnPhong; surface: the surface share w; irradiance0/1: each light's irradiance
// (lights 0-3, 4-7), its geometry and radiance in the light uniforms
// (vtkMultiMaterialLightUniforms.h); environment: the environment's radiance
// along the mirrored view direction.
vec3 mmvShadeSample(vec4 material, float anisotropy, float reflection, float emission,
  vec4 segment, vec3 position, vec3 n, vec3 v, float surface, vec4 irradiance0,
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
    // The particles' share in-scatters by the phase function; the surface's
    // ambient is the BRDF's.
    lit.x *= mix(mmvHenyeyGreensteinRelative(anisotropy, -dot(v, l)), 1.0, surface);
#endif
    radiance +=
      irradiance * mmv_lightRadiance[k] * mmvBlinnPhong(lit, segment, n, v, l, surface);
  }
#elif !MMV_USE_SKY
  // No active light and no sky: ambient emission only, so the volume stays
  // visible.
  radiance = material.x * segment.rgb;
#endif
#if MMV_USE_REFLECTION
  if (reflection > 0.0)
  {
    radiance += surface * reflection * segment.a * environment;
  }
#endif
#if MMV_USE_EMISSION
  radiance += mmvEmission(emission, segment);
#endif
  return radiance;
}

// The sky's radiance of one segment: the renderer's background as an
// infinitely distant environment, seen through the volume's visibility
// moments sky = (S0, S1) (Filters/vtkSkyVisibility.h), with the sky's
// radiance L(w) = mean + slope * w. Physical, as the path tracer's sky:
// albedo = the segment's colour; particles scatter isotropically,
// F0 / (4 pi); surfaces are Lambertian with the truth's diffuse weight
// (1 - ks), E(n) / pi:
//   F0 = int L T dw = mean S0 + slope S1,
//   E(n) = int L T max(n.w, 0) dw ~ F0 / 4 + F1.n / 2 (the clamped cosine's
//   order-1 fit), F1.n = mean (S1.n) + (slope n) S0 / 3 (the second moment
//   taken as isotropic).
// Mirrors mmvSkyRadiance in vtkMultiMaterialShading.h.
vec3 mmvSkyRadiance(vec4 material, vec4 segment, vec3 n, float surface, vec4 sky, vec3 mean,
  mat3 slope)
{
  vec3 f0 = mean * sky.x + slope * sky.yzw;
  vec3 f1n = mean * dot(sky.yzw, n) + (slope * n) * (sky.x / 3.0);
  vec3 e = max(0.25 * f0 + 0.5 * f1n, vec3(0.0));
  float diffuse = 1.0 - clamp(material.z, 0.0, 1.0);
  const float pi = 3.14159265358979;
  return ((1.0 - surface) * f0 / (4.0 * pi) + surface * diffuse * e / pi) * segment.rgb;
}
