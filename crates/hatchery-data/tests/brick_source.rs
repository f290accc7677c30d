//! Bricks read on demand (brick_source.rs): a brick with its apron equals the same voxels of the
//! whole grid (edges repeated), read from memory or from an OME-Zarr's chunks; the host cache
//! keeps to its budget, evicting the least recently used; worker threads read every requested
//! brick once and report a bad request as an error.

use hatchery_data::brick_source::{
    BrickCache, BrickId, BrickLoader, BrickSource, MemorySource, brick_grid, read_brick,
};
use hatchery_data::ome_zarr::Multiscale;
use hatchery_data::voxels::Voxels;
use hatchery_data::{VolumeData, load_volume};
use std::path::PathBuf;
use std::sync::Arc;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/fixtures/world")
        .join(name)
}

/// The brick as the whole grid says it should be: stored voxel `l` = voxel `b·inner − 1 + l`,
/// clamped.
fn expected(v: &VolumeData, brick: [u32; 3], inner: u32) -> Vec<f32> {
    let values = v.values_f32();
    let c = |a: usize, l: u32| {
        (brick[a] as i64 * inner as i64 - 1 + l as i64).clamp(0, v.dims[a] as i64 - 1) as usize
    };
    let mut out = Vec::new();
    for z in 0..inner + 2 {
        for y in 0..inner + 2 {
            for x in 0..inner + 2 {
                let (i, j, k) = (c(0, x), c(1, y), c(2, z));
                out.push(values[i + v.dims[0] as usize * (j + v.dims[1] as usize * k)]);
            }
        }
    }
    out
}

fn as_f32(v: &Voxels) -> Vec<f32> {
    hatchery_data::with_voxels!(v, x => x.iter().map(|&a| hatchery_data::voxels::Voxel::to_f32(a)).collect())
}

fn every_brick(dims: [u32; 3], inner: u32, level: u32) -> Vec<BrickId> {
    let [gx, gy, gz] = brick_grid(dims, inner);
    let mut ids = Vec::new();
    for z in 0..gz {
        for y in 0..gy {
            for x in 0..gx {
                ids.push(BrickId {
                    level,
                    brick: [x, y, z],
                });
            }
        }
    }
    ids
}

#[test]
fn bricks_from_memory_and_from_ome_zarr_chunks_equal_the_whole_grid() {
    let path = fixture("ome_v05.zarr");
    let whole = load_volume(&path).unwrap();
    let zarr = Multiscale::open(&path).unwrap();
    let memory = MemorySource::new(whole.clone(), 2).unwrap();
    assert_eq!(zarr.levels()[0].dims, whole.dims);
    // Inner 6 on a 20×16×12 grid: partial bricks at the far faces, aprons clamped at both ends.
    for inner in [6, 7, 30] {
        for id in every_brick(whole.dims, inner, 0) {
            let want = expected(&whole, id.brick, inner);
            let from_zarr = read_brick(&zarr, id, inner).unwrap();
            assert!(
                matches!(from_zarr, Voxels::U8(_)),
                "the stored type is kept"
            );
            assert_eq!(as_f32(&from_zarr), want, "OME-Zarr brick {id:?} of {inner}");
            assert_eq!(
                as_f32(&read_brick(&memory, id, inner).unwrap()),
                want,
                "memory {id:?}"
            );
        }
    }
    // The memory source's coarser levels are pyramid.rs's.
    let level1 = hatchery_data::pyramid::coarser_volume(&whole).unwrap();
    assert_eq!(memory.levels()[1].dims, level1.dims);
    for id in every_brick(level1.dims, 4, 1) {
        let got = as_f32(&read_brick(&memory, id, 4).unwrap());
        assert_eq!(got, expected(&level1, id.brick, 4), "level 1 {id:?}");
    }
    // Outside the grid: an error, never a panic.
    for bad in [
        BrickId {
            level: 0,
            brick: [4, 0, 0],
        },
        BrickId {
            level: 9,
            brick: [0, 0, 0],
        },
    ] {
        assert!(read_brick(&zarr, bad, 6).is_err());
        assert!(read_brick(&memory, bad, 6).is_err());
    }
    assert!(zarr.read_box(0, [18, 0, 0], [4, 1, 1]).is_err());
}

#[test]
fn the_host_cache_keeps_to_its_budget_and_evicts_the_least_recently_used() {
    let brick = |n: u8| Arc::new(Voxels::U8(vec![n; 1000]));
    let id = |n: u32| BrickId {
        level: 0,
        brick: [n, 0, 0],
    };
    let mut cache = BrickCache::new(3000);
    for n in 0..3 {
        assert!(cache.insert(id(n), brick(n as u8)).is_empty());
    }
    assert_eq!(cache.used(), 3000);
    assert!(cache.get(&id(0)).is_some(), "brick 0 is used again");
    assert_eq!(
        cache.insert(id(3), brick(3)),
        vec![id(1)],
        "the least recently used goes"
    );
    assert_eq!(cache.insert(id(4), brick(4)), vec![id(2)]);
    assert!(cache.get(&id(0)).is_some() && cache.get(&id(1)).is_none());
    assert_eq!((cache.len(), cache.used()), (3, 3000));
    // Replacing a brick does not count it twice; one larger than the budget is not kept.
    cache.insert(id(4), brick(9));
    assert_eq!(cache.used(), 3000);
    assert!(
        cache
            .insert(id(7), Arc::new(Voxels::U16(vec![0; 2000])))
            .is_empty()
    );
    assert!(cache.get(&id(7)).is_none());
    assert_eq!(cache.used(), 3000);
}

#[test]
fn worker_threads_read_each_requested_brick_once() {
    let path = fixture("ome_v04.zarr");
    let whole = load_volume(&path).unwrap();
    let source: Arc<dyn BrickSource> = Arc::new(Multiscale::open(&path).unwrap());
    let mut loader = BrickLoader::new(source, 5, 3);
    let ids = every_brick(whole.dims, 5, 0);
    for &id in ids.iter().chain(&ids) {
        loader.request(id);
    }
    let bad = BrickId {
        level: 0,
        brick: [0, 0, 99],
    };
    loader.request(bad);
    assert_eq!(
        loader.pending(),
        ids.len() + 1,
        "repeated requests are read once"
    );
    let mut done = loader.poll();
    done.extend(loader.wait_all());
    assert_eq!(done.len(), ids.len() + 1);
    assert_eq!(loader.pending(), 0);
    for (id, brick) in done {
        if id == bad {
            let err = brick.unwrap_err().to_string();
            assert!(err.contains("outside"), "{err}");
        } else {
            assert_eq!(
                as_f32(&brick.unwrap()),
                expected(&whole, id.brick, 5),
                "{id:?}"
            );
        }
    }
}

#[test]
fn bricks_of_a_memory_mapped_metaimage_equal_the_loaded_volume() {
    // sitk.mhd: int16 in a detached sitk.raw, as SimpleITK writes it.
    let path = fixture("sitk.mhd");
    let whole = load_volume(&path).unwrap();
    let source = hatchery_data::metaimage_file::metaimage_source(&path).unwrap();
    assert_eq!(source.levels()[0].dims, whole.dims);
    assert_eq!(source.levels()[0].geometry, whole.geometry);
    for id in every_brick(whole.dims, 7, 0) {
        let brick = read_brick(&source, id, 7).unwrap();
        assert!(matches!(brick, Voxels::I16(_)));
        assert_eq!(as_f32(&brick), expected(&whole, id.brick, 7), "{id:?}");
    }
    // A compressed file cannot be read a box at a time: said so, naming it.
    let err = hatchery_data::metaimage_file::metaimage_source(&fixture("sitk.mha"))
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("sitk.mha") && err.contains("compressed"),
        "{err}"
    );
    // A data file shorter than the header says.
    let dir = tempfile::tempdir().unwrap();
    let header = std::fs::read_to_string(&path).unwrap();
    std::fs::write(dir.path().join("short.mhd"), header).unwrap();
    std::fs::write(dir.path().join("sitk.raw"), [0u8; 100]).unwrap();
    let err = hatchery_data::metaimage_file::metaimage_source(&dir.path().join("short.mhd"))
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("too few"), "{err}");
}

#[test]
fn bricks_of_a_memory_mapped_nifti_equal_the_loaded_volume() {
    // NIfTI-1 little-endian and NIfTI-2 big-endian, as nibabel writes them.
    for name in ["nifti_ras.nii", "nifti2_big_endian.nii"] {
        let path = fixture(name);
        let whole = load_volume(&path).unwrap();
        let source = hatchery_data::nifti_file::nifti_source(&path).unwrap();
        assert_eq!(source.levels()[0].dims, whole.dims, "{name}");
        assert_eq!(source.levels()[0].geometry, whole.geometry, "{name}");
        for id in every_brick(whole.dims, 6, 0) {
            let brick = read_brick(&source, id, 6).unwrap();
            assert_eq!(
                as_f32(&brick),
                expected(&whole, id.brick, 6),
                "{name} {id:?}"
            );
        }
    }
    let err = hatchery_data::nifti_file::nifti_source(&fixture("nifti_las.nii.gz"))
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("nifti_las.nii.gz") && err.contains("gzip"),
        "{err}"
    );
}

#[test]
fn bricks_of_a_memory_mapped_nrrd_equal_the_loaded_volume() {
    let dir = tempfile::tempdir().unwrap();
    // A detached header over the MetaImage fixture's raw int16 data, 100 bytes in (byte skip),
    // and one whose data ends its file (byte skip -1).
    let raw = std::fs::read(fixture("sitk.raw")).unwrap();
    let mut padded = vec![0xAB; 100];
    padded.extend_from_slice(&raw);
    std::fs::write(dir.path().join("padded.raw"), &padded).unwrap();
    let header = |skip: i64| {
        format!(
            "NRRD0004\ntype: short\ndimension: 3\nspace: left-posterior-superior\nsizes: 20 16 12\n\
             space directions: (0.8,0,0) (0,0.8,0) (0,0,2.5)\nendian: little\nencoding: raw\n\
             space origin: (3,-7,-12)\nbyte skip: {skip}\ndata file: padded.raw\n"
        )
    };
    std::fs::write(dir.path().join("skip.nhdr"), header(100)).unwrap();
    std::fs::write(dir.path().join("end.nhdr"), header(-1)).unwrap();
    for path in [
        fixture("sitk.nrrd"),
        dir.path().join("skip.nhdr"),
        dir.path().join("end.nhdr"),
    ] {
        let whole = load_volume(&path).unwrap();
        let source = hatchery_data::nrrd_file::nrrd_source(&path).unwrap();
        assert_eq!(source.levels()[0].geometry, whole.geometry, "{path:?}");
        for id in every_brick(whole.dims, 6, 0) {
            let brick = read_brick(&source, id, 6).unwrap();
            assert_eq!(
                as_f32(&brick),
                expected(&whole, id.brick, 6),
                "{path:?} {id:?}"
            );
        }
    }
    let err = hatchery_data::nrrd_file::nrrd_source(&fixture("sitk_gzip.nhdr"))
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("sitk_gzip.nhdr") && err.contains("compressed"),
        "{err}"
    );
}

#[test]
fn open_picks_the_streaming_reader_by_format() {
    for (name, levels) in [
        ("ome_v05.zarr", 2),
        ("nifti_ras.nii", 1),
        ("sitk.nrrd", 1),
        ("sitk.mhd", 1),
    ] {
        let source = hatchery_data::stream_file::open_stream(&fixture(name)).unwrap();
        assert_eq!(source.levels().len(), levels, "{name}");
        assert_eq!(source.levels()[0].dims, [20, 16, 12], "{name}");
    }
    for name in ["nifti_las.nii.gz", "imagej_stack.tif"] {
        let err = hatchery_data::stream_file::open_stream(&fixture(name))
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains(name) && err.contains("hatchery convert"),
            "{err}"
        );
    }
}
