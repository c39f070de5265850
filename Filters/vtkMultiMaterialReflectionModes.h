/**
 * @file   vtkMultiMaterialReflectionModes.h
 * @brief  The choices of the reflection term (eq. 17): where its colour comes
 *         from and how its visibility is estimated (the mapper's
 *         ReflectionSource and ReflectionVisibility settings).
 */
#ifndef vtkMultiMaterialReflectionModes_h
#define vtkMultiMaterialReflectionModes_h

namespace mmv
{
/// Where reflections take their environment colour c_r from (eq. 17).
enum ReflectionSource
{
  /// The renderer's environment texture when one is set (cube map or
  /// equirectangular image), else the background colour or gradient.
  ReflectEnvironmentTexture = 0,
  /// The background colour or gradient, even when a texture is set.
  ReflectBackground = 1
};

/// How the visibility I(x, w_r) of eq. 17 is estimated.
enum ReflectionVisibility
{
  /// I = 1: reflections see the environment through the volume.
  UnoccludedReflections = 0,
  /// From each shaded sample, a march along w_r through the pre-filtered
  /// extinction the irradiance pass uses.
  MarchedReflectionVisibility = 1,
  /// The same march once per irradiance voxel, when the camera or the volume
  /// changes (vtkReflectionVisibilityPass), interpolated by the ray cast.
  ViewDependentReflectionVisibility = 2,
  /// Per frame, the cheaper of the two (the default): per sample while the
  /// view has fewer pixels than PerSampleMarchPixelsPerVoxel times the
  /// irradiance grid's voxels, else the view-dependent pass.
  AutomaticReflectionVisibility = 3
};
}

#endif
