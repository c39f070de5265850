# The scene of the progress GUI test, shared by the client's startup script
# (setup_progress.py) and the reference render (progress_reference.py): the
# fine-structured chest of Testing/Benchmark/mmv_fine_volume.py as
# 'Multi-Material Volume' under the view's light kit, a fixed camera and a
# fixed irradiance grid (the screen-dependent automatic grid would differ
# between the client's view and the reference's), and the opacity edit.
import os
import sys

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Benchmark"))
import mmv_fine_volume  # noqa: E402

ARRAY = "ImageFile"
DIMS = (256, 256, 128)
OPACITY_POINTS = [0.0, 0.0, 0.5, 0.0, 500.0, 0.0, 0.5, 0.0, 800.0, 0.12, 0.5, 0.0,
                  1100.0, 0.2, 0.5, 0.0, 1400.0, 0.8, 0.5, 0.0, 3926.0, 0.9, 0.5, 0.0]
RGB_POINTS = [0.0, 0.0, 0.0, 0.0, 500.0, 0.35, 0.3, 0.28, 900.0, 0.78, 0.68, 0.62,
              1400.0, 0.93, 0.9, 0.82, 3926.0, 1.0, 1.0, 1.0]
CAMERA = dict(CameraPosition=[127.5, 620.0, 63.5], CameraFocalPoint=[127.5, 127.5, 63.5],
              CameraViewUp=[0.0, 0.0, 1.0], CameraViewAngle=30.0)
IMAGE_SIZE = [400, 400]


def volume_path(folder):
    """The chest, written once into `folder`."""
    path = os.path.join(folder, "chest_%dx%dx%d.vti" % DIMS)
    if not os.path.exists(path):
        mmv_fine_volume.write_vti(path, mmv_fine_volume.chest(DIMS))
    return path


def show(path, view):
    """The representation of the chest in `view`, rendered once."""
    reader = simple.XMLImageDataReader(registrationName="Chest", FileName=[path])
    display = simple.Show(reader, view)
    display.SetRepresentationType("Multi-Material Volume")
    simple.ColorBy(display, ("POINTS", ARRAY))
    lut = simple.GetColorTransferFunction(ARRAY)
    lut.RGBPoints = RGB_POINTS
    lut.ScalarRangeInitialized = 1.0
    pwf = simple.GetOpacityTransferFunction(ARRAY)
    pwf.Points = OPACITY_POINTS
    pwf.ScalarRangeInitialized = 1
    display.ScalarOpacityUnitDistance = 2.0
    # The full grid and a scattering material: an update of over a second on
    # llvmpipe (shadows and diffusion), so the bar has time to move, and the
    # same grid whatever the view's size.
    display.IrradianceScale = 1.0
    display.MaterialPreset = "skin"
    view.OrientationAxesVisibility = 0
    view.Background = [0.1, 0.1, 0.15]
    for key, value in CAMERA.items():
        setattr(view, key, value)
    simple.SetActiveSource(reader)
    simple.Render(view)
    return display


def edit_opacity():
    """One opacity point raised, as a drag in the colour-map editor does:
    every light's irradiance is recomputed."""
    pwf = simple.GetOpacityTransferFunction(ARRAY)
    points = list(pwf.Points)
    points[13] += 0.1  # the 1100 point's opacity
    pwf.Points = points
