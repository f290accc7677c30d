//! `hatchery convert IN OUT.zarr`: any volume hatchery reads, written as an OME-Zarr 0.5
//! multiscale image (what ome-zarr-py, napari and neuroglancer read), with a label map on its
//! grid as a label image.

use anyhow::{Context, Result, bail};
use hatchery_data::ome_zarr::{self, ConvertOptions};
use hatchery_data::segmentation::{self, LabelData};
use hatchery_data::volume_file::{LoadOptions, load_volume_with};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// The volume: any format `hatchery info` reads (NIfTI, NRRD, MetaImage, VTK, TIFF, DICOM,
    /// MGH, OME-Zarr).
    input: PathBuf,
    /// The OME-Zarr folder to write (ending in .zarr); an OME-Zarr already there is replaced.
    output: PathBuf,
    /// The named data array of the input to read (VTK; OME-Zarr: a label image).
    #[arg(long)]
    array: Option<String>,
    /// A label map on the input's grid, written as labels/NAME with its object names.
    #[arg(long)]
    labels: Option<PathBuf>,
    /// The label image's name (default: the label file's name without its ending).
    #[arg(long, value_name = "NAME")]
    label_name: Option<String>,
    /// Object names for the label map: CSV `id,name` or an ITK-SNAP label file (names in the
    /// label file itself are read too).
    #[arg(long)]
    names: Option<PathBuf>,
    /// Chunk side in voxels.
    #[arg(long, default_value_t = 64)]
    chunk: u32,
    /// Levels below full resolution (default: halve until every axis fits one chunk).
    #[arg(long)]
    levels: Option<u32>,
}

/// The file name without its volume ending (`organs.seg.nrrd` → `organs`).
fn stem(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = name.trim_end_matches('/');
    name.split('.').next().unwrap_or(name).to_string()
}

fn load_labels(path: &Path, names: Option<&Path>) -> Result<LabelData> {
    let (volume, mut table) =
        hatchery_data::volume_file::load_label_volume(path, &LoadOptions::default())?;
    for w in &volume.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    if let Some(names) = names {
        table.extend(segmentation::read_names(names)?);
    }
    let mut labels =
        LabelData::from_volume(&volume).with_context(|| format!("{}", path.display()))?;
    labels.name_objects(&table);
    Ok(labels)
}

pub fn command(args: Args) -> Result<()> {
    let ending = args.output.to_string_lossy().to_ascii_lowercase();
    if !ending.trim_end_matches('/').ends_with(".zarr") {
        bail!(
            "{}: the output of `convert` is an OME-Zarr folder; name it with the ending .zarr",
            args.output.display()
        );
    }
    let options = LoadOptions {
        array: args.array.clone(),
    };
    let volume = load_volume_with(&args.input, &options)?;
    for w in &volume.warnings {
        eprintln!("warning: {}: {w}", args.input.display());
    }
    let labels = match &args.labels {
        Some(path) => {
            let name = args.label_name.clone().unwrap_or_else(|| stem(path));
            Some((name, load_labels(path, args.names.as_deref())?))
        }
        None if args.names.is_some() || args.label_name.is_some() => {
            bail!("--names and --label-name describe a label map: give it with --labels FILE")
        }
        None => None,
    };
    let convert = ConvertOptions {
        chunk: args.chunk,
        levels: args.levels,
        ..Default::default()
    };
    let warnings = ome_zarr::write_ome_zarr(
        &volume,
        labels.as_ref().map(|(n, l)| (n.as_str(), l)),
        &args.output,
        &convert,
    )?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    // Read it back: what was written is what hatchery (and the spec) say it is.
    let image = ome_zarr::Multiscale::open(&args.output)
        .with_context(|| format!("reading back {}", args.output.display()))?;
    println!("{}: OME-Zarr {}", args.output.display(), image.version);
    for (k, l) in image.levels.iter().enumerate() {
        let [x, y, z] = l.dims;
        let s = l.geometry.spacing;
        println!(
            "  level {k} ({}): {x}×{y}×{z} voxels, {:.4}×{:.4}×{:.4} mm",
            l.path, s.x, s.y, s.z
        );
    }
    if let Some((name, l)) = &labels {
        println!(
            "  labels/{name}: {} objects{}",
            l.objects.len(),
            if l.objects.is_empty() {
                String::new()
            } else {
                format!(
                    " ({})",
                    l.objects.values().cloned().collect::<Vec<_>>().join(", ")
                )
            }
        );
    }
    Ok(())
}
