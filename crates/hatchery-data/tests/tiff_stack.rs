//! TIFF stacks written here with the `tiff` crate's encoder: page types, ImageJ and resolution
//! spacing, and the errors of stacks we refuse.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use hatchery_data::tiff_stack::load_tiff_stack;
use hatchery_data::{DataError, load_volume};
use tiff::encoder::colortype::{self, ColorType};
use tiff::encoder::{Compression, DeflateLevel, Rational, TiffEncoder, TiffValue};
use tiff::tags::{ResolutionUnit, Tag};

const W: u32 = 4;
const H: u32 = 3;

/// Page `k` of a W x H stack: value = x + W y + W H k.
fn page<T: TryFrom<u32>>(k: u32) -> Vec<T> {
    (0..W * H)
        .map(|i| T::try_from(i + W * H * k).ok().unwrap())
        .collect()
}

/// What goes into a stack's pages besides the pixels.
#[derive(Default)]
struct Tags<'a> {
    description: Option<&'a str>,
    /// (x, y) pixels per unit.
    resolution: Option<(Rational, Rational)>,
    unit: Option<ResolutionUnit>,
    compression: Compression,
}

/// A multi-page TIFF with one `C` page per slice of `pages`, each `(width, height, pixels)`.
fn stack<C: ColorType>(pages: &[(u32, u32, Vec<C::Inner>)], tags: &Tags) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let mut bytes = Cursor::new(Vec::new());
    let mut tiff = TiffEncoder::new(&mut bytes)
        .unwrap()
        .with_compression(tags.compression);
    for (k, (w, h, data)) in pages.iter().enumerate() {
        let mut image = tiff.new_image::<C>(*w, *h).unwrap();
        if let (0, Some(d)) = (k, tags.description) {
            image.encoder().write_tag(Tag::ImageDescription, d).unwrap();
        }
        if let Some((x, y)) = &tags.resolution {
            image.x_resolution(x.clone());
            image.y_resolution(y.clone());
        }
        if let Some(unit) = tags.unit {
            image.resolution_unit(unit);
        }
        image.write_data(data).unwrap();
    }
    bytes.into_inner()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn rational(n: u32, d: u32) -> Rational {
    Rational { n, d }
}

fn error(path: &Path) -> String {
    let e = load_tiff_stack(path).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(!e.contains('\n'), "{e}");
    e
}

#[test]
fn imagej_stacks_and_sample_types() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let pages: Vec<_> = (0..5).map(|k| (W, H, page::<u8>(k))).collect();
    let tags = Tags {
        description: Some("ImageJ=1.54f\nimages=5\nslices=5\nunit=mm\nspacing=2.5\nloop=false\n"),
        resolution: Some((rational(2, 1), rational(4, 1))),
        unit: Some(ResolutionUnit::None),
        ..Tags::default()
    };
    let p = write(d, "u8.tif", &stack::<colortype::Gray8>(&pages, &tags));
    let v = load_tiff_stack(&p).unwrap();
    assert_eq!(v.dims, [W, H, 5]);
    assert_eq!(v.stored_type, "uint8");
    let want: Vec<f32> = (0..W * H * 5).map(|i| i as f32).collect();
    assert_eq!(v.values_f32(), want);
    assert_eq!(v.spacing(), [0.5, 0.25, 2.5]);
    assert_eq!(v.origin(), [0.0; 3]);
    assert!(v.geometry.is_axis_aligned());
    assert!(v.placement.contains("ImageJ spacing"), "{}", v.placement);
    assert!(
        v.placement.contains("no anatomical frame"),
        "{}",
        v.placement
    );
    assert_eq!(load_volume(&p).unwrap(), v);

    // Microns become mm.
    let pages: Vec<_> = (0..2).map(|k| (W, H, page::<u16>(k))).collect();
    let tags = Tags {
        description: Some("ImageJ=1.54f\nimages=2\nslices=2\nunit=micron\nspacing=4\n"),
        resolution: Some((rational(1, 2), rational(1, 2))),
        unit: Some(ResolutionUnit::None),
        ..Tags::default()
    };
    let p = write(d, "u16.tiff", &stack::<colortype::Gray16>(&pages, &tags));
    let v = load_volume(&p).unwrap();
    assert_eq!((v.stored_type, v.value(3, 2, 1)), ("uint16", 23.0));
    let s = v.spacing();
    assert!(
        (s[0] - 0.002).abs() < 1e-9 && (s[2] - 0.004).abs() < 1e-9,
        "{s:?}"
    );

    // Signed 16-bit and float pages; no description: the resolution without unit is taken
    // as given, z spacing 1.
    let pages: Vec<_> = (0..3).map(|k| (W, H, page::<i16>(k))).collect();
    let tags = Tags {
        resolution: Some((rational(1, 3), rational(1, 3))),
        ..Tags::default()
    };
    let v = load_tiff_stack(&write(
        d,
        "i16.tif",
        &stack::<colortype::GrayI16>(&pages, &tags),
    ))
    .unwrap();
    assert_eq!((v.stored_type, v.spacing()), ("int16", [3.0, 3.0, 1.0]));
    let pages: Vec<_> = (0..3)
        .map(|k| {
            (
                W,
                H,
                page::<u16>(k).into_iter().map(|v| v as f32 - 0.5).collect(),
            )
        })
        .collect();
    let tags = Tags {
        resolution: Some((rational(72, 1), rational(72, 1))),
        unit: Some(ResolutionUnit::Inch),
        ..Tags::default()
    };
    let v = load_tiff_stack(&write(
        d,
        "f32.tif",
        &stack::<colortype::Gray32Float>(&pages, &tags),
    ))
    .unwrap();
    assert_eq!((v.stored_type, v.value(0, 0, 0)), ("float32", -0.5));
    // A 72 dpi print resolution is not a voxel size.
    assert_eq!(v.spacing(), [1.0; 3]);
    assert!(v.placement.contains("inch"), "{}", v.placement);
    // Centimetres are.
    let tags = Tags {
        resolution: Some((rational(20, 1), rational(10, 1))),
        unit: Some(ResolutionUnit::Centimeter),
        ..Tags::default()
    };
    let v = load_tiff_stack(&write(
        d,
        "cm.tif",
        &stack::<colortype::Gray32Float>(&pages, &tags),
    ))
    .unwrap();
    assert_eq!(v.spacing(), [0.5, 1.0, 1.0]);
}

#[test]
fn compressed_pages() {
    let dir = tempfile::tempdir().unwrap();
    let pages: Vec<_> = (0..3).map(|k| (W, H, page::<u16>(k))).collect();
    let want: Vec<f32> = (0..W * H * 3).map(|i| i as f32).collect();
    for (name, compression) in [
        ("lzw.tif", Compression::Lzw),
        ("deflate.tif", Compression::Deflate(DeflateLevel::Balanced)),
        ("packbits.tif", Compression::Packbits),
    ] {
        let tags = Tags {
            compression,
            ..Tags::default()
        };
        let p = write(dir.path(), name, &stack::<colortype::Gray16>(&pages, &tags));
        assert_eq!(load_tiff_stack(&p).unwrap().values_f32(), want, "{name}");
    }
}

#[test]
fn stacks_we_refuse() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let none = Tags::default();
    let gray: Vec<_> = (0..3).map(|k| (W, H, page::<u8>(k))).collect();

    let rgb: Vec<_> = (0..2)
        .map(|_| (W, H, vec![7u8; (W * H * 3) as usize]))
        .collect();
    let p = write(d, "rgb.tif", &stack::<colortype::RGB8>(&rgb, &none));
    assert!(error(&p).contains("only one-sample grayscale"));

    let u32s: Vec<_> = (0..2).map(|k| (W, H, page::<u32>(k))).collect();
    let p = write(d, "u32.tif", &stack::<colortype::Gray32>(&u32s, &none));
    assert!(error(&p).contains("32-bit unsigned integer samples are not supported"));

    let mut uneven = gray.clone();
    uneven[2] = (H, W, page::<u8>(2));
    let p = write(d, "uneven.tif", &stack::<colortype::Gray8>(&uneven, &none));
    assert!(error(&p).contains("page 2 is 3x4"));

    for (name, description, want) in [
        (
            "channels",
            "ImageJ=1.54f\nimages=3\nchannels=3\n",
            "3 channels",
        ),
        ("frames", "ImageJ=1.54f\nimages=3\nframes=3\n", "3 frames"),
        (
            "images",
            "ImageJ=1.54f\nimages=30\nslices=30\n",
            "promises 30 images",
        ),
    ] {
        let tags = Tags {
            description: Some(description),
            ..Tags::default()
        };
        let p = write(
            d,
            &format!("{name}.tif"),
            &stack::<colortype::Gray8>(&gray, &tags),
        );
        let e = error(&p);
        assert!(e.contains(want), "{name}: {e}");
    }

    let p = write(
        d,
        "single.tif",
        &stack::<colortype::Gray8>(&gray[..1], &none),
    );
    assert!(error(&p).contains("at least 2"));

    let whole = stack::<colortype::Gray8>(&gray, &none);
    let p = write(d, "cut.tif", &whole[..whole.len() - 20]);
    let e = load_tiff_stack(&p).unwrap_err();
    assert!(matches!(e, DataError::Format { .. }), "{e}");
    let p = write(d, "text.tif", b"this is not a TIFF file at all");
    assert!(error(&p).contains("TIFF"));
}
