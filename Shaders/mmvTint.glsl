// The tint of each light's irradiance (a non-white transmission colour,
// vtkMultiMaterialParameters.h): light k arrives as its grey irradiance
// times mmv_lightTint[k] (K per channel, from its RGBA16F texture on the
// tint grid). Only in the MMV_USE_RGB_IRRADIANCE variant, before
// mmvShading.glsl; mmvShadeSegment (mmvRayCastDec.glsl) fills mmv_lightTint
// by mmvFetchTints before it shades.

uniform vec3 mmv_tintScale; // irradiance texture coordinate -> tint texture coordinate
uniform vec3 mmv_tintBias;
uniform sampler3D mmv_tint0;
#if MMV_NUMBER_OF_LIGHTS > 1
uniform sampler3D mmv_tint1;
#endif
#if MMV_NUMBER_OF_LIGHTS > 2
uniform sampler3D mmv_tint2;
#endif
#if MMV_NUMBER_OF_LIGHTS > 3
uniform sampler3D mmv_tint3;
#endif
#if MMV_NUMBER_OF_LIGHTS > 4
uniform sampler3D mmv_tint4;
#endif
#if MMV_NUMBER_OF_LIGHTS > 5
uniform sampler3D mmv_tint5;
#endif
#if MMV_NUMBER_OF_LIGHTS > 6
uniform sampler3D mmv_tint6;
#endif
#if MMV_NUMBER_OF_LIGHTS > 7
uniform sampler3D mmv_tint7;
#endif

vec3 mmv_lightTint[MMV_NUMBER_OF_LIGHTS];

// Separate samplers, not an array: GLSL 1.50 indexes sampler arrays only by
// constant expressions.
void mmvFetchTints(vec3 irradianceCoord)
{
  vec3 c = irradianceCoord * mmv_tintScale + mmv_tintBias;
  mmv_lightTint[0] = texture(mmv_tint0, c).rgb;
#if MMV_NUMBER_OF_LIGHTS > 1
  mmv_lightTint[1] = texture(mmv_tint1, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 2
  mmv_lightTint[2] = texture(mmv_tint2, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 3
  mmv_lightTint[3] = texture(mmv_tint3, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 4
  mmv_lightTint[4] = texture(mmv_tint4, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 5
  mmv_lightTint[5] = texture(mmv_tint5, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 6
  mmv_lightTint[6] = texture(mmv_tint6, c).rgb;
#endif
#if MMV_NUMBER_OF_LIGHTS > 7
  mmv_lightTint[7] = texture(mmv_tint7, c).rgb;
#endif
}
