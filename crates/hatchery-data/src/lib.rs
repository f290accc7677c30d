//! hatchery's CPU-side data: volumes and triangle meshes, the file formats they come from
//! (NIfTI, NRRD, MetaImage, TIFF stacks, DICOM series, VTK ImageData, OME-Zarr, OBJ, PLY, STL), label
//! masks, procedural default data sets and marching cubes.
// One `unsafe` block (raw_source.rs: the memory map), allowed there with its reason.
#![deny(unsafe_code)]

pub mod brick_source;
pub mod bricks;
pub mod derived_levels;
pub mod dicom_series;
pub mod distance;
pub mod error;
pub mod files;
pub mod geometry;
pub mod gradient;
pub mod labels;
pub mod lighting;
pub mod lit_sphere;
pub mod marching_cubes;
pub mod mesh;
pub mod mesh_file;
pub mod metaimage_file;
pub mod mgh_file;
pub mod nifti_file;
pub mod nifti_header;
pub mod nrrd_file;
#[cfg(not(target_arch = "wasm32"))]
pub mod ome_zarr;
#[cfg(target_arch = "wasm32")]
#[path = "ome_zarr_web.rs"]
pub mod ome_zarr;
pub mod paint;
pub mod preintegration;
pub mod procedural;
pub mod pyramid;
pub mod raw_source;
pub(crate) mod raw_voxels;
pub mod segmentation;
pub mod stream_file;
pub mod style;
pub mod thinning;
pub mod tiff_stack;
pub mod transfer_function;
pub mod transfer_function_2d;
pub mod value_stats;
pub mod vector_field;
pub mod volume;
pub mod volume_file;
pub mod voxels;
pub mod vti_file;

pub use error::DataError;
pub use mesh::MeshData;
pub use volume::VolumeData;
pub use volume_file::load_volume;
