// Tricubic B-spline reconstruction of values, gradients and Hessians (Hadwiger et al., tutorial
// §1.3 "Filter kernel considerations"), prepended after ray_common. The B-spline of the data
// extended by clamping at the grid's faces (as the trilinear sampler clamps to the edge), in
// voxel space: voxel centres at integers, q = i + a with i = floor(q).
//
// Values and first derivatives come from 8 trilinear fetches each (Sigg & Hadwiger's fast
// third-order filtering): along every axis the four weights of voxels i−1 … i+2 fall into two
// pairs of one sign, and a pair's weighted sum is one linear fetch between its two voxels, at
// the fraction given by the pair's weight ratio, scaled by the pair's total weight. Each fetch
// goes through grid_uv, so bricked grids (their one-voxel apron) and the border read as the
// whole texture does. Where a fetch leans on "no data" the trilinear filter is used instead —
// a guard only: a "no data" voxel of small weight passes it, so the nodes draw a volume with
// "no data" trilinear (Reconstruction::on).
// Curvature passes, which need the Hessian once per pixel rather than per sample, sum the
// 4×4×4 voxels directly (bspline_derivatives).

// The cubic B-spline's weights of voxels i−1, i, i+1, i+2 at fraction a (per axis).
struct Weights4 {
    w0: vec3<f32>,
    w1: vec3<f32>,
    w2: vec3<f32>,
    w3: vec3<f32>,
};

fn bspline_weights(a: vec3<f32>) -> Weights4 {
    let b = 1.0 - a;
    let a2 = a * a;
    let a3 = a2 * a;
    return Weights4(b * b * b / 6.0, (3.0 * a3 - 6.0 * a2 + 4.0) / 6.0,
                    (-3.0 * a3 + 3.0 * a2 + 3.0 * a + 1.0) / 6.0, a3 / 6.0);
}

// Their first derivatives d/da: w0', w1' ≤ 0 and w2', w3' ≥ 0 on [0, 1].
fn bspline_derivative_weights(a: vec3<f32>) -> Weights4 {
    let b = 1.0 - a;
    let a2 = a * a;
    return Weights4(-0.5 * b * b, 1.5 * a2 - 2.0 * a, -1.5 * a2 + a + 0.5, 0.5 * a2);
}

// Their second derivatives.
fn bspline_second_weights(a: vec3<f32>) -> Weights4 {
    return Weights4(1.0 - a, 3.0 * a - 2.0, 1.0 - 3.0 * a, a);
}

// Two linear fetches per axis standing for four voxels: positions at0, at1 and total weights
// g0 = w0 + w1, g1 = w2 + w3 of the pairs.
struct Taps {
    at0: vec3<f32>,
    at1: vec3<f32>,
    g0: vec3<f32>,
    g1: vec3<f32>,
};

fn taps(i: vec3<f32>, w: Weights4) -> Taps {
    let g0 = w.w0 + w.w1;
    let g1 = w.w2 + w.w3;
    // The pairs' totals never vanish for the value and first-derivative weights (|g| ≥ 1/6).
    return Taps(i - 1.0 + w.w1 / g0, i + 1.0 + w.w3 / g1, g0, g1);
}

// The 8 fetches of `t`: x = Σ weight × texel, y = 1 where a fetch leans on "no data".
fn eight_fetches(t: Taps) -> vec2<f32> {
    var sum = 0.0;
    var missing = 0.0;
    for (var c = 0u; c < 8u; c++) {
        let pick = vec3<bool>((c & 1u) != 0u, (c & 2u) != 0u, (c & 4u) != 0u);
        let texel = trilinear_texel(select(t.at0, t.at1, pick));
        if texel < -0.5 {
            missing = 1.0;
        }
        let w = select(t.g0, t.g1, pick);
        sum += w.x * w.y * w.z * texel;
    }
    return vec2<f32>(sum, missing);
}

// q clamped to the grid, split into the voxel i and the fraction a.
fn bspline_cell(q: vec3<f32>) -> array<vec3<f32>, 2> {
    let p = clamp(q, vec3<f32>(0.0), ray.dims - 1.0);
    let i = floor(p);
    return array<vec3<f32>, 2>(i, p - i);
}

// The B-spline's normalised texel at q (8 fetches), or the trilinear one next to "no data".
fn bspline_texel(q: vec3<f32>) -> f32 {
    if RAY_BSPLINE_QUADS != 0 {
        return quads_value_and_gradient(q);
    }
    let cell = bspline_cell(q);
    let r = eight_fetches(taps(cell[0], bspline_weights(cell[1])));
    if r.y != 0.0 {
        return trilinear_texel(q);
    }
    return r.x;
}

// The B-spline's gradient at q in data units per voxel (24 fetches); w = 1 where a fetch leans
// on "no data" (the caller falls back to central differences).
fn bspline_gradient(q: vec3<f32>) -> vec4<f32> {
    if RAY_BSPLINE_QUADS != 0 {
        if any(q != quads_last.q) {
            quads_value_and_gradient(q);
        }
        return quads_last.gradient;
    }
    let cell = bspline_cell(q);
    let value = taps(cell[0], bspline_weights(cell[1]));
    let slope = taps(cell[0], bspline_derivative_weights(cell[1]));
    var g = vec3<f32>(0.0);
    var missing = 0.0;
    for (var axis = 0; axis < 3; axis++) {
        var t = value;
        t.at0[axis] = slope.at0[axis];
        t.at1[axis] = slope.at1[axis];
        t.g0[axis] = slope.g0[axis];
        t.g1[axis] = slope.g1[axis];
        let r = eight_fetches(t);
        g[axis] = r.x;
        missing = max(missing, r.y);
    }
    return vec4<f32>(g * (ray.texel_values.y - ray.texel_values.x), missing);
}

// Value, gradient and Hessian of the B-spline at q, in data units and voxel coordinates, from
// the 64 voxels around q read directly; `missing` where one of them holds "no data".
struct Derivatives {
    value: f32,
    gradient: vec3<f32>,
    hessian: mat3x3<f32>,
    missing: bool,
};

fn bspline_derivatives(q: vec3<f32>) -> Derivatives {
    let cell = bspline_cell(q);
    let w = bspline_weights(cell[1]);
    let d = bspline_derivative_weights(cell[1]);
    let s = bspline_second_weights(cell[1]);
    let ws = array<vec3<f32>, 4>(w.w0, w.w1, w.w2, w.w3);
    let ds = array<vec3<f32>, 4>(d.w0, d.w1, d.w2, d.w3);
    let ss = array<vec3<f32>, 4>(s.w0, s.w1, s.w2, s.w3);
    var out: Derivatives;
    out.missing = false;
    var h = array<f32, 6>(0.0, 0.0, 0.0, 0.0, 0.0, 0.0); // xx yy zz xy xz yz
    let base = vec3<i32>(cell[0]) - 1;
    for (var z = 0; z < 4; z++) {
        for (var y = 0; y < 4; y++) {
            for (var x = 0; x < 4; x++) {
                let texel = textureLoad(volume, grid_texel(base + vec3<i32>(x, y, z)), 0).r;
                if texel < -0.5 {
                    out.missing = true;
                }
                let wv = vec3<f32>(ws[x].x, ws[y].y, ws[z].z);
                let dv = vec3<f32>(ds[x].x, ds[y].y, ds[z].z);
                let sv = vec3<f32>(ss[x].x, ss[y].y, ss[z].z);
                out.value += wv.x * wv.y * wv.z * texel;
                out.gradient += vec3<f32>(dv.x * wv.y * wv.z, wv.x * dv.y * wv.z, wv.x * wv.y * dv.z) * texel;
                h[0] += sv.x * wv.y * wv.z * texel;
                h[1] += wv.x * sv.y * wv.z * texel;
                h[2] += wv.x * wv.y * sv.z * texel;
                h[3] += dv.x * dv.y * wv.z * texel;
                h[4] += dv.x * wv.y * dv.z * texel;
                h[5] += wv.x * dv.y * dv.z * texel;
            }
        }
    }
    let scale = ray.texel_values.y - ray.texel_values.x;
    out.value = ray.texel_values.x + out.value * scale;
    out.gradient *= scale;
    out.hessian = scale * mat3x3<f32>(vec3<f32>(h[0], h[3], h[4]), vec3<f32>(h[3], h[1], h[5]),
                                      vec3<f32>(h[4], h[5], h[2]));
    return out;
}

// On CPU drivers (llvmpipe/lavapipe) a texture fetch is a loop in software, filtered or not, so
// the 32 fetches of a sample's value and gradient cost more than reading its 64 voxels once.
// There the `volume` binding holds x-quads instead (value/bspline_quads.rs): texel (i, j, k) =
// voxels i … i+3 of row (j, k), clamped to the row, in the volume's own encoding — so .r is the
// voxel itself and every other read of `volume` is unchanged — and one load brings a whole row
// of the 4×4×4 neighbourhood: 16 loads give the value and the gradient together. The gradient
// is kept for the sample just valued (ray casters classify, then shade the same sample).
// Unlike the fetches, the quads carry no "no data" guard: volumes with "no data" voxels are
// drawn trilinear (Reconstruction::on), and the guard's test and fallback fetch, though never
// taken, made the whole march twice as slow on llvmpipe.
override RAY_BSPLINE_QUADS: i32 = 0;

struct QuadsSample {
    q: vec3<f32>,
    // Data units per voxel (w = 0: bspline_gradient's "no fetch leant on no data").
    gradient: vec4<f32>,
};

var<private> quads_last: QuadsSample = QuadsSample(vec3<f32>(-1e30), vec4<f32>(0.0));

// Voxels i−1 … i+2 of row (y, z) of the neighbourhood whose first voxel is `base`.
fn quads_row(base: vec3<i32>, y: i32, z: i32) -> vec4<f32> {
    let t = textureLoad(volume, grid_texel(base + vec3<i32>(0, y, z)), 0);
    // Below the grid's first voxel the row starts clamped: voxel 0 twice.
    return select(t, vec4<f32>(t.r, t.rgb), base.x < 0);
}

// The B-spline's normalised texel at q (see bspline_texel); stores its gradient in quads_last.
fn quads_value_and_gradient(q: vec3<f32>) -> f32 {
    let cell = bspline_cell(q);
    let w = bspline_weights(cell[1]);
    let d = bspline_derivative_weights(cell[1]);
    // The weights of the four voxels along each axis, as vectors over the voxels.
    let wx = vec4<f32>(w.w0.x, w.w1.x, w.w2.x, w.w3.x);
    let dx = vec4<f32>(d.w0.x, d.w1.x, d.w2.x, d.w3.x);
    let wy = vec4<f32>(w.w0.y, w.w1.y, w.w2.y, w.w3.y);
    let dy = vec4<f32>(d.w0.y, d.w1.y, d.w2.y, d.w3.y);
    let wz = vec4<f32>(w.w0.z, w.w1.z, w.w2.z, w.w3.z);
    let dz = vec4<f32>(d.w0.z, d.w1.z, d.w2.z, d.w3.z);
    let base = vec3<i32>(cell[0]) - 1;
    // Sums over x, then y, then z (separable): value, ∂x, ∂y, ∂z.
    var sum = vec4<f32>(0.0);
    for (var z = 0; z < 4; z++) {
        var plane = vec3<f32>(0.0); // Σy wy·(wx·row), Σy wy·(dx·row), Σy dy·(wx·row)
        for (var y = 0; y < 4; y++) {
            let row = quads_row(base, y, z);
            let along = dot(wx, row);
            plane += vec3<f32>(wy[y] * along, wy[y] * dot(dx, row), dy[y] * along);
        }
        sum += vec4<f32>(wz[z] * plane, dz[z] * plane.x);
    }
    let scale = ray.texel_values.y - ray.texel_values.x;
    quads_last = QuadsSample(q, vec4<f32>(sum.yzw * scale, 0.0));
    return sum.x;
}
