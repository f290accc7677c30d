// Classification: the transfer-function tables (colour TF, or the style TF's (i, α_u) rows, one
// row per object, §4.2) looked up by data value.

// The LUT rule of hatchery_data::transfer_function::TransferFunction1D::lookup, on table row `row`.
fn table_lookup_row(v: f32, row: i32, domain: vec2<f32>) -> vec4<f32> {
    let span = domain.y - domain.x;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((v - domain.x) / span, 0.0, 1.0);
    }
    let x = u * (LUT_SIZE - 1.0);
    let k = min(floor(x), LUT_SIZE - 2.0);
    let f = x - k;
    let a = textureLoad(tf_table, vec2<i32>(i32(k), row), 0);
    let b = textureLoad(tf_table, vec2<i32>(i32(k) + 1, row), 0);
    return mix(a, b, f);
}

// A 2-D transfer function's entry at value v and second coordinate s (second domain `second`):
// bilinear between the LUT_SIZE × LUT_SIZE table's entries, each coordinate by the 1-D rule
// (hatchery_data::transfer_function_2d::TransferFunction2D::lookup).
fn table2d_lookup(v: f32, s: f32, second: vec2<f32>) -> vec4<f32> {
    let x = table_coordinate(v, ray.tf_domain);
    let y = table_coordinate(s, second);
    let k = min(floor(vec2<f32>(x, y)), vec2<f32>(LUT_SIZE - 2.0));
    let f = vec2<f32>(x, y) - k;
    let c = vec2<i32>(k);
    let a = textureLoad(tf_table, c, 0);
    let b = textureLoad(tf_table, c + vec2<i32>(1, 0), 0);
    let d = textureLoad(tf_table, c + vec2<i32>(0, 1), 0);
    let e = textureLoad(tf_table, c + vec2<i32>(1, 1), 0);
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

// Position of x in a table over `domain`, [0, LUT_SIZE − 1] (clamped).
fn table_coordinate(x: f32, domain: vec2<f32>) -> f32 {
    let span = domain.y - domain.x;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((x - domain.x) / span, 0.0, 1.0);
    }
    return u * (LUT_SIZE - 1.0);
}

// ∇²f at voxel-space q by second differences of trilinear samples one voxel either side, in data
// units per voxel² (hatchery_data::transfer_function_2d::laplacian): at the border the missing
// neighbour is the clamped sample itself; an axis with "no data" on a side adds 0.
fn laplacian_at(q: vec3<f32>) -> f32 {
    let top = ray.dims - 1.0;
    let p = clamp(q, vec3<f32>(0.0), top);
    let centre = trilinear_value(p);
    if no_data(centre) {
        return 0.0;
    }
    var sum = 0.0;
    for (var axis = 0; axis < 3; axis++) {
        var lo = p;
        var hi = p;
        lo[axis] = max(p[axis] - 1.0, 0.0);
        hi[axis] = min(p[axis] + 1.0, top[axis]);
        let a = trilinear_value(lo);
        let b = trilinear_value(hi);
        if !no_data(a) && !no_data(b) {
            sum += b - 2.0 * centre + a;
        }
    }
    return sum;
}

fn table_lookup(v: f32) -> vec4<f32> {
    return table_lookup_row(v, 0, ray.tf_domain);
}

// The table row, domain and style-node count of the object at voxel-space q (the label at the
// nearest voxel picks the row, §4.2); row 0 when no label volume is bound.
struct TableRow {
    row: i32,
    domain: vec2<f32>,
    node_count: f32,
};

fn table_row_at(q: vec3<f32>) -> TableRow {
    var r: TableRow;
    r.row = 0;
    r.domain = ray.tf_domain;
    r.node_count = f32(ray.style_nodes);
    if ray.use_labels != 0u {
        let voxel = grid_texel(vec3<i32>(round(clamp(q, vec3<f32>(0.0), ray.dims - 1.0))));
        let label = round(ray.label_texels.x + textureLoad(label_volume, voxel, 0).r * (ray.label_texels.y - ray.label_texels.x));
        let slot = clamp(i32(label), 0, i32(ray.label_rows) - 1);
        r.row = i32(textureLoad(label_rows, vec2<i32>(slot, 0), 0).r + 0.5);
        let info = textureLoad(label_rows, vec2<i32>(r.row, 1), 0);
        r.domain = info.xy;
        r.node_count = info.z;
    }
    return r;
}
