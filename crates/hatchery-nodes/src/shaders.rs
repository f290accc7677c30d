//! The WGSL parts shared by several programs. Each module declares its
//! own programs (`declare`; the list is [`crate::kinds::programs`]) from its own shader files and these shared
//! parts: `mesh_common.wgsl` is prepended to the mesh shaders, `fullscreen.wgsl` to the
//! image-space ones, the `ray_*.wgsl` parts to the ray casters (WGSL has no includes).

/// A file of `shaders/`, embedded at build time.
macro_rules! shader_file {
    ($name:literal) => {
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shaders/",
            $name
        ))
    };
}
pub(crate) use shader_file;

/// A program part: the file of `shaders/` and its text, embedded at build time.
macro_rules! part {
    ($name:literal) => {
        ($name, $crate::shaders::shader_file!($name))
    };
}
pub(crate) use part;

pub const MESH_COMMON: &str = shader_file!("mesh_common.wgsl");
pub const FULLSCREEN: &str = shader_file!("fullscreen.wgsl");
pub const RAY_COMMON: &str = shader_file!("ray_common.wgsl");
pub const RAY_BSPLINE: &str = shader_file!("ray_bspline.wgsl");
pub const RAY_CLASSIFY: &str = shader_file!("ray_classify.wgsl");
pub const RAY_SHADE: &str = shader_file!("ray_shade.wgsl");
pub const RAY_SKIP: &str = shader_file!("ray_skip.wgsl");
pub const RAY_OBJECTS: &str = shader_file!("ray_objects.wgsl");
pub const CURVATURE_SHAPE: &str = shader_file!("curvature_shape.wgsl");
pub const CURVATURE_COMMON: &str = shader_file!("curvature_common.wgsl");
pub const CURVATURE_FIELD: &str = shader_file!("curvature_field.wgsl");

/// A program part: (file name, WGSL text).
pub type Part = (&'static str, &'static str);
type Parts = Vec<Part>;

/// A mesh program: the shared camera block and vertex layout, then `own`.
pub fn mesh(own: Part) -> Parts {
    vec![("mesh_common.wgsl", MESH_COMMON), own]
}

/// An image-space program: the full-screen triangle and texel helpers, then `own`.
pub fn screen(own: Part) -> Parts {
    vec![("fullscreen.wgsl", FULLSCREEN), own]
}

/// A ray caster: the shared sampling, classification, shading and skipping parts, then `own`.
pub fn ray(own: Part) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("ray_bspline.wgsl", RAY_BSPLINE),
        ("ray_classify.wgsl", RAY_CLASSIFY),
        ("ray_shade.wgsl", RAY_SHADE),
        ("ray_skip.wgsl", RAY_SKIP),
        own,
    ]
}

/// A ray caster of segmented volumes: [`ray`]'s parts, the object tables, then `own`.
pub fn ray_objects(own: Part) -> Parts {
    let mut parts = ray(("ray_objects.wgsl", RAY_OBJECTS));
    parts.push(own);
    parts
}

/// A ray caster of segmented volumes that also needs the iso-surfaces' shape operator
/// (TwoLevelRaycast's volume thinning): [`ray_objects`]'s parts, curvature_shape, then `own`.
pub fn ray_objects_shape(own: Part) -> Parts {
    let mut parts = ray(("ray_objects.wgsl", RAY_OBJECTS));
    parts.push(("curvature_shape.wgsl", CURVATURE_SHAPE));
    parts.push(own);
    parts
}

/// A ray caster that samples on its own (no tables, shading or skipping): primary rays, the
/// sampling and B-spline helpers, then `own` (Schlieren).
pub fn ray_sampling(own: Part) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("ray_bspline.wgsl", RAY_BSPLINE),
        own,
    ]
}

/// A curvature pass: primary rays and the curvature helpers, then `own`.
pub fn curvature(own: Part) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("ray_bspline.wgsl", RAY_BSPLINE),
        ("curvature_shape.wgsl", CURVATURE_SHAPE),
        ("curvature_common.wgsl", CURVATURE_COMMON),
        own,
    ]
}

/// `source` with each named `override` declaration (`override NAME: T = default;`, one per
/// line) turned into a `const` of the given value — a specialised program. Pipeline-overridable
/// constants would say the same, but lavapipe folds `const`s through the whole march and
/// override-derived branches only partly (TwoLevelRaycast's four-object frame: 1209 → 814 ms at
/// 512², issue 32), so the ray casters specialise their source instead. Errors name a constant
/// the program does not declare, or a type other than bool, i32, u32 and f32.
pub(crate) fn specialise(source: &str, constants: &[(&str, f64)]) -> Result<String, String> {
    let mut out = source.to_owned();
    for &(name, value) in constants {
        let start = format!("override {name}:");
        let Some(at) = out.find(&start) else {
            return Err(format!("the program declares no `override {name}`"));
        };
        let end = at
            + out[at..]
                .find(';')
                .ok_or_else(|| format!("`{start}` without `;`"))?;
        let declaration = &out[at + start.len()..end];
        let ty = declaration.split('=').next().unwrap_or("").trim();
        let literal = match ty {
            "bool" => (value != 0.0).to_string(),
            "i32" => format!("{}", value as i32),
            "u32" => format!("{}u", value as u32),
            "f32" => format!("{value:?}"),
            other => return Err(format!("`override {name}` has type `{other}`")),
        };
        out.replace_range(at..end, &format!("const {name}: {ty} = {literal}"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::specialise;

    #[test]
    fn overrides_become_constants_of_their_type() {
        let source = "override A: i32 = -1;\noverride B: f32 = 1.0;\nfn f() -> i32 { return A; }";
        let out = specialise(source, &[("A", 3.0), ("B", 0.5)]).unwrap();
        assert_eq!(
            out,
            "const A: i32 = 3;\nconst B: f32 = 0.5;\nfn f() -> i32 { return A; }"
        );
        naga::front::wgsl::parse_str(&out).unwrap();
        assert!(
            specialise(source, &[("C", 1.0)])
                .unwrap_err()
                .contains("override C")
        );
    }
}
