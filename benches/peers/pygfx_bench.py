"""pygfx's volume MIP (wgpu-native) with hatchery's camera and image size. Prints
`pygfx_mip_ms <median>` over FRAMES frames after one warm-up, the camera orbiting as in
`hatchery bench --scenario orbit:camera`. pygfx 0.17 has no shaded DVR material and no sample
distance setting (it steps one voxel), so only MIP at its own step is measured.

    python pygfx_bench.py VOLUME.nii.gz CAMERA.json FRAMES [OUT.npy]
"""

import sys
import time

import numpy as np
import pygfx as gfx
from rendercanvas.offscreen import RenderCanvas

from common import orbit, read_camera, read_nifti_u8

volume_path, camera_path, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
voxels, affine = read_nifti_u8(volume_path)
camera = read_camera(camera_path)

canvas = RenderCanvas(size=(camera["width"], camera["height"]), pixel_ratio=1)
renderer = gfx.renderers.WgpuRenderer(canvas)
scene = gfx.Scene()
scene.add(gfx.Background.from_color("#fff"))
volume = gfx.Volume(
    gfx.Geometry(grid=gfx.Texture(voxels.astype(np.float32), dim=3)),
    gfx.VolumeMipMaterial(clim=(0, 255)),
)
# Voxel (i, j, k) -> world as the file's affine says (pygfx's grid is x-fastest like NIfTI).
volume.local.matrix = affine
scene.add(volume)
cam = gfx.PerspectiveCamera(camera["fov_y_deg"], camera["width"] / camera["height"])
cam.world.reference_up = camera["up"]


def draw(frame):
    cam.local.position = orbit(camera, frame * 360.0 / (frames + 1))
    cam.look_at(camera["target"])
    return np.asarray(canvas.draw())


canvas.request_draw(lambda: renderer.render(scene, cam))
draw(0)
times = []
for frame in range(1, frames + 1):
    start = time.perf_counter()
    draw(frame)
    times.append(time.perf_counter() - start)
print(f"pygfx_mip_ms {np.median(times) * 1000:.1f}")
if len(sys.argv) > 4:
    np.save(sys.argv[4], draw(0))
