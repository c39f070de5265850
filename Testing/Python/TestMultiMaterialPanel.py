"""The Properties panel of a Multi-Material Volume display shows exactly the
controls that act on it: its own choices (at most 10), Volume's controls that
act on its image (Scalar Opacity Unit Distance, Blend Mode, cropping), and
none of the surface controls or of the internals that Lighting Quality sets.

The panel is built by pqProxyWidget from the proxy's XML: a property is
shown unless its panel_visibility is "never", and its decorators (its own
hints and those of the last property group that lists it) must all allow it.
This test reads those from the server manager and evaluates the decorators
the panel uses here (GenericDecorator, CompositeDecorator), for the default
and the advanced (gear) view. It also checks that Lighting Quality sets the
internals and that Volume's panel is as ParaView's own."""

from paraview import servermanager as sm
from paraview import simple

import mmv_panel_sets as sets
import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()

# Controls whose decorators this emulation cannot evaluate without the GUI
# (they hide themselves for one-component data or without OSPRay).
UNEVALUATED = {"OSPRayHidingDecorator", "MultiComponentsDecorator", "ShowWidgetDecorator"}


def value_of(proxy, name):
    prop = proxy.GetProperty(name)
    helper = sm.vtkSMPropertyHelper(proxy, name)
    if isinstance(prop, sm.vtkSMStringVectorProperty):
        return [helper.GetAsString(i) for i in range(helper.GetNumberOfElements())]
    return [str(helper.GetAsInt(i)) if isinstance(prop, sm.vtkSMIntVectorProperty)
            else str(helper.GetAsDouble(i)) for i in range(helper.GetNumberOfElements())]


def evaluate(proxy, element):
    """Whether a decorator (or Expression) element allows the widget."""
    name = element.GetName()
    if name == "Expression":
        results = [evaluate(proxy, element.GetNestedElement(i))
                   for i in range(element.GetNumberOfNestedElements())]
        return all(results) if element.GetAttribute("type") == "and" else any(results)
    kind = element.GetAttribute("type")
    if kind == "CompositeDecorator":
        return all(evaluate(proxy, element.GetNestedElement(i))
                   for i in range(element.GetNumberOfNestedElements()))
    if kind == "GenericDecorator":
        if element.GetAttribute("mode") != "visibility":
            return True
        wanted = element.GetAttribute("value")
        wanted = [wanted] if wanted is not None else element.GetAttribute("values").split()
        current = value_of(proxy, element.GetAttribute("property"))
        match = any(v in current for v in wanted)
        return not match if element.GetAttribute("inverse") == "1" else match
    if kind in UNEVALUATED:
        return False
    raise RuntimeError("decorator %s not evaluated" % kind)


def decorators(hints):
    found = []
    if hints is None:
        return found
    for i in range(hints.GetNumberOfNestedElements()):
        child = hints.GetNestedElement(i)
        if child.GetName() == "PropertyWidgetDecorator":
            found.append(child)
    return found


def panel(display, advanced):
    """Names the panel shows: properties, and custom group widgets as 'group:<label>'."""
    proxy = display.SMProxy
    shown = set()
    it = proxy.NewPropertyIterator()
    it.Begin()
    while not it.IsAtEnd():
        key, prop = it.GetKey(), it.GetProperty()
        it.Next()
        visibility = prop.GetPanelVisibility() or "default"
        # Representations show no widget for their inputs.
        if (prop.GetInformationOnly() or prop.GetIsInternal() or visibility == "never"
                or isinstance(prop, sm.vtkSMInputProperty)):
            continue
        if visibility == "advanced" and not advanced:
            continue
        group = None
        for g in range(proxy.GetNumberOfPropertyGroups()):
            candidate = proxy.GetPropertyGroup(g)
            if any(candidate.GetProperty(p) is prop or candidate.GetProperty(p) == prop
                   for p in range(candidate.GetNumberOfProperties())):
                group = candidate  # the last group wins, as in pqProxyWidget
        hints = decorators(prop.GetHints())
        label = key
        if group is not None:
            gvis = group.GetPanelVisibility() or "default"
            # "multiblock_inspector" groups live in another panel.
            if gvis not in ("default", "advanced") or (gvis == "advanced" and not advanced):
                continue
            hints += decorators(group.GetHints())
            if group.GetPanelWidget():
                label = "group:" + group.GetXMLLabel()
        if all(evaluate(proxy, d) for d in hints):
            shown.add(label)
    return shown


view = mmv.make_view()
source = mmv.make_volume()
display = mmv.show_volume(source, view, preset="bone")
simple.Render(view)

OWN, INTERNALS, DEAD = sets.OWN, sets.INTERNALS, sets.DEAD

advanced = panel(display, True)
default = panel(display, False)
print("advanced:", sorted(advanced))
print("default:", sorted(default))
expected_advanced = sets.ADVANCED
checker.check(advanced == expected_advanced,
              "advanced panel is the expected set (extra %s, missing %s)"
              % (sorted(advanced - expected_advanced), sorted(expected_advanced - advanced)))
checker.check(not (advanced & (DEAD | INTERNALS)),
              "no dead control or internal is shown: %s" % sorted(advanced & (DEAD | INTERNALS)))
# PointLightRadius shows with its falloff: 9 of our own at most.
checker.check(len(advanced & OWN) + 1 <= 10,
              "%d own controls shown (at most 10)" % (len(advanced & OWN) + 1))
checker.check(default == sets.DEFAULT,
              "default panel is the expected set (extra %s, missing %s)"
              % (sorted(default - sets.DEFAULT), sorted(sets.DEFAULT - default)))

# Cropping's box appears with Use Cropping; the falloff radius with its falloff.
display.UseCropping = 1
display.LightFalloff = "Inverse Square Beyond Radius"
shown = panel(display, True)
checker.check(shown == sets.ADVANCED | sets.WITH_CROPPING_AND_RADIUS,
              "Use Cropping shows the cropping box, Inverse Square Beyond Radius its radius "
              "(extra %s, missing %s)" % (sorted(shown - sets.ADVANCED - sets.WITH_CROPPING_AND_RADIUS),
                                          sorted((sets.ADVANCED | sets.WITH_CROPPING_AND_RADIUS) - shown)))
display.UseCropping = 0
display.LightFalloff = "Light Attenuation"
checker.check("PointLightRadius" not in panel(display, True),
              "Light Attenuation hides the radius")

# Lighting Quality sets the internals (and keeps them in the state), and an
# internal set apart from its level makes the level Custom.
display.LightingQuality = "Exact"
checker.check(display.ShadowEstimation == "Full Shadow Rays" and display.IrradianceScale == 1.0
              and display.ReflectionVisibility == "Through The Volume, Per Sample",
              "Exact sets full shadow rays, scale 1, per-sample reflection visibility")
display.LightingQuality = "Fast"
checker.check(display.PiecewiseShadowSlices == 4 and display.IrradianceMemoryMB == 16.0,
              "Fast sets 4 slices and 16 MB (got %s, %s)"
              % (display.PiecewiseShadowSlices, display.IrradianceMemoryMB))
display.PiecewiseShadowSlices = 8
checker.check(display.LightingQuality == "Custom",
              "an internal set apart from its level makes it Custom (got %s)" % display.LightingQuality)
display.LightingQuality = "Balanced"
checker.check(display.PiecewiseShadowSlices == 16 and display.IrradianceMemoryMB == 64.0
              and display.LightingQuality == "Balanced", "Balanced restores the defaults")

# Volume's panel is ParaView's: it keeps Edge Styling and its own groups.
display.SetRepresentationType("Volume")
volume = panel(display, True)
checker.check("Opacity" not in volume and "EdgeColor" in volume and "BlendMode" in volume
              and "LightingQuality" not in volume and "MaterialNodes" not in volume,
              "Volume's panel is unchanged and has none of ours")
display.SetRepresentationType("Surface")
surface = panel(display, True)
checker.check({"Opacity", "Specular", "PointSize", "EdgeColor", "Triangulate"} <= surface
              and not (surface & (OWN | {"BlendMode"})), "Surface's panel keeps its controls")

checker.finish()
