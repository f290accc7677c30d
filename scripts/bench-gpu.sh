#!/bin/sh
# The benchmark of issue 15 item 5, as one script for a machine with a real GPU:
#   scripts/bench-gpu.sh [HATCHERY] [OUTDIR] [FRAMES]
# HATCHERY defaults to target/release/hatchery, OUTDIR to bench-gpu/, FRAMES to 50. The MRI
# graphs read ../shared/data/volumes/mni152_t1.nii.gz (relative to graphs/), as everywhere.
# Every block is one `hatchery bench` run (interleaved, medians after a warm-up frame); the
# adapter it ran on is the first line of each output. Set QUICK=1 for a small smoke run (what a
# machine without a GPU can finish in a minute).
set -eu
bin=${1:-target/release/hatchery}
out=${2:-bench-gpu}
frames=${3:-50}
mkdir -p "$out"
# (The graphs need mni152_t1, mni152_wm, mni152_gm and frog_tissues.vti in ../shared/data/volumes/.)

# Sizes of the issue; QUICK shrinks them so the script itself can be tried on lavapipe.
if [ "${QUICK:-0}" = 1 ]; then
    hd=320x180 sq=256x256 xga=256x192 res=96 pres=64
else
    hd=1920x1080 sq=1024x1024 xga=1024x768 res=512 pres=256
fi

run() {
    name=$1
    shift
    echo "== $name: ${HATCHERY_IMAGE_KERNEL:+HATCHERY_IMAGE_KERNEL=$HATCHERY_IMAGE_KERNEL }hatchery bench $*" | tee "$out/$name.txt"
    "$bin" bench "$@" --frames "$frames" 2>&1 | tee -a "$out/$name.txt"
}

(nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv 2>/dev/null ||
    echo "no nvidia-smi") | tee "$out/machine.txt"
nproc | sed 's/^/cpus: /' | tee -a "$out/machine.txt"

# 1. Hidden structures (Fischer 2005 set-up) on the engine block at resolution 512³ (over a
# million triangles) vs. the Blinn–Phong frame of the same block, same camera, camera orbiting.
run hidden_structures_1080p \
    graphs/shaded_surface.ron graphs/hidden_structures.ron \
    --set 1:shells.shape=engine_block --set "1:shells.resolution=$res" \
    --set 1:camera.azimuth=35 --set 1:camera.distance=3.4 --set 1:camera.elevation=25 \
    --set "2:block.resolution=$res" --set "2:pistons.resolution=$pres" \
    --scenario orbit:camera --size "$hd" --size "$xga"

# 2. The MRI surface (300k triangles): Blinn–Phong, two hidden layers (GBuffer + DepthPeel, and
# both layers from one k-buffer pass, DepthLayers), + secondary structures; the k-buffer graph
# once more with every node in a pass of its own (no fused image-space pass).
run hidden_layers_brain \
    graphs/brain_surface.ron graphs/hidden_layers_brain.ron \
    benches/graphs/hidden_layers_brain_kbuffer.ron graphs/hidden_structures_brain.ron \
    benches/graphs/hidden_layers_brain_kbuffer.ron --unfused 5 \
    --scenario orbit:camera --size "$hd" --size "$xga"
# The same with the fused image-space passes as fragment shaders (the default runs them as
# compute kernels on H100/H200-class parts, and as fragment shaders elsewhere).
export HATCHERY_IMAGE_KERNEL=fragment
run hidden_layers_brain_fragment_passes \
    graphs/brain_surface.ron graphs/hidden_layers_brain.ron \
    benches/graphs/hidden_layers_brain_kbuffer.ron graphs/hidden_structures_brain.ron \
    --scenario orbit:camera --size "$hd" --size "$xga"
unset HATCHERY_IMAGE_KERNEL

# 3. Ray casting the MRI at 1024²: MIP at 1-voxel steps, shaded DVR at 0.5, context-preserving
# (same TF and camera as shaded DVR), each as fragment shader and as compute kernel.
run raycast_mri \
    graphs/tf1d_phong_brain.ron graphs/tf1d_phong_brain.ron graphs/tf1d_phong_brain.ron \
    graphs/tf1d_phong_brain.ron graphs/context_preserving_brain.ron \
    graphs/context_preserving_brain.ron \
    --set 1:ray.mode=mip --set 1:ray.step=1 --set 1:ray.kernel=fragment \
    --set 2:ray.mode=mip --set 2:ray.step=1 --set 2:ray.kernel=compute \
    --set 3:ray.kernel=fragment --set 4:ray.kernel=compute \
    --set 5:ray.kernel=fragment --set 6:ray.kernel=compute \
    --scenario orbit:camera --size "$sq"

# 4. A 512³ procedural volume (the sphere of volume_styles): style-TF DVR and MIP, fragment
# shader and compute kernel.
run raycast_procedural \
    graphs/volume_styles.ron graphs/volume_styles.ron graphs/volume_styles.ron \
    graphs/volume_styles.ron \
    --set "volume.resolution=$res" --set 1:ray.kernel=fragment --set 2:ray.kernel=compute \
    --set 3:ray.mode=mip --set 3:ray.step=1 --set 3:ray.kernel=fragment \
    --set 4:ray.mode=mip --set 4:ray.step=1 --set 4:ray.kernel=compute \
    --scenario orbit:camera --size "$sq"

# 5. Two-level volume rendering of the frog (4 objects, the preset's modes; then all shaded DVR)
# against Raycast of the same volume with one transfer function over the same labels; then one
# object (the skeleton, unshaded) against Raycast showing that label only. Compute kernels. The
# Raycasts stay trilinear, as when the ratio was first measured (tf1d_phong_brain is B-spline).
tf4="9.5: 0.75 0.3 0.25 0; 10: 0.75 0.3 0.25 1; 10.5: 0.75 0.3 0.25 0; 10.6: 0.2 0.3 0.6 0; 11: 0.2 0.3 0.6 1; 11.5: 0.2 0.3 0.6 0; 12.5: 0.95 0.92 0.85 0; 13: 0.95 0.92 0.85 0.35; 13.5: 0.95 0.92 0.85 0; 14.5: 0.2 0.3 0.6 0; 15: 0.2 0.3 0.6 1; 15.5: 0.2 0.3 0.6 0"
tf1="12.5: 0.95 0.92 0.85 0; 13: 0.95 0.92 0.85 0.35; 13.5: 0.95 0.92 0.85 0"
frog_camera() {
    for k in 3 5; do
        printf -- '--set %s:camera.azimuth=20 --set %s:camera.distance=720 --set %s:camera.elevation=60 --set %s:camera.far=3000 --set %s:camera.target=[250,235,101] ' $k $k $k $k $k
    done
}
# shellcheck disable=SC2046
run two_level_frog \
    graphs/two_level_frog.ron graphs/two_level_frog.ron graphs/tf1d_phong_brain.ron \
    graphs/two_level_frog.ron graphs/tf1d_phong_brain.ron \
    --set "2:objects.objects=13: shaded_dvr over tf=1; 10: shaded_dvr over tf=2; 11: shaded_dvr over tf=3; 15: shaded_dvr over tf=3" \
    --set 2:ray.normals=data \
    --set 3:volume.path=../shared/data/volumes/frog_tissues.vti --set "3:tf.points=$tf4" \
    --set "4:objects.objects=13: dvr over tf=1" --set 4:ray.normals=data \
    --set 5:volume.path=../shared/data/volumes/frog_tissues.vti --set "5:tf.points=$tf1" \
    --set 5:ray.shading=none $(frog_camera) \
    --set 3:ray.reconstruction=trilinear --set 5:ray.reconstruction=trilinear \
    --scenario orbit:camera --size "$sq"

# 6. Importance-driven rendering (issue 11): conical MImP of the frog (liver as focus, the
# ImportanceCompositing pass included, re-run every frame as the camera orbits) vs. the same
# objects by TwoLevelRaycast without importance.
run importance_frog \
    graphs/importance_frog_mimp.ron benches/graphs/frog_dense.ron \
    --scenario orbit:camera --size "$sq"

# 7. Reconstruction (issue 36): the tricubic B-spline vs trilinear on the MRI (shaded DVR, a
# style transfer function, iso-surface + curvature), and the pre-integrated transfer function
# against post-classification at the same step.
run reconstruction \
    graphs/tf1d_phong_brain.ron graphs/tf1d_phong_brain.ron \
    graphs/style_tf_brain.ron graphs/style_tf_brain.ron \
    graphs/curvature_brain.ron graphs/curvature_brain.ron graphs/tf1d_phong_brain.ron \
    --set 1:ray.reconstruction=trilinear --set 2:ray.reconstruction=bspline \
    --set 3:ray.reconstruction=trilinear --set 4:ray.reconstruction=bspline \
    --set 6:surface.reconstruction=bspline --set 6:curvature.reconstruction=bspline \
    --set 7:ray.reconstruction=trilinear --set 7:ray.preintegrated=true \
    --scenario orbit:camera --size "$xga"

echo "results in $out/"
