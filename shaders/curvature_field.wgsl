// The principal-direction field of Curvature's (κ1, κ2, θ1, θ2) image, shared by HatchStrokes
// and CurvatureFlow (prepended to their shaders).

// Screen angle of the principal direction of the larger |κ| at a curvature texel (the smaller
// with `smaller`), or −10 off the surface.
fn principal_angle(c: vec4<f32>, smaller: bool) -> f32 {
    if c.z < -5.0 {
        return -10.0;
    }
    // θ1 belongs to κ1, θ2 to κ2.
    let first = (abs(c.x) >= abs(c.y)) != smaller;
    return select(c.w, c.z, first);
}

// The direction field at pixel position p (centres at .5): the doubled-angle vectors of the
// four texels around p, bilinearly weighted (a direction is an axis, θ ≡ θ + π), as a unit
// vector (x right, y down); zero where less than half the weight lies on the surface.
fn direction_field(curvature: texture_2d<f32>, p: vec2<f32>, smaller: bool) -> vec2<f32> {
    let q = p - 0.5;
    let base = vec2<i32>(floor(q));
    let f = q - floor(q);
    let size = vec2<i32>(textureDimensions(curvature));
    var sum = vec2<f32>(0.0);
    var weight = 0.0;
    for (var c = 0; c < 4; c++) {
        let o = vec2<i32>(c & 1, c >> 1u);
        let t = clamp(base + o, vec2<i32>(0), size - 1);
        let theta = principal_angle(textureLoad(curvature, t, 0), smaller);
        if theta < -5.0 {
            continue;
        }
        let w = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
        sum += w * vec2<f32>(cos(2.0 * theta), sin(2.0 * theta));
        weight += w;
    }
    if weight < 0.5 || dot(sum, sum) < 1e-12 {
        return vec2<f32>(0.0);
    }
    let theta = 0.5 * atan2(sum.y, sum.x);
    return vec2<f32>(cos(theta), sin(theta));
}

// `v` turned to point along `reference` (an axis has two senses).
fn align(v: vec2<f32>, reference: vec2<f32>) -> vec2<f32> {
    return select(v, -v, dot(v, reference) < 0.0);
}
