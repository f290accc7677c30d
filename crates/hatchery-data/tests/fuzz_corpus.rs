//! Replays the fuzz corpora and crash regressions of the file readers (`fuzz/corpus/<target>/`
//! and `fuzz/regressions/<target>/` at the repository root) through the fuzz targets' own
//! entry points: every input must load or fail with an error naming the file, never panic,
//! and never allocate more than [`ALLOCATION_LIMIT`] at once (as libFuzzer's malloc limit
//! guards the fuzz runs). `HATCHERY_FUZZ_SHOW=1` prints each file and its outcome. See
//! `docs/fuzzing.md`.

#[allow(dead_code)]
#[path = "../../../fuzz/src/data_targets.rs"]
mod data_targets;

use std::alloc::{GlobalAlloc, Layout, System};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use data_targets::{Scratch, TARGETS};

/// The largest single allocation one input may make. The corpus files are small, so no reader
/// needs much for them; a reader that allocates what a header promises before checking that
/// the file holds it asks for gigabytes (the `oom-*` regressions).
const ALLOCATION_LIMIT: usize = 256 << 20;

/// The largest allocation asked for since the last reset.
static LARGEST: AtomicUsize = AtomicUsize::new(0);

/// The system allocator, refusing (null, so `try_reserve` fails and other allocations abort)
/// and recording allocations above the limit.
struct Guard;

// SAFETY: forwards to `System` unchanged, or returns null, which `GlobalAlloc` allows.
unsafe impl GlobalAlloc for Guard {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if admit(layout.size()) {
            unsafe { System.alloc(layout) }
        } else {
            std::ptr::null_mut()
        }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if admit(layout.size()) {
            unsafe { System.alloc_zeroed(layout) }
        } else {
            std::ptr::null_mut()
        }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if admit(new_size) {
            unsafe { System.realloc(ptr, layout, new_size) }
        } else {
            std::ptr::null_mut()
        }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

fn admit(size: usize) -> bool {
    LARGEST.fetch_max(size, Ordering::Relaxed);
    size <= ALLOCATION_LIMIT
}

#[global_allocator]
static GUARD: Guard = Guard;

fn files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .map(|e| e.expect("cannot list a corpus folder").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

#[test]
fn fuzz_corpus_and_regressions_load_or_fail_cleanly() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let fuzz = fuzz.canonicalize().unwrap_or(fuzz);
    let show = std::env::var_os("HATCHERY_FUZZ_SHOW").is_some();
    let scratch = Scratch::new();
    let mut failures = Vec::new();
    for (name, target) in TARGETS {
        let corpus = files(&fuzz.join("corpus").join(name));
        assert!(
            !corpus.is_empty(),
            "no corpus for fuzz target `{name}` in {}",
            fuzz.display()
        );
        let regressions = files(&fuzz.join("regressions").join(name));
        for path in corpus.iter().chain(&regressions) {
            let data = std::fs::read(path).expect("cannot read a corpus file");
            if show {
                // Before running it: an allocation refused outside `try_reserve` aborts.
                print!("{}: ", path.display());
            }
            LARGEST.store(0, Ordering::Relaxed);
            let outcome = catch_unwind(AssertUnwindSafe(|| target(&scratch, &data)));
            let largest = LARGEST.load(Ordering::Relaxed);
            match outcome {
                Ok(_) if largest > ALLOCATION_LIMIT => failures.push(format!(
                    "{}: allocates {largest} bytes at once",
                    path.display()
                )),
                Ok(outcome) if show => println!("{outcome:?} (largest allocation {largest})"),
                Ok(_) => {}
                Err(_) => failures.push(format!("{}: panics", path.display())),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "these inputs fail (reproduce with `cargo fuzz run <target> <file>`):\n{}",
        failures.join("\n")
    );
}
