// Shading of one ray segment: Zhang & Ma eq. 16 (Blinn-Phong with the ambient
// term inside the per-light sum, so occlusion darkens it too) and the
// environment term of eq. 17. Mirrors Rendering/vtkMultiMaterialShading.h.
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
