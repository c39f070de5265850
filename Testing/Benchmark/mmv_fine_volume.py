"""A fine-structured CT-like volume of the project's own, for benchmarks:
a chest with a 2-voxel skin shell, ribs and vessels 1-2 voxels thick, a
spine and lungs, on a 256 x 256 x 128 grid (uint16, the MR head's range).

Thin shells and ribs lose their self-shadowing on any coarser irradiance
grid, so the error probe keeps the full grid on it: the opposite of the
smooth MR head. `write_series` writes time steps in which the vessels pulse
and the ribs move by a fraction of a voxel (same grid, new values).

    pvpython Testing/Benchmark/mmv_fine_volume.py OUT.vti [--dims 256 256 128]
"""

import argparse
import math

import numpy

AIR, LUNG, SKIN, TISSUE, VESSEL, BONE = 0, 150, 900, 620, 1350, 1700


def _tube_distance(points, curve):
    """Distance from each of `points` (N x 3) to the polyline `curve` (M x 3)."""
    best = numpy.full(points.shape[0], numpy.inf)
    for a, b in zip(curve[:-1], curve[1:]):
        ab = b - a
        t = numpy.clip(((points - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
        d = numpy.linalg.norm(points - (a + t[:, None] * ab), axis=1)
        best = numpy.minimum(best, d)
    return best


def chest(dims=(256, 256, 128), phase=0.0, seed=7):
    """uint16 values, x fastest (index [z, y, x]); `phase` in [0, 1) moves
    the ribs by up to half a voxel and pulses the vessels' radius."""
    nx, ny, nz = dims
    z, y, x = numpy.meshgrid(numpy.arange(nz, dtype=numpy.float32),
                             numpy.arange(ny, dtype=numpy.float32),
                             numpy.arange(nx, dtype=numpy.float32), indexing="ij")
    cx, cy = 0.5 * (nx - 1), 0.5 * (ny - 1)
    ax, ay = 0.42 * nx, 0.32 * ny
    r = numpy.sqrt(((x - cx) / ax) ** 2 + ((y - cy) / ay) ** 2)
    scale = min(ax, ay)
    values = numpy.full(dims[::-1], AIR, dtype=numpy.float32)
    body = r <= 1.0
    values[body] = TISSUE
    # A skin shell 2 voxels thick.
    values[body & (r >= 1.0 - 2.0 / scale)] = SKIN
    # Two lungs.
    for side in (-1.0, 1.0):
        lx = cx + side * 0.45 * ax
        lung = (((x - lx) / (0.38 * ax)) ** 2 + ((y - cy) / (0.72 * ay)) ** 2 +
                ((z - 0.5 * nz) / (0.46 * nz)) ** 2) <= 1.0
        values[lung] = LUNG
    # A spine: a column of vertebrae behind the lungs.
    sy = cy + 0.78 * ay
    spine = (((x - cx) / 7.0) ** 2 + ((y - sy) / 6.0) ** 2 <= 1.0) & (numpy.mod(z, 8.0) < 6.0)
    values[spine] = BONE
    # Ribs: elliptic arcs 1.5 voxels thick just inside the skin, one every
    # 10 slices, sloping down toward the front.
    shift = 0.5 * math.sin(2.0 * math.pi * phase)
    rib_r = 0.9
    theta = numpy.arctan2((y - cy) / ay, (x - cx) / ax)
    for level in numpy.arange(8.0, nz - 4.0, 10.0):
        zc = level + shift + 4.0 * numpy.cos(theta)  # lower in front (theta ~ -pi/2 is front)
        ring = numpy.abs(r - rib_r) * scale
        rib = (ring <= 0.75) & (numpy.abs(z - zc) <= 0.9) & (numpy.abs(theta + 0.5 * math.pi) > 0.5)
        values[rib] = BONE
    # Vessels: random smooth curves through the lungs, radius 0.6-1.0 voxel.
    rng = numpy.random.default_rng(seed)
    pts = numpy.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    inside = body.ravel()
    candidates = pts[inside]
    radius = 0.8 + 0.2 * math.sin(2.0 * math.pi * phase)
    vessel = numpy.zeros(candidates.shape[0], dtype=bool)
    for _ in range(14):
        side = rng.choice([-1.0, 1.0])
        start = numpy.array([cx + side * 0.1 * ax, cy, rng.uniform(0.2, 0.8) * nz])
        curve = [start]
        direction = numpy.array([side, rng.uniform(-0.6, 0.6), rng.uniform(-0.5, 0.5)])
        for _ in range(8):
            direction = direction / numpy.linalg.norm(direction)
            curve.append(curve[-1] + 9.0 * direction)
            direction = direction + rng.normal(0.0, 0.35, 3)
        curve = numpy.array(curve)
        lo = curve.min(axis=0) - 2.0
        hi = curve.max(axis=0) + 2.0
        box = numpy.all((candidates >= lo) & (candidates <= hi), axis=1)
        idx = numpy.nonzero(box)[0]
        if idx.size:
            vessel[idx[_tube_distance(candidates[idx], curve) <= radius]] = True
    flat = values.ravel()
    where = numpy.nonzero(inside)[0]
    flat[where[vessel]] = VESSEL
    noise = numpy.random.default_rng(seed + 1).normal(0.0, 12.0, flat.shape)
    flat = numpy.clip(flat + noise * (flat > 0), 0, 3926)
    return flat.reshape(dims[::-1]).astype(numpy.uint16)


def write_vti(path, values, name="ImageFile", spacing=(1.0, 1.0, 1.0)):
    """values indexed [z, y, x]; written with VTK's XML writer."""
    from vtkmodules.util import numpy_support
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    image = vtkImageData()
    image.SetDimensions(values.shape[2], values.shape[1], values.shape[0])
    image.SetSpacing(spacing)
    array = numpy_support.numpy_to_vtk(values.ravel(), deep=1)
    array.SetName(name)
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()
    return path


def write_series(prefix, steps, dims=(256, 256, 128)):
    """`steps` files PREFIX_K.vti of the chest, phase K / steps."""
    return [write_vti("%s_%d.vti" % (prefix, k), chest(dims, phase=k / float(steps)))
            for k in range(steps)]


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("--dims", type=int, nargs=3, default=[256, 256, 128])
    p.add_argument("--phase", type=float, default=0.0)
    a = p.parse_args()
    write_vti(a.out, chest(tuple(a.dims), a.phase))
