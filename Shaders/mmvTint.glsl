// The tint of each light's irradiance (a non-white transmission colour,
// vtkMultiMaterialParameters.h): light k arrives at a sample with its grey
// irradiance and the radiance mmv_lightRadiance[k] times its tint K (per
// channel, from its RGBA16F texture on the tint grid). Only in the
// MMV_USE_RGB_IRRADIANCE variant, before mmvShading.glsl; mmvShadeSegment
// (mmvRayCastDec.glsl) fills the tinted radiances by mmvFetchTints before it
// shades. The reference renderer passes the same product to mmvShadeSample
// as the light's radiance.

uniform vec3 mmv_tintScale; // irradiance texture coordinate -> tint texture coordinate
uniform vec3 mmv_tintBias;
uniform sampler3D mmv_tint[MMV_NUMBER_OF_LIGHTS]; // light k's tint texture

// Each light's radiance as it arrives at the current sample.
vec3 mmv_tintedRadiance[MMV_NUMBER_OF_LIGHTS];

void mmvSetLightTint(int k, vec3 tint)
{
  mmv_tintedRadiance[k] = mmv_lightRadiance[k] * tint;
}

// One line per light: GLSL 1.50 indexes sampler arrays only by constant
// expressions, not by a loop's index.
void mmvFetchTints(vec3 irradianceCoord)
{
  vec3 c = irradianceCoord * mmv_tintScale + mmv_tintBias;
  mmvSetLightTint(0, texture(mmv_tint[0], c).rgb);
#if MMV_NUMBER_OF_LIGHTS > 1
  mmvSetLightTint(1, texture(mmv_tint[1], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 2
  mmvSetLightTint(2, texture(mmv_tint[2], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 3
  mmvSetLightTint(3, texture(mmv_tint[3], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 4
  mmvSetLightTint(4, texture(mmv_tint[4], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 5
  mmvSetLightTint(5, texture(mmv_tint[5], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 6
  mmvSetLightTint(6, texture(mmv_tint[6], c).rgb);
#endif
#if MMV_NUMBER_OF_LIGHTS > 7
  mmvSetLightTint(7, texture(mmv_tint[7], c).rgb);
#endif
}

// From here on (mmvShading.glsl's light loop) a light's radiance is the one
// that arrives through the tinted medium: mmvShading.glsl, shared by every
// variant, needs no RGB code of its own.
#define mmv_lightRadiance mmv_tintedRadiance
