// Shared by every shader that draws a triangle mesh: the camera block and the vertex stage.
// Prepended to every mesh shader (gbuffer, depth_peel, secondary_geometry, shaded_surface).

struct Camera {
    view: mat4x4<f32>,
    proj: mat4x4<f32>,
    // World eye position, and 1 for an orthographic camera.
    eye: vec3<f32>,
    orthographic: u32,
};

@group(0) @binding(0) var<uniform> camera: Camera;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
};

struct VertexOut {
    // Invariant: every pass computes bit-identical depth, so depth peeling can compare exactly.
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) view_pos: vec3<f32>,
    @location(1) view_normal: vec3<f32>,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    let view_pos = camera.view * vec4<f32>(v.position, 1.0);
    out.clip = camera.proj * view_pos;
    out.view_pos = view_pos.xyz;
    // The view matrix is rigid (no model transform), so it maps normals too.
    out.view_normal = (camera.view * vec4<f32>(v.normal, 0.0)).xyz;
    return out;
}

// Unit vector from the surface point towards the viewer, in view space.
fn to_viewer(view_pos: vec3<f32>) -> vec3<f32> {
    if camera.orthographic != 0u {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return normalize(-view_pos);
}
