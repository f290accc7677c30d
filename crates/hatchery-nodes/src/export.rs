//! Getting values out of the graph: raw float arrays (`.npy`, for numpy) and viewable pictures
//! (`.png`), used by `--dump`, by `SaveImage` and by tests.

use crate::value::{TransferFunction, Value};
use hatchery_gpu::{GpuContext, GpuError, TextureData};
use std::io::Write;
use std::path::Path;

/// A C-order float array.
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    pub shape: Vec<usize>,
    pub data: Vec<f32>,
}

/// Why a value could not be exported ([`to_array`], [`to_rgba8`]).
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Reading the value back from the GPU failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The value has no array (or no picture) of that form; the message names its port type.
    #[error("{0}")]
    NoSuchForm(String),
}

fn read(gpu: &GpuContext, texture: &wgpu::Texture) -> Result<TextureData, GpuError> {
    gpu.read_texture(texture)
}

/// The raw data of a value: Image H×W×4 (premultiplied RGBA), Mask H×W, GBuffer H×W×4
/// (depth, nx, ny, nz), Volume D×H×W, VectorField D×H×W×3 (U_x, U_y, U_z), Mesh N×6 (position, normal per vertex), Importance H×W×4
/// (countersink depth E, importance sum, footprint flag, focus last-hit depth).
pub fn to_array(value: &Value, gpu: &GpuContext) -> Result<Array, ExportError> {
    Ok(match value {
        Value::Image(image) => texture_array(read(gpu, &image.texture)?),
        Value::Importance(i) => texture_array(read(gpu, &i.buffer)?),
        Value::Mask(mask) => {
            let t = read(gpu, &mask.texture)?;
            Array {
                shape: vec![t.height as usize, t.width as usize],
                data: t.data,
            }
        }
        Value::GBuffer(g) => {
            let depth = read(gpu, &g.depth)?;
            let normal = read(gpu, &g.normal)?;
            let mut data = Vec::with_capacity(depth.data.len() * 4);
            for (d, n) in depth.data.iter().zip(normal.data.chunks_exact(4)) {
                data.extend_from_slice(&[*d, n[0], n[1], n[2]]);
            }
            Array {
                shape: vec![depth.height as usize, depth.width as usize, 4],
                data,
            }
        }
        Value::Volume(v) => {
            let [x, y, z] = v.data.dims.map(|d| d as usize);
            Array {
                shape: vec![z, y, x],
                data: v.data.values_f32().into_owned(),
            }
        }
        Value::Mesh(m) => {
            let mut data = Vec::with_capacity(m.data.positions.len() * 6);
            for (p, n) in m.data.positions.iter().zip(&m.data.normals) {
                data.extend_from_slice(p);
                data.extend_from_slice(n);
            }
            Array {
                shape: vec![m.data.positions.len(), 6],
                data,
            }
        }
        Value::TransferFunction(tf) => match tf.as_ref() {
            TransferFunction::Color(f) => Array {
                shape: vec![f.lut.len(), 4],
                data: f.lut.iter().flatten().copied().collect(),
            },
            TransferFunction::Style { function, .. } => Array {
                shape: vec![function.tft.len(), 2],
                data: function.tft.iter().flatten().copied().collect(),
            },
            TransferFunction::TwoD(f) => Array {
                shape: vec![
                    hatchery_data::transfer_function_2d::ROWS,
                    hatchery_data::transfer_function::LUT_SIZE,
                    4,
                ],
                data: f.table.iter().flatten().copied().collect(),
            },
        },
        Value::StyleSet(set) => {
            let size = set.maps.first().map_or(0, |m| m.size as usize);
            let data = set
                .maps
                .iter()
                .flat_map(|m| m.texels.iter().flatten().copied())
                .collect();
            Array {
                shape: vec![set.maps.len(), size, size, 4],
                data,
            }
        }
        Value::VectorField(f) => {
            let [x, y, z] = f.data.dims.map(|d| d as usize);
            Array {
                shape: vec![z, y, x, 3],
                data: f.data.vectors.iter().flatten().copied().collect(),
            }
        }
        Value::Labels(l) => {
            let [x, y, z] = l.data.dims.map(|d| d as usize);
            Array {
                shape: vec![z, y, x],
                data: l.data.ids.iter().map(|&id| f32::from(id)).collect(),
            }
        }
        Value::Annotations(a) => {
            // N × 7: anchor x, y, z (world), shown (0/1), label rectangle min x, min y (pixels;
            // NaN before AnnotationLayout), leader opacity.
            let mut data = Vec::new();
            for (i, anchor) in a.anchors.iter().enumerate() {
                let label = a
                    .placed
                    .as_ref()
                    .and_then(|p| p.layout.labels.iter().find(|l| l.anchor == i));
                data.extend_from_slice(&anchor.position.to_array());
                match label {
                    Some(l) => data.extend_from_slice(&[
                        f32::from(u8::from(l.shown)),
                        l.rect.min.x,
                        l.rect.min.y,
                        l.opacity,
                    ]),
                    None => data.extend_from_slice(&[0.0, f32::NAN, f32::NAN, 0.0]),
                }
            }
            Array {
                shape: vec![a.anchors.len(), 7],
                data,
            }
        }
        Value::Strokes(s) => {
            // One row per stroke point: stroke index, seed (mesh vertex), cross-hatching (0/1),
            // x, y (pixels).
            let mut data = Vec::new();
            let lines = s.lines(gpu)?;
            for (i, line) in lines.iter().enumerate() {
                for q in &line.points {
                    data.extend_from_slice(&[
                        i as f32,
                        line.seed as f32,
                        f32::from(u8::from(line.cross)),
                        q.x,
                        q.y,
                    ]);
                }
            }
            Array {
                shape: vec![data.len() / 5, 5],
                data,
            }
        }
        Value::Camera(_) | Value::Light(_) | Value::ObjectStyles(_) => {
            return Err(ExportError::NoSuchForm(format!(
                "a {} value holds no array to dump",
                value.port_type()
            )));
        }
    })
}

fn texture_array(t: TextureData) -> Array {
    Array {
        shape: vec![t.height as usize, t.width as usize, t.channels as usize],
        data: t.data,
    }
}

fn to_u8(x: f32) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Premultiplied RGBA texels → straight-alpha 8-bit picture.
pub fn image_to_rgba8(t: &TextureData) -> image::RgbaImage {
    image::RgbaImage::from_fn(t.width, t.height, |x, y| {
        let p = t.texel(x, y);
        let a = p[3];
        let un = |c: f32| if a > 1e-6 { c / a } else { 0.0 };
        image::Rgba([to_u8(un(p[0])), to_u8(un(p[1])), to_u8(un(p[2])), to_u8(a)])
    })
}

/// A picture of a value: images as they are, masks in grey, G-buffer normals as colours
/// (n·0.5 + 0.5), the middle z-slice of a volume scaled to its value range (of a vector field:
/// U / max |U| as colours).
/// A viewable 8-bit picture of `value` (see the module doc); errors: [`ExportError`].
pub fn to_rgba8(value: &Value, gpu: &GpuContext) -> Result<image::RgbaImage, ExportError> {
    Ok(match value {
        Value::Image(image) => image_to_rgba8(&read(gpu, &image.texture)?),
        Value::Importance(i) => {
            // Red: the focus footprint; green: the importance sum (scaled to its largest
            // value); blue: where the countersink cuts.
            let t = read(gpu, &i.buffer)?;
            let top = (0..t.height)
                .flat_map(|y| (0..t.width).map(move |x| (x, y)))
                .map(|(x, y)| t.texel(x, y)[1])
                .fold(1e-6f32, f32::max);
            image::RgbaImage::from_fn(t.width, t.height, |x, y| {
                let [e, sum, inside, _] = [0, 1, 2, 3].map(|c| t.texel(x, y)[c]);
                let cut = if e > -1e29 && inside < 0.5 { 0.6 } else { 0.0 };
                image::Rgba([to_u8(inside), to_u8(sum / top), to_u8(cut), 255])
            })
        }
        Value::Mask(mask) => {
            let t = read(gpu, &mask.texture)?;
            image::RgbaImage::from_fn(t.width, t.height, |x, y| {
                let g = to_u8(t.texel(x, y)[0]);
                image::Rgba([g, g, g, 255])
            })
        }
        Value::GBuffer(g) => {
            let t = read(gpu, &g.normal)?;
            image::RgbaImage::from_fn(t.width, t.height, |x, y| {
                let n = t.texel(x, y);
                let c = |v: f32| to_u8(v * 0.5 + 0.5);
                image::Rgba([c(n[0]), c(n[1]), c(n[2]), to_u8(n[3])])
            })
        }
        Value::Volume(v) => {
            let [w, h, d] = v.data.dims;
            let [lo, hi] = v.data.value_range;
            let scale = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
            let z = d / 2;
            // Row 0 of the picture is the largest y, so anatomy is upright.
            image::RgbaImage::from_fn(w, h, |x, y| {
                let g = to_u8((v.data.value(x, h - 1 - y, z) - lo) * scale);
                image::Rgba([g, g, g, 255])
            })
        }
        Value::TransferFunction(tf) => {
            // The colour ramp (over white, by opacity) or the style index as grey.
            let (w, h) = (256u32, 32u32);
            image::RgbaImage::from_fn(w, h, |x, y| match tf.as_ref() {
                TransferFunction::Color(f) => {
                    let c = f.lut[(x as usize * (f.lut.len() - 1)) / (w as usize - 1)];
                    let over = |v: f32| v * c[3] + (1.0 - c[3]);
                    image::Rgba([to_u8(over(c[0])), to_u8(over(c[1])), to_u8(over(c[2])), 255])
                }
                TransferFunction::Style { function, .. } => {
                    let e =
                        function.tft[(x as usize * (function.tft.len() - 1)) / (w as usize - 1)];
                    let g = to_u8(e[0] / (function.ift.len().max(2) - 1) as f32);
                    image::Rgba([g, g, g, to_u8(e[1])])
                }
                TransferFunction::TwoD(f) => {
                    // Value along x, the second coordinate upwards, over white by opacity.
                    let cols = hatchery_data::transfer_function::LUT_SIZE;
                    let rows = hatchery_data::transfer_function_2d::ROWS;
                    let i = (x as usize * (cols - 1)) / (w as usize - 1);
                    let j = ((h - 1 - y) as usize * (rows - 1)) / (h as usize - 1);
                    let c = f.table[j * cols + i];
                    let over = |v: f32| v * c[3] + (1.0 - c[3]);
                    image::Rgba([to_u8(over(c[0])), to_u8(over(c[1])), to_u8(over(c[2])), 255])
                }
            })
        }
        Value::VectorField(f) => {
            // The middle z-slice, U / max |U| as colour (u·0.5 + 0.5), upright as volumes are.
            let [w, h, d] = f.data.dims;
            let max = f.data.max_magnitude();
            let scale = if max > 0.0 { 0.5 / max } else { 0.0 };
            image::RgbaImage::from_fn(w, h, |x, y| {
                let i = (x + w * ((h - 1 - y) + h * (d / 2))) as usize;
                let c = f.data.vectors[i].map(|u| to_u8(u * scale + 0.5));
                image::Rgba([c[0], c[1], c[2], 255])
            })
        }
        Value::Labels(l) => {
            // The middle z-slice, each object in its own colour (golden-angle hues).
            let [w, h, d] = l.data.dims;
            let z = d / 2;
            image::RgbaImage::from_fn(w, h, |x, y| {
                let id = l.data.id(x, h - 1 - y, z);
                if id == 0 {
                    return image::Rgba([0, 0, 0, 255]);
                }
                let hue = (f32::from(id) * 137.508).rem_euclid(360.0) / 60.0;
                let f = |n: f32| {
                    let k = (n + hue).rem_euclid(6.0);
                    to_u8(1.0 - 0.8 * k.min(4.0 - k).clamp(0.0, 1.0))
                };
                image::Rgba([f(5.0), f(3.0), f(1.0), 255])
            })
        }
        Value::StyleSet(set) => {
            let size = set.maps.first().map_or(1, |m| m.size);
            image::RgbaImage::from_fn(size * set.maps.len().max(1) as u32, size, |x, y| {
                let Some(map) = set.maps.get((x / size) as usize) else {
                    return image::Rgba([0, 0, 0, 0]);
                };
                let t = map.texels[(y * size + x % size) as usize];
                image::Rgba([to_u8(t[0]), to_u8(t[1]), to_u8(t[2]), to_u8(t[3])])
            })
        }
        Value::Mesh(_)
        | Value::Camera(_)
        | Value::Light(_)
        | Value::ObjectStyles(_)
        | Value::Annotations(_)
        | Value::Strokes(_) => {
            return Err(ExportError::NoSuchForm(format!(
                "a {} value has no picture; dump it to .npy instead",
                value.port_type()
            )));
        }
    })
}

/// Writes a little-endian f32 `.npy` file (format version 1.0), readable by `numpy.load`.
pub fn write_npy(path: &Path, array: &Array) -> std::io::Result<()> {
    let shape = match array.shape.as_slice() {
        [one] => format!("({one},)"),
        dims => format!(
            "({})",
            dims.iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6) + version (2) + length (2) + header + '\n' must be a multiple of 64.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + array.data.len() * 4);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in &array.data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    hatchery_graph::atomic::write_bytes_atomically(path, &out)
}

/// Writes `picture` as a PNG file, atomically (hatchery_graph::atomic: the old file or the
/// complete new one, never a partial one). Errors: the folder or the encoder.
pub fn write_png(picture: &image::RgbaImage, path: &Path) -> std::io::Result<()> {
    hatchery_graph::atomic::write_atomically(path, |file| {
        let mut out = std::io::BufWriter::new(file);
        picture
            .write_to(&mut out, image::ImageFormat::Png)
            .map_err(std::io::Error::other)?;
        out.flush()
    })
}
