//! Every data preset pointed at data it was not written for (issue 25): a synthetic head of
//! another size, spacing, orientation, position and value range (written as NRRD the way teem
//! and 3D Slicer write it), probability maps in 0–1 instead of 0–255, a label map with the
//! frog's organ ids in other places, a mesh elsewhere in the world; and the shared frog read as
//! an "MRI". Each picture must show the data framed: not blank, its silhouette covering at
//! least a quarter of the frame, and inside it (the frame's border is background). The
//! silhouette is the filled outline (each row from its first to its last drawn pixel), so line
//! drawings (PIP stipples, hatching) count by the shape they draw, not by their ink.

mod common;

use hatchery_nodes::{Session, export};
use std::f32::consts::PI;
use std::io::Write;
use std::path::{Path, PathBuf};

const W: u32 = 160;
const H: u32 = 120;

/// Writes a NRRD volume (raw, little-endian) with an oblique, anisotropic grid: `dims` voxels of
/// `spacing` mm, rotated by `turn_deg` about the scanner z axis, first voxel at `origin` (LPS,
/// as NRRD's "left-posterior-superior" space says).
fn write_nrrd(
    path: &Path,
    kind: &str,
    dims: [usize; 3],
    spacing: [f32; 3],
    turn_deg: f32,
    origin: [f32; 3],
    bytes: &[u8],
) {
    let (s, c) = turn_deg.to_radians().sin_cos();
    let axes = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]];
    let dir = |i: usize| {
        let a = axes[i].map(|v| v * spacing[i]);
        format!("({},{},{})", a[0], a[1], a[2])
    };
    let header = format!(
        "NRRD0004\n# written by hatchery's tests/presets_on_other_data.rs\ntype: {kind}\n\
         dimension: 3\nspace: left-posterior-superior\nsizes: {} {} {}\n\
         space directions: {} {} {}\nkinds: domain domain domain\nendian: little\n\
         encoding: raw\nspace origin: ({},{},{})\n\n",
        dims[0],
        dims[1],
        dims[2],
        dir(0),
        dir(1),
        dir(2),
        origin[0],
        origin[1],
        origin[2]
    );
    let mut f = std::fs::File::create(path).unwrap();
    f.write_all(header.as_bytes()).unwrap();
    f.write_all(bytes).unwrap();
}

/// Normalised ellipsoid radius of voxel (i, j, k) of a grid of `dims` (1 on the head's skin).
fn head_radius(dims: [usize; 3], i: usize, j: usize, k: usize) -> f32 {
    let u = |n: usize, x: usize, r: f32| (x as f32 - (n as f32 - 1.0) / 2.0) / (r * n as f32);
    let (x, y, z) = (u(dims[0], i, 0.42), u(dims[1], j, 0.44), u(dims[2], k, 0.4));
    (x * x + y * y + z * z).sqrt()
}

struct OtherData {
    _dir: tempfile::TempDir,
    head: PathBuf,
    white: PathBuf,
    grey: PathBuf,
    labels: PathBuf,
    names: PathBuf,
    mesh: PathBuf,
}

/// The synthetic data set: a 96 × 112 × 80 head of 1.7 × 1.5 × 1.9 mm voxels turned 25°,
/// centred far from the MNI template's origin, int16 values 0–1500 (skin 600, a folded brain
/// 900–1500); white/grey-matter maps in float 0–1 on its grid; a 90 × 70 × 60 uint8 label map
/// with ellipsoid organs 9, 10, 11, 13, 15 and their names; an OBJ ellipsoid off the origin.
fn other_data() -> OtherData {
    let dir = tempfile::tempdir().unwrap();
    let dims = [96usize, 112, 80];
    let (spacing, turn, origin) = ([1.7, 1.5, 1.9], 25.0, [120.0, -260.0, 310.0]);
    let mut head = Vec::new();
    let (mut white, mut grey) = (Vec::new(), Vec::new());
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let r = head_radius(dims, i, j, k);
                let folds = (i as f32 * 0.5).sin() * (j as f32 * 0.4).cos() * 0.04;
                let brain = r < 0.85 + folds;
                let v: i16 = if brain {
                    (900.0 + 600.0 * (1.0 - r)) as i16
                } else if r < 1.0 {
                    600
                } else {
                    ((i * 7 + j * 3 + k) % 11) as i16 // scanner noise in the air
                };
                head.extend_from_slice(&v.to_le_bytes());
                let w = (1.0 - (r / 0.55)).clamp(0.0, 1.0).sqrt();
                let g = if brain && r > 0.5 { 1.0 - w } else { 0.0 };
                white.extend_from_slice(&w.to_le_bytes());
                grey.extend_from_slice(&g.to_le_bytes());
            }
        }
    }
    let p = |name: &str| dir.path().join(name);
    write_nrrd(&p("head.nrrd"), "int16", dims, spacing, turn, origin, &head);
    write_nrrd(
        &p("white.nrrd"),
        "float",
        dims,
        spacing,
        turn,
        origin,
        &white,
    );
    write_nrrd(&p("grey.nrrd"), "float", dims, spacing, turn, origin, &grey);

    let ldims = [90usize, 70, 60];
    let organs: [(u8, [f32; 3], [f32; 3]); 5] = [
        (13, [0.5, 0.5, 0.5], [0.42, 0.4, 0.4]), // skeleton: the body's hull
        (10, [0.45, 0.5, 0.5], [0.12, 0.14, 0.12]), // liver
        (11, [0.62, 0.45, 0.55], [0.1, 0.08, 0.1]), // lung
        (15, [0.35, 0.6, 0.45], [0.08, 0.1, 0.08]), // stomach
        (9, [0.55, 0.62, 0.4], [0.07, 0.06, 0.07]), // large intestine
    ];
    let mut labels = Vec::new();
    for k in 0..ldims[2] {
        for j in 0..ldims[1] {
            for i in 0..ldims[0] {
                let q = [i, j, k].map(|x| x as f32);
                let id = organs
                    .iter()
                    .rev()
                    .find(|(_, c, r)| {
                        (0..3)
                            .map(|a| ((q[a] / ldims[a] as f32 - c[a]) / r[a]).powi(2))
                            .sum::<f32>()
                            < 1.0
                    })
                    .map_or(0, |o| o.0);
                // The skeleton is a shell, the organs sit inside it.
                let shell = id == 13 && {
                    let c = organs[0];
                    (0..3)
                        .map(|a| ((q[a] / ldims[a] as f32 - c.1[a]) / c.2[a]).powi(2))
                        .sum::<f32>()
                        > 0.8
                };
                labels.push(if id == 13 && !shell { 0 } else { id });
            }
        }
    }
    write_nrrd(
        &p("labels.nrrd"),
        "uint8",
        ldims,
        [0.8, 0.9, 1.3],
        -40.0,
        [-30.0, 55.0, -210.0],
        &labels,
    );
    std::fs::write(
        p("names.csv"),
        "id,name\n9,large intestine\n10,liver\n11,lung\n13,skeleton\n15,stomach\n",
    )
    .unwrap();

    // A lat-long ellipsoid far from the origin, 3:2:1 in size.
    let mut obj = String::new();
    let (n_lat, n_lon) = (24, 48);
    for a in 0..=n_lat {
        for b in 0..n_lon {
            let (t, f) = (
                PI * a as f32 / n_lat as f32,
                2.0 * PI * b as f32 / n_lon as f32,
            );
            let v = [
                400.0 + 30.0 * t.sin() * f.cos(),
                -75.0 + 20.0 * t.sin() * f.sin(),
                12.0 + 10.0 * t.cos(),
            ];
            obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
        }
    }
    for a in 0..n_lat {
        for b in 0..n_lon {
            let i = |a: usize, b: usize| a * n_lon + b % n_lon + 1;
            obj += &format!("f {} {} {}\n", i(a, b), i(a + 1, b), i(a + 1, b + 1));
            obj += &format!("f {} {} {}\n", i(a, b), i(a + 1, b + 1), i(a, b + 1));
        }
    }
    std::fs::write(p("ellipsoid.obj"), obj).unwrap();
    OtherData {
        head: p("head.nrrd"),
        white: p("white.nrrd"),
        grey: p("grey.nrrd"),
        labels: p("labels.nrrd"),
        names: p("names.csv"),
        mesh: p("ellipsoid.obj"),
        _dir: dir,
    }
}

/// The filled silhouette's share of the frame: per row, the span from the first to the last
/// pixel that differs from the background (the top-left pixel).
fn silhouette_fraction(picture: &image::RgbaImage) -> f64 {
    let background = *picture.get_pixel(0, 0);
    let (w, h) = picture.dimensions();
    let mut area = 0u64;
    for y in 0..h {
        let drawn: Vec<u32> = (0..w)
            .filter(|&x| *picture.get_pixel(x, y) != background)
            .collect();
        if let (Some(a), Some(b)) = (drawn.first(), drawn.last()) {
            area += (b - a + 1) as u64;
        }
    }
    area as f64 / (w * h) as f64
}

/// How "covering a quarter of the frame" is measured.
#[derive(Clone, Copy)]
enum Coverage {
    /// The filled silhouette ([`silhouette_fraction`]).
    Silhouette,
    /// The silhouette's bounding box: for shapes of thin limbs (the frog's splayed legs), whose
    /// filled outline is a small part of the box they span.
    Extent,
}

/// The share of the frame inside the bounding box of everything drawn.
fn extent_fraction(picture: &image::RgbaImage) -> f64 {
    let background = *picture.get_pixel(0, 0);
    let drawn: Vec<(u32, u32)> = picture
        .enumerate_pixels()
        .filter(|(_, _, p)| **p != background)
        .map(|(x, y, _)| (x, y))
        .collect();
    let (Some(x0), Some(x1)) = (
        drawn.iter().map(|p| p.0).min(),
        drawn.iter().map(|p| p.0).max(),
    ) else {
        return 0.0;
    };
    let y0 = drawn.iter().map(|p| p.1).min().unwrap();
    let y1 = drawn.iter().map(|p| p.1).max().unwrap();
    ((x1 - x0 + 1) * (y1 - y0 + 1)) as f64 / (picture.width() * picture.height()) as f64
}

/// What a framed picture must show: at least a quarter of the frame covered, and the data
/// inside the frame (at most 2% of the 2-pixel border differs from the background; not checked
/// where the preset itself draws on the border, `border` false).
fn check_framed(
    picture: &image::RgbaImage,
    what: &str,
    check_border: bool,
    coverage: Coverage,
) -> Result<(), String> {
    let fraction = match coverage {
        Coverage::Silhouette => silhouette_fraction(picture),
        Coverage::Extent => extent_fraction(picture),
    };
    let background = *picture.get_pixel(0, 0);
    let (w, h) = picture.dimensions();
    let border: Vec<_> = picture
        .enumerate_pixels()
        .filter(|(x, y, _)| *x < 2 || *y < 2 || *x >= w - 2 || *y >= h - 2)
        .collect();
    let on_border =
        border.iter().filter(|(_, _, p)| **p != background).count() as f64 / border.len() as f64;
    if fraction >= 0.25 && (on_border <= 0.02 || !check_border) {
        return Ok(());
    }
    let saved = common::save_failure(what, picture);
    Err(format!(
        "{what}: its silhouette covers {fraction:.3} of the frame (want ≥ 0.25), {on_border:.3} of its border \
         (want ≤ 0.02); see {}",
        saved.display()
    ))
}

/// Renders every saver of `preset` with `inputs` given, checking each picture.
fn render_with(
    preset: &Path,
    inputs: &[(&str, &Path)],
    sets: &[(&str, &str, &str)],
    tag: &str,
    coverage: Coverage,
) -> Vec<String> {
    let name = preset.file_stem().unwrap().to_string_lossy().into_owned();
    let mut session = Session::open(preset, W, H).unwrap();
    for (node, param, value) in sets {
        session.set_param_text(node, param, value).unwrap();
    }
    for (input, path) in inputs {
        session
            .set_input(input, path)
            .unwrap_or_else(|e| panic!("{name}: --input {input}: {e}"));
    }
    let mut failures = Vec::new();
    for saver in common::savers(&session) {
        let (node, port) = {
            let (n, p) = session.graph.input_sources(&saver)[&0];
            (n.to_owned(), p)
        };
        if let Err(e) = session.run(&[&node]) {
            failures.push(format!("{name} on {tag}: {e}"));
            continue;
        }
        let value = session.executor.output(&node, port).unwrap().clone();
        let picture = export::to_rgba8(&value, &session.ctx.gpu).unwrap();
        // custom_shader_brain's own shader draws a vignette up to the frame's edge.
        let border = name != "custom_shader_brain";
        if let Err(e) = check_framed(
            &picture,
            &format!("{name}_{saver}_on_{tag}"),
            border,
            coverage,
        ) {
            failures.push(e);
        }
    }
    failures
}

#[test]
fn every_data_preset_frames_data_it_was_not_written_for() {
    let data = other_data();
    if std::env::var_os("KEEP").is_some() {
        eprintln!("DATA {}", data.labels.display());
        std::thread::sleep(std::time::Duration::from_secs(120));
    }
    let mut failures = Vec::new();
    let mut tried = 0;
    for preset in common::presets() {
        let session = Session::open(&preset, 8, 8).unwrap();
        let declared: Vec<String> = session
            .graph
            .inputs()
            .iter()
            .map(|i| i.name.clone())
            .collect();
        if declared.is_empty() {
            continue;
        }
        let inputs: Vec<(&str, &Path)> = declared
            .iter()
            .map(|n| {
                let path: &Path = match n.as_str() {
                    "volume" => &data.head,
                    "white_matter" => &data.white,
                    "grey_matter" => &data.grey,
                    "labels" => &data.labels,
                    "names" => &data.names,
                    "mesh" => &data.mesh,
                    other => panic!("{}: no test data for input `{other}`", preset.display()),
                };
                (n.as_str(), path)
            })
            .collect();
        failures.extend(render_with(
            &preset,
            &inputs,
            &[],
            "other_data",
            Coverage::Silhouette,
        ));
        tried += 1;
    }
    assert!(tried >= 20, "only {tried} presets declare inputs");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The MRI presets that read one volume, given the shared frog (object ids 0–29 as values),
/// seen from above (elevation 75°): from the presets' own side views the flat frog (500 × 470 ×
/// 204 mm) cannot cover a quarter of a 4:3 frame however it is framed. Its splayed legs fill
/// little of the box they span, so coverage is that of the drawn shape's bounding box.
#[test]
fn mri_presets_frame_the_frog_read_as_a_volume() {
    let frog = common::shared_data("volumes/frog_tissues.vti");
    let mut failures = Vec::new();
    for name in [
        "brain_surface",
        "style_tf_brain",
        "volume_toon",
        "hidden_layers_brain",
    ] {
        let preset = common::repo_root().join(format!("graphs/{name}.ron"));
        let above = [("camera", "elevation", "75")];
        failures.extend(render_with(
            &preset,
            &[("volume", &frog)],
            &above,
            "frog",
            Coverage::Extent,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
