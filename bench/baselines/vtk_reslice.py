#!/usr/bin/python3
"""The baseline issue 10's lavapipe goals are set against: VTK's vtkImageReslice slicing alone.

A 1024 x 1024 image, trilinear, on an oblique plane through a 400 x 600 x 1200 8-bit volume at
0.1 mm voxels (echosim's 0.1 mm bench volume has that shape), on `--threads` threads. Prints one
line: the frames per second over `--seconds` of back-to-back reslices (each one Modified() and
Update(), as an application slicing a new pose each frame would).

The goals are figures measured on a shared virtual machine whose speed drifts by tens of per cent
over minutes; bench/baselines/paired.sh runs this alternately with `echosim bench slice`, so the two
are compared in the same spell. Needs Debian's python3-vtk9 and python3-numpy (not installed by
scripts/: only this comparison uses them): `apt-get install python3-vtk9 python3-numpy`.
"""
import argparse
import math
import sys
import time

try:
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import VTK_UNSIGNED_CHAR, vtkMultiThreader
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkCommonMath import vtkMatrix4x4
    from vtkmodules.vtkImagingCore import vtkImageReslice
except ImportError as e:
    sys.exit(f"vtk_reslice.py: {e.name} is missing: apt-get install python3-vtk9 python3-numpy")


def volume(shape_xyz, spacing_mm):
    """A speckle-like volume: the reslice's cost does not depend on the values, but a constant
    volume would let a cache or a branch see more than a real one shows."""
    nx, ny, nz = shape_xyz
    rng = np.random.default_rng(1)
    voxels = rng.integers(0, 256, size=nx * ny * nz, dtype=np.uint8)  # x fastest, as VTK lays it out
    image = vtkImageData()
    image.SetDimensions(nx, ny, nz)
    image.SetSpacing(spacing_mm, spacing_mm, spacing_mm)
    image.GetPointData().SetScalars(numpy_to_vtk(voxels, deep=False, array_type=VTK_UNSIGNED_CHAR))
    image._keep = voxels  # numpy_to_vtk without a copy: the array must outlive the image
    return image


def oblique_axes(centre_mm, about_y_deg, about_x_deg):
    """Reslice axes (columns: the image's x, its y, its normal, in the volume's frame) through
    `centre_mm`: the volume's axes turned `about_y_deg` about its y, then `about_x_deg` about its x.
    echosim's bench volumes are the resting probe's axes turned 4 deg about the beam and 3 deg about
    the array (bench/slice_scene.cpp), so its image is this plane."""
    a, b = math.radians(about_y_deg), math.radians(about_x_deg)
    ry = [[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]]
    rx = [[1, 0, 0], [0, math.cos(b), -math.sin(b)], [0, math.sin(b), math.cos(b)]]
    r = [[sum(rx[i][k] * ry[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    m = vtkMatrix4x4()
    for i in range(3):
        for j in range(3):
            m.SetElement(i, j, r[i][j])
        m.SetElement(i, 3, centre_mm[i])
    return m


def inside_fraction(m, extent_mm, half_width, half_depth, n=64):
    """The fraction of the image inside the volume (outside, the reslice writes the background,
    which costs less than a sample), from an n x n grid of its points."""
    hits = 0
    for iu in range(n):
        for iv in range(n):
            u = -half_width + (iu + 0.5) * 2 * half_width / n
            v = -half_depth + (iv + 0.5) * 2 * half_depth / n
            p = [m.GetElement(i, 0) * u + m.GetElement(i, 1) * v + m.GetElement(i, 3) for i in range(3)]
            hits += all(0 <= c <= e for c, e in zip(p, extent_mm))
    return hits / (n * n)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0, help="how long to reslice")
    parser.add_argument("--threads", type=int, default=2, help="VTK's threads")
    parser.add_argument("--size", type=int, default=1024, help="the image's side [pixels]")
    args = parser.parse_args()

    shape, spacing = (400, 600, 1200), 0.1
    image = volume(shape, spacing)
    extent_mm = [n * spacing for n in shape]
    reslice = vtkImageReslice()
    reslice.SetInputData(image)
    reslice.SetInterpolationModeToLinear()
    reslice.SetOutputDimensionality(2)
    axes = oblique_axes([e / 2 for e in extent_mm], 4.0, 3.0)
    inside = inside_fraction(axes, [e - spacing for e in extent_mm], 20.0, 25.0)
    if inside < 0.99:
        sys.exit(f"vtk_reslice.py: {100 * (1 - inside):.0f} % of the plane lies outside the volume")
    reslice.SetResliceAxes(axes)
    # echosim's default image, 40 mm wide and 50 mm deep, centred on the plane's origin
    reslice.SetOutputSpacing(40.0 / args.size, 50.0 / args.size, 1.0)
    reslice.SetOutputOrigin(-20.0, -25.0, 0.0)
    reslice.SetOutputExtent(0, args.size - 1, 0, args.size - 1, 0, 0)
    reslice.SetNumberOfThreads(args.threads)
    vtkMultiThreader.SetGlobalMaximumNumberOfThreads(args.threads)
    reslice.Update()  # the first, untimed: allocation
    frames, start = 0, time.perf_counter()
    while time.perf_counter() - start < args.seconds:
        reslice.Modified()
        reslice.Update()
        frames += 1
    elapsed = time.perf_counter() - start
    out = reslice.GetOutput()
    dims = out.GetDimensions()
    if dims[0] != args.size or dims[1] != args.size:
        sys.exit(f"vtk_reslice.py: the output is {dims}, not {args.size} x {args.size}")
    print(f"vtk_reslice {args.size}x{args.size} threads={args.threads} fps={frames / elapsed:.1f} frames={frames} "
          f"inside={100 * inside:.1f}%")


if __name__ == "__main__":
    main()
