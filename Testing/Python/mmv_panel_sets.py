"""The Properties panel of a Multi-Material Volume display of image data:
the controls it shows, by property name ("group:<label>" for a group's own
widget). PVMultiMaterialPanel (from the proxy XML) and GUI.PropertiesPanel
(the real client's widgets) assert the same sets."""

OWN = {"MaterialNodes", "LightingQuality", "FieldArrays", "MultipleScattering", "EnvironmentLighting",
       "ReflectionSource", "GradientSmoothing", "LightFalloff",
       "SamplingDimensions"}
VOLUME = {"ScalarOpacityUnitDistance", "BlendMode", "UseCropping"}
PARAVIEW = {"Representation", "group:Coloring", "MapScalars", "Position", "Scale", "Orientation",
            "Origin", "Pickable", "PolarAxes", "DataAxesGrid"}
INTERNALS = {"InteractiveIrradiance", "ShadowEstimation", "PiecewiseShadowSlices", "ExponentialDiffusion",
             "PieceIrradianceOnly", "LightDirectionTolerance", "ReflectionVisibility",
             "IrradianceErrorBound", "IrradianceMemoryMB", "IrradianceScale", "DimLightCoarsening"}
DEAD = {"Opacity", "Specular", "PointSize", "LineWidth", "Texture", "group:Edge Styling",
        "EdgeColor", "BackfaceRepresentation", "Triangulate", "NonlinearSubdivisionLevel",
        "Interpolation", "SpecularPower", "Ambient", "Diffuse", "MaterialPreset"}

# The gear's advanced view, and the default view.
ADVANCED = OWN | VOLUME | PARAVIEW
DEFAULT = {"MaterialNodes", "LightingQuality", "FieldArrays", "MultipleScattering",
           "EnvironmentLighting", "BlendMode",
           "UseCropping", "Representation", "group:Coloring", "DataAxesGrid"}
# Shown besides ADVANCED with UseCropping on and the inverse-square falloff.
WITH_CROPPING_AND_RADIUS = {"group:Cropping Parameters", "PointLightRadius"}


# A group's own widget is named after its panel_widget.
GROUP_WIDGETS = {"ColorEditor": "group:Coloring", "InteractiveBox": "group:Cropping Parameters"}


def gui_name(object_name, property_name, class_name):
    """The set's name of a pqPropertyWidget the probe recorded."""
    if property_name != "-":
        return property_name
    return GROUP_WIDGETS.get(object_name, "group:" + object_name)
