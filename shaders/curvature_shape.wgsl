// The volume's world gradient and Hessian at a world point, and the shape operator of the
// iso-surface through it (the tutorial's §1.3, Kindlmann et al. 2003): functions only, no
// bindings, so any program with ray_common and ray_bspline prepended can use them — the
// curvature family (after curvature_common) and TwoLevelRaycast's volume thinning.

fn world_gradient(p: vec3<f32>) -> vec3<f32> {
    return gradient_at((ray.to_voxel * vec4<f32>(p, 1.0)).xyz);
}

// The Hessian of the volume at world point p: the B-spline's own second derivatives
// (ray_bspline, Hadwiger §1.3) where the reconstruction is the B-spline; else, and next to "no
// data", central differences of the gradient at ±h (world units) along the world axes,
// symmetrised.
fn world_hessian(p: vec3<f32>, h: f32) -> mat3x3<f32> {
    if reconstruction() == RECONSTRUCTION_BSPLINE {
        let d = bspline_derivatives((ray.to_voxel * vec4<f32>(p, 1.0)).xyz);
        if !d.missing {
            // q = A p + b with A^T = grad_to_world's linear part G: H_world = G H_voxel G^T.
            let g = mat3x3<f32>(ray.grad_to_world[0].xyz, ray.grad_to_world[1].xyz,
                                ray.grad_to_world[2].xyz);
            return g * d.hessian * transpose(g);
        }
    }
    var columns: array<vec3<f32>, 3>;
    for (var axis = 0; axis < 3; axis++) {
        var e = vec3<f32>(0.0);
        e[axis] = h;
        columns[axis] = (world_gradient(p + e) - world_gradient(p - e)) / (2.0 * h);
    }
    let hessian = mat3x3<f32>(columns[0], columns[1], columns[2]);
    return 0.5 * (hessian + transpose(hessian));
}

// The 2×2 shape operator of the iso-surface through a point of world gradient g (|g| =
// g_length > 0) and Hessian `hessian`: with n = −g/|g| (outward where the field is larger
// inside) and a tangent basis (t1, t2) of n, A = [[a, b], [b, c]], A_ab = −t_a·H t_b / |g|.
// Its eigenvalues are the principal curvatures κ1 ≥ κ2 (positive for a convex bump).
struct ShapeOperator {
    n: vec3<f32>,
    t1: vec3<f32>,
    t2: vec3<f32>,
    a: f32,
    b: f32,
    c: f32,
};

fn shape_operator(g: vec3<f32>, g_length: f32, hessian: mat3x3<f32>) -> ShapeOperator {
    var s: ShapeOperator;
    s.n = -g / g_length;
    var helper = vec3<f32>(1.0, 0.0, 0.0);
    if abs(s.n.x) > 0.9 {
        helper = vec3<f32>(0.0, 1.0, 0.0);
    }
    s.t1 = normalize(cross(s.n, helper));
    s.t2 = cross(s.n, s.t1);
    s.a = -dot(s.t1, hessian * s.t1) / g_length;
    s.b = -dot(s.t1, hessian * s.t2) / g_length;
    s.c = -dot(s.t2, hessian * s.t2) / g_length;
    return s;
}

// The curvature magnitude √(κ1² + κ2²) of a shape operator (its Frobenius norm, which needs no
// eigenvalues).
fn curvature_magnitude(s: ShapeOperator) -> f32 {
    return sqrt(s.a * s.a + 2.0 * s.b * s.b + s.c * s.c);
}
