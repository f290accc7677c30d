//! hatchery's CPU-side data: volumes and triangle meshes, the file formats they come from
//! (NIfTI, OBJ, PLY, STL), procedural default data sets and marching cubes.

pub mod error;
pub mod marching_cubes;
pub mod mesh;
pub mod mesh_file;
pub mod nifti_file;
pub mod procedural;
pub mod volume;

pub use error::DataError;
pub use mesh::MeshData;
pub use volume::VolumeData;
