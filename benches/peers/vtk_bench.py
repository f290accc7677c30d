"""VTK's vtkGPUVolumeRayCastMapper with hatchery's camera, image size, sample distance, transfer
function and blend mode. Prints `vtk_<mode>_ms <median>` over FRAMES frames after one warm-up,
the camera orbiting as in `hatchery bench --scenario orbit:camera`.

    python vtk_bench.py VOLUME.nii.gz CAMERA.json mip|dvr FRAMES STEP_VOXELS "TF POINTS" [OUT.png]
"""

import sys
import time

import numpy as np
import vtk
from vtk.util import numpy_support

from common import orbit, parse_tf, read_camera, read_nifti_u8

volume_path, camera_path, mode, frames, step, tf_text = sys.argv[1:7]
frames, step = int(frames), float(step)
voxels, affine = read_nifti_u8(volume_path)
camera = read_camera(camera_path)

image = vtk.vtkImageData()
nz, ny, nx = voxels.shape
image.SetDimensions(nx, ny, nz)
spacing = np.linalg.norm(affine[:3, :3], axis=0)
image.SetSpacing(*spacing)
image.SetOrigin(*affine[:3, 3])
direction = vtk.vtkMatrix3x3()
for i in range(3):
    for j in range(3):
        direction.SetElement(i, j, affine[i, j] / spacing[j])
image.SetDirectionMatrix(direction)
image.GetPointData().SetScalars(
    numpy_support.numpy_to_vtk(voxels.ravel(), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR))

mapper = vtk.vtkGPUVolumeRayCastMapper()
mapper.SetInputData(image)
mapper.SetAutoAdjustSampleDistances(0)
# hatchery's step is in voxels of the smallest spacing.
mapper.SetSampleDistance(step * float(spacing.min()))
prop = vtk.vtkVolumeProperty()
prop.SetInterpolationTypeToLinear()
color, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
for value, r, g, b, a in parse_tf(tf_text):
    color.AddRGBPoint(value, r, g, b)
    opacity.AddPoint(value, a)
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
# hatchery's opacities are per voxel of path (1 mm here): VTK's unit distance.
prop.SetScalarOpacityUnitDistance(float(spacing.min()))
if mode == "mip":
    mapper.SetBlendModeToMaximumIntensity()
else:
    mapper.SetBlendModeToComposite()
    prop.ShadeOn()
    prop.SetAmbient(0.15)
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.4)
    prop.SetSpecularPower(32.0)
actor = vtk.vtkVolume()
actor.SetMapper(mapper)
actor.SetProperty(prop)

renderer = vtk.vtkRenderer()
renderer.SetBackground(1, 1, 1)
renderer.AddVolume(actor)
window = vtk.vtkRenderWindow()
window.SetOffScreenRendering(1)
window.AddRenderer(renderer)
window.SetSize(camera["width"], camera["height"])
cam = renderer.GetActiveCamera()
cam.SetFocalPoint(*camera["target"])
cam.SetViewUp(*camera["up"])
cam.SetViewAngle(camera["fov_y_deg"])
cam.SetClippingRange(camera["near"], camera["far"])


def draw(frame):
    cam.SetPosition(*orbit(camera, frame * 360.0 / (frames + 1)))
    cam.SetViewUp(*camera["up"])
    window.Render()


draw(0)
times = []
for frame in range(1, frames + 1):
    start = time.perf_counter()
    draw(frame)
    times.append(time.perf_counter() - start)
print(f"vtk_{mode}_ms {np.median(times) * 1000:.1f}")
if len(sys.argv) > 7:
    draw(0)
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(sys.argv[7])
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
