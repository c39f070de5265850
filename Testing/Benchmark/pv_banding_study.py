"""Banding study of the demo scene (docs/stability.md, "Stripes on thin shells"): which setting removes the
stripes on the cheek and neck of docs/demo.png (run with scripts/pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_banding_study.py OUT [variant,variant...]

The demo's scene (Testing/Examples/MultiMaterialVolumeDemo.cxx: the MR head,
skin and bone, a warm camera key light and a cool spot light, 640 x 640) is
rendered once per variant; the stripes are measured as the RMS of the
luminance minus its 7 x 7 box blur over the cheek and neck (x 0.62-0.80,
y 0.35-0.60 of the image). Writes OUT/banding.csv, OUT/<variant>.png and
OUT/banding.png (the region of a few variants side by side, 2x).
"""
import sys, os, math
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkImagingCore import vtkImageResample
from vtkmodules.vtkRenderingCore import (vtkRenderWindow, vtkRenderer, vtkVolume, vtkVolumeProperty,
    vtkColorTransferFunction, vtkLight, vtkWindowToImageFilter)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa
import multimaterialvolume as m

OUT = sys.argv[1]
os.makedirs(OUT, exist_ok=True)
reader = vtkXMLImageDataReader()
ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
reader.SetFileName(os.path.join(ROOT, "Testing", "Data", "headsq.vti"))
reader.Update()
src = reader.GetOutput()

def render(name, gsmooth=0.0, smooth=0.0, ambient=False, iso=False, sd=None, jitter=False, preint=True, irr=None, lights="both",
           vtk_phong=False, atten=True, size=640):
    image = src
    if smooth > 0:
        from vtkmodules.vtkImagingGeneral import vtkImageGaussianSmooth
        g0 = vtkImageGaussianSmooth()
        g0.SetInputData(src)
        g0.SetDimensionality(3)
        g0.SetStandardDeviations(smooth, smooth, smooth * 3.2 / 1.5)
        g0.Update()
        image = g0.GetOutput()
    if iso:
        r = vtkImageResample()
        r.SetInputData(src)
        r.SetOutputSpacing(1.5, 1.5, 1.5)
        r.SetInterpolationModeToLinear()
        r.Update()
        image = r.GetOutput()
    lo, hi = image.GetPointData().GetScalars().GetRange()
    dr = hi - lo
    color = vtkColorTransferFunction()
    for x, c in ((0, (0, 0, 0)), (0.15, (.9, .6, .5)), (.28, (.9, .65, .55)), (.35, (1, .98, .9)), (1, (1, 1, .95))):
        color.AddRGBPoint(lo + x * dr, *c)
    op = vtkPiecewiseFunction()
    for x, a in ((0, 0), (.12, 0), (.18, .25), (.28, .25), (.33, .6), (1, .8)):
        op.AddPoint(lo + x * dr, a)
    prop = vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(op)
    prop.SetInterpolationTypeToLinear()
    prop.SetScalarOpacityUnitDistance(src.GetSpacing()[0])
    if vtk_phong:
        mapper = vtkOpenGLGPUVolumeRayCastMapper()
        prop.ShadeOn()
    else:
        mats = m.vtkMaterialTransferFunction()
        if ambient:
            mats.AddNode(lo + .2 * dr, 0.5, 0.0, 0.0, 15, 0.0, 0, 0)
        else:
            mats.AddNode(lo + .2 * dr, .35, .7, .3, 15, .5 if atten else 0.0, 8, 0)
            mats.AddNode(lo + .35 * dr, .2, .8, .2, 25, 1.0 if atten else 0.0, 1, 0)
        mapper = m.vtkMultiMaterialVolumeMapper()
        mapper.SetMaterialTransferFunction(mats)
        mapper.SetPreIntegration(preint)
        mapper.SetGradientSmoothing(gsmooth)
        if irr is not None:
            mapper.SetIrradianceScale(irr)
    mapper.SetInputData(image)
    if sd is not None:
        mapper.AutoAdjustSampleDistancesOff()
        mapper.SetSampleDistance(sd)
    mapper.SetUseJittering(1 if jitter else 0)
    vol = vtkVolume(); vol.SetMapper(mapper); vol.SetProperty(prop)
    ren = vtkRenderer(); ren.AddVolume(vol)
    ren.SetBackground(0.08, 0.09, 0.12); ren.SetBackground2(0.35, 0.38, 0.45); ren.GradientBackgroundOn()
    ren.ResetCamera()
    cam = ren.GetActiveCamera(); cam.Elevation(80); cam.OrthogonalizeViewUp(); cam.Azimuth(20)
    ren.ResetCamera(); cam.Zoom(1.3)
    c = src.GetCenter()
    if lights in ("both", "key"):
        key = vtkLight(); key.SetLightTypeToCameraLight(); key.SetPosition(-.6, .8, 1); key.SetFocalPoint(0, 0, 0)
        key.SetColor(1, .95, .85); ren.AddLight(key)
    if lights in ("both", "spot"):
        spot = vtkLight(); spot.SetLightTypeToSceneLight(); spot.PositionalOn(); spot.SetConeAngle(25)
        spot.SetPosition(c[0] + 300, c[1] - 150, c[2] + 50); spot.SetFocalPoint(c); spot.SetColor(.7, .8, 1)
        spot.SetIntensity(.8); ren.AddLight(spot)
    win = vtkRenderWindow(); win.SetOffScreenRendering(1); win.SetSize(size, size); win.AddRenderer(ren)
    win.Render()
    g = vtkWindowToImageFilter(); g.SetInput(win); g.ReadFrontBufferOff(); g.Update()
    w = vtkPNGWriter(); w.SetFileName(os.path.join(OUT, name + ".png")); w.SetInputConnection(g.GetOutputPort()); w.Write()
    arr = vtk_to_numpy(g.GetOutput().GetPointData().GetScalars()).reshape(size, size, -1)[:, :, :3].astype(float)
    info = ""
    if not vtk_phong:
        d = mapper.GetIrradianceDimensions(); info = "irr %dx%dx%d" % tuple(d)
    win.Finalize()
    return arr, info

def banding(arr, size=640):
    # Cheek and neck of the demo view (image rows bottom first).
    lum = arr.mean(axis=2)
    y0, y1, x0, x1 = int(.35 * size), int(.60 * size), int(.62 * size), int(.80 * size)
    roi = lum[y0:y1, x0:x1]
    # High-pass: minus a 7x7 box blur; the stripes are 3-6 px apart.
    k = 3
    pad = np.pad(lum, k, mode="edge")
    blur = np.zeros_like(lum)
    for dy in range(-k, k + 1):
        for dx in range(-k, k + 1):
            blur += pad[k + dy:k + dy + lum.shape[0], k + dx:k + dx + lum.shape[1]]
    blur /= (2 * k + 1) ** 2
    hp = (lum - blur)[y0:y1, x0:x1]
    return float(np.sqrt((hp ** 2).mean())), float(roi.mean())

variants = [
    ("default", {}),  # the demo as it is
    ("vtk_phong", {"vtk_phong": True}),
    ("jitter", {"jitter": True}),
    ("no_preint", {"preint": False}),
    ("sd_0.5", {"sd": 0.5}),
    ("sd_0.25", {"sd": 0.25}),
    ("iso_1.5", {"iso": True}),
    ("key_only", {"lights": "key"}),
    ("spot_only", {"lights": "spot"}),
    ("no_shadows", {"atten": False}),
    ("irr_0.5", {"irr": 0.5}),
    ("ambient_only", {"ambient": True}),
    ("smooth_0.5", {"smooth": 0.5}),
    ("smooth_1", {"smooth": 1.0}),
    ("gsmooth_0.5", {"gsmooth": 0.5}),
    ("gsmooth_1", {"gsmooth": 1.0}),
    ("gsmooth_2", {"gsmooth": 2.0}),
]
only = sys.argv[2].split(",") if len(sys.argv) > 2 else None
with open(os.path.join(OUT, "banding.csv"), "w") as f:
    f.write("variant,highpass_rms,roi_mean,info\n")
    for name, kw in variants:
        if only and name not in only:
            continue
        arr, info = render(name, **kw)
        hp, mean = banding(arr)
        print("%-12s high-pass RMS %.2f  mean %.1f  %s" % (name, hp, mean, info), flush=True)
        f.write("%s,%.3f,%.2f,%s\n" % (name, hp, mean, info))

# The region of a few variants side by side, doubled, for docs/stability.md, "Stripes on thin shells".
shown = [n for n in ("default", "vtk_phong", "sd_0.25", "ambient_only", "gsmooth_1", "smooth_1")
         if os.path.exists(os.path.join(OUT, n + ".png"))]
if shown:
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    crops = []
    for n in shown:
        r = vtkPNGReader(); r.SetFileName(os.path.join(OUT, n + ".png")); r.Update()
        d = r.GetOutput().GetDimensions()
        a = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).reshape(d[1], d[0], -1)[:, :, :3]
        c = a[::-1][150:400, 390:540]  # top row first
        crops.append(np.kron(c, np.ones((2, 2, 1), dtype=np.uint8)))
    m = np.concatenate(crops, axis=1)[::-1].copy()
    img = vtkImageData(); img.SetDimensions(m.shape[1], m.shape[0], 1)
    img.GetPointData().SetScalars(numpy_to_vtk(m.reshape(-1, 3), deep=True))
    w = vtkPNGWriter(); w.SetFileName(os.path.join(OUT, "banding.png")); w.SetInputData(img); w.Write()
    print("banding.png, left to right:", ", ".join(shown))
